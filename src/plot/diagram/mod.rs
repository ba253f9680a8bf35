//! A cutter's facet diagram as SVG, in the manner of a GemCad printout: a plot of the cut.
//!
//! One page with four parts, all views orthographic and drawn at one scale:
//! - face up (crown, seen from above): every upward facet outlined and tinted by tier, the
//!   outline drawn heavier, one label per tier;
//! - face down (pavilion, seen from below, so left and right are mirrored);
//! - side view (seen from the front, −y): the facets facing the viewer, the silhouette, the
//!   girdle plane, crown and pavilion angles, and dimension lines for the table width, crown
//!   height, pavilion depth and total depth;
//! - a text block with the proportions, each tier's angle and facet count, and the cutting
//!   instructions ([`crate::io::asc::cutting_instructions`]: each tier in cutting order,
//!   pavilion first, with its angle at 0.01° and its indices on the design's gear).
//!
//! Above them the design's heading as its GemCad record gives it
//! ([`GemcadRecord::for_file`](crate::cut::GemcadRecord::for_file)): its title, the further
//! title lines (author, credits), and a line with its index (and the material of that index),
//! gear, symmetry and facet count; below them its notes. The page is as wide as its text needs
//! (text measured in DejaVu Sans, the page's first font), so every index of the cutting order
//! is on the page.
//!
//! The SVG is written by hand (no drawing library) and every name is escaped, so the output is
//! well-formed XML.
//!
//! The rooms: `page.rs` lays out the page ([`diagram`]); `svg.rs` holds the SVG primitives
//! (escaping, number formats, a view's map to page pixels, text and lines); `views.rs` draws
//! one view's facets, outline and tier labels; `side.rs` the side view's dimension lines and
//! angles; `text_block.rs` the proportions, tiers and cutting instructions.

mod page;
mod side;
mod svg;
mod text_block;
mod views;

pub use page::diagram;
