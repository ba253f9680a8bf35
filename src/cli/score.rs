//! `facetlab score`.
