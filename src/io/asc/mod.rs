//! GemCad `.asc` designs: read them into a [`Cut`], write a [`Cut`] as one, and print its
//! cutting instructions.
//!
//! # The format
//!
//! A line-based text file. Each line starts with a keyword letter:
//!
//! - `GemCad 5.0`: the header (ignored);
//! - `g 96 0.0`: the index gear (teeth per turn; negative = indices run clockwise) and the gear
//!   offset, an *index* (see below);
//! - `y 8 y`: symmetry (fold count, mirror `y`/`n`), kept as metadata only: every facet is
//!   listed explicitly in the file;
//! - `I 1.54`: refractive index;
//! - `H text`: header/title lines; `F text`: footnotes;
//! - `a ANGLE DISTANCE INDEX [INDEX …] [n NAME] [G INSTRUCTIONS…]`: facets with one angle and
//!   distance, one facet per index. `n NAME` names the facet of the index just before it (the
//!   first name of the line also names the tier); the token right after `n` is always a name,
//!   even `G`. `G` starts the cutting instructions, which run to the end of the line.
//!
//! # How a facet line becomes planes
//!
//! - ANGLE is the facet's tilt from the girdle plane in degrees: positive (and `0`) = crown,
//!   negative (and `-0`) = pavilion, ±90 = girdle. Allowed range −90…90.
//! - INDEX `i` on a gear of `g` teeth with offset `o` has the azimuth (our convention: degrees
//!   from +x toward +y, counter-clockwise seen from above)
//!   `azimuth = −90° + 360° · (i − o) / g`.
//!   This follows the GemCad manual: the offset is the index drawn at the bottom (6 o'clock) of
//!   the Top View, and with a positive tooth count the indices increase counter-clockwise in
//!   the Top View (seen from above the crown); a negative tooth count runs clockwise. So for
//!   `g 96 0`, index 96 faces −y, 24 faces +x, 48 faces +y and 72 faces −x, and the design is
//!   not mirrored. (The opposite choice would mirror chiral designs in y; symmetric designs
//!   are the same either way.)
//! - DISTANCE is the plane's distance from the origin (the stone's axis point in the girdle
//!   plane). GemCad keeps that point inside the stone, so a *negative* distance puts the plane
//!   on the other side of the origin, facing the other way: `a 0 -0.1 96` is a culet 0.1
//!   below the girdle plane, the same facet as `a -0 0.1 96`.
//! - The facet's outward normal is [`facet_normal`]`(|angle|, azimuth, crown)`, its offset the
//!   distance.
//! - A facet repeating an earlier facet's plane exactly (real files do this) is dropped: it
//!   cuts nothing.
//!
//! Names: a facet is called after its own `n` name, else the first name on its line, else a
//! generated tier name (`table`, `culet`, `girdle`, `crown-34.00`, `pavilion-42.50`). Names
//! shared by several facets get `-1`, `-2`, … so that every facet name in a cut is unique
//! (`A-1` … `A-16`). The tier is the line's first name, or the generated name.
//!
//! # Units
//!
//! [`AscDesign::planes`] are in the file's units. [`AscDesign::to_cut`] scales the solid about
//! the origin so that its width W is 1, like every preset and every other import (the unit
//! convention of [`crate::cut::units`]: W is the outline's smaller extent along x and y, the
//! diameter of a round), and every plane offset is scaled with it; the factor is kept in the design's record
//! ([`GemcadRecord::scale`]), with the index, titles, notes, gear, symmetry and instructions,
//! on [`Cut::record`]. [`write()`] writes a design's distances back in its file's units, a
//! generated cut's in its own.
//!
//! # Tolerated
//!
//! Index lists wrapped onto following lines (a line starting with a number, `n` or `G`
//! continues the open `a` line), fractional and negative indices, negative gears, keywords
//! glued to their number (`g96`, `a-42.5`), a UTF-8 BOM, CR, LF or CRLF line ends, blank and
//! unknown lines (skipped). Bytes that are not UTF-8 are read as Windows-1252 (0x80–0x9F) or
//! Latin-1. A malformed `a`, `g`, `y` or `I` line is an error naming the file and line.
//!
//! # Files
//!
//! - `check.rs`: the rules for a design's index, gear and offset, shared with the `.gem`
//!   reader ([`crate::io::gem`]);
//! - `decode.rs`: bytes to lines (UTF-8, Windows-1252, Latin-1; line ends), keywords and
//!   continuation lines;
//! - `read.rs`: the reader: [`parse`], [`read()`], [`AscDesign`] and its [`AscTier`]s, and the
//!   solid scaled to W = 1;
//! - `write.rs`: the writer, [`write()`]: the cut's tiers ([`crate::design::tiers()`]) as `a`
//!   lines with the design's record;
//! - `instructions.rs`: the cutting instructions (the `G` lines with each tier's angle and
//!   indices), [`cutting_instructions`].
//!
//! [`Cut`]: crate::cut::Cut
//! [`Cut::record`]: crate::cut::Cut::record
//! [`facet_normal`]: crate::geometry::facet_normal
//! [`GemcadRecord::scale`]: crate::cut::GemcadRecord::scale

pub(in crate::io) mod check;
pub(in crate::io) mod decode;
mod instructions;
mod read;
mod write;

#[cfg(test)]
mod measure_tests;

pub use check::{MAX_GEAR, RI_ABOVE, RI_MAX};
pub use instructions::{cutting_instructions, CuttingInstructions, CuttingStep};
pub(in crate::io) use read::{assemble, generated_tier, read_design, RawFacet};
pub use read::{parse, read, AscDesign, AscTier};
pub(in crate::io) use write::derived_name;
pub use write::{check, write, write_for};

/// The index gear used when a file has no `g` line, and by [`write()`] for a cut without a
/// GemCad record.
pub const DEFAULT_GEAR: u32 = 96;
