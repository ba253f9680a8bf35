//! `facetlab trace`.
