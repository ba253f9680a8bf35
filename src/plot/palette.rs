//! Every colour the plot floor hands out: the charts' palette ([`TAB10`], and [`SERIES`] for the
//! cuts compared in one chart) and the grounds the stone pictures are laid on, each named for
//! where it is used ([`PICTURE_GROUND`] on sheets and in reports, [`CAPTION_GROUND`] under the
//! captions, [`STAGE_GROUND`] on the workbench's dark stage).

use plotters::style::RGBColor;

/// Tableau's ten colours: the one palette every chart takes its colours from.
pub const TAB10: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Colours of the cuts compared in one chart, in order: blue, red, green, purple, … (red second,
/// so two cuts never look alike to a red–green colour-blind reader).
pub const SERIES: [RGBColor; 8] = [
    TAB10[0], TAB10[3], TAB10[2], TAB10[4], TAB10[1], TAB10[5], TAB10[6], TAB10[9],
];

/// Ground around the stones in the pictures written to files, on render sheets
/// ([`compose`](super::render::compose)) and report pages (sRGB-encoded, 0–1): a mid grey, so
/// that black (ASET leakage, the port, a dark pavilion) and white (IdealScope leakage) both
/// stand out from it.
pub const PICTURE_GROUND: [f64; 3] = [0.4, 0.4, 0.4];

/// Ground of a sheet's caption and legend strip (8-bit sRGB): a light grey for dark text.
pub const CAPTION_GROUND: [u8; 3] = [236, 236, 236];

/// Ground of the pictures on the workbench's page (`facetlab serve`; sRGB-encoded, 0–1): the
/// page's dark stage.
pub const STAGE_GROUND: [f64; 3] = [0.075, 0.082, 0.094];
