//! Scores computed from beam trees.
