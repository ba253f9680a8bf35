//! Charts and pictures (plotters).
