//! GemCad `.gem` designs: the binary file GemCad writes by default, read into the same
//! [`AscDesign`] as a `.asc` (so every reader of designs reads both), and written from a
//! [`Cut`] with what the `.asc` writer keeps.
//!
//! # The format
//!
//! GemCad does not publish it; the layout here is the public decoding (an MIT-licensed reader's
//! record order, checked on hundreds of files) and GemCad's own `.asc` twins of four designs.
//! Little-endian, no magic number:
//!
//! - **facet records**, one per facet: `f64 px, py, pz`, the plane vector `p` with `p · x = 1`
//!   on the facet (outward unit normal `p/|p|`, distance `1/|p|` from the origin, in the
//!   design's units); `i32` the tier number (the facet's line of the `.asc`, from 1); a
//!   string `NAME\tINSTRUCTIONS` (the facet's own name, empty on most, and its line's cutting
//!   instructions, repeated on every facet of the line); then the facet's vertices, each
//!   `i32 1` followed by `f64 x, y, z`, closed by `i32 0`;
//! - `f64 -99999.0`, which ends the facets;
//! - the **trailer**: `i32` symmetry folds, `i32` mirror (0 or 1), `i32` gear (its tooth count;
//!   negative: the indices run clockwise), `f64` refractive index, `u32` 0x7FFF (not read), `f64`
//!   gear offset (an index), then four title strings and four footnote strings (empty ones
//!   where the design has fewer);
//! - optionally the string `preform` and a nested design (GemCad's preform), which is skipped.
//!
//! A string is a length and that many Windows-1252 bytes. The length is one byte; a longer
//! string (none of GemCad's sample files has one) is taken to follow MFC's `CArchive`
//! convention, which GemCad, an MFC program, writes with: `0xFF` then a `u16` length, and
//! `0xFF 0xFFFF` then a `u32` length.
//!
//! **The planes are authoritative.** The vertices are what GemCad drew (some files' are
//! scaled); the reader skips them, and the writer writes the vertices of the solid its planes
//! make. **Frame**: GemCad's index `i` on a gear of `g` teeth with offset `o` is the azimuth
//! `90° − 360° · (i − o) / g` in the file's coordinates, the mirror image (`y → −y`) of the
//! azimuth `−90° + 360° · (i − o) / g` facetlab gives a `.asc` index ([`crate::io::asc`]); the
//! reader and the writer turn the file's `y` over, so a design read from its `.gem` and from
//! its `.asc` is one solid (checked on GemCad's own twins, a chiral design among them).
//!
//! # Reading
//!
//! Facets of one tier number make one line: its angle, its distance and each facet's index
//! on the design's gear are derived from the planes (an index off the gear is fractional),
//! its first facet name names the tier, its instructions are the first non-empty ones of its
//! facets. Names and repeats are settled as for a `.asc` ([`crate::io::asc`]). The index,
//! gear and offset are checked by the same rules as a `.asc`'s. A file cut short, a length
//! that runs past the end, a vertex marker other than 0 or 1, a plane vector that is not a
//! plane, a mirror flag other than 0 or 1, or bytes after the footnotes that are not a
//! preform are one-line errors naming the file and the byte offset (`design.gem: byte 1234:
//! …`); every length is checked against the bytes left before anything is allocated.
//!
//! # Writing
//!
//! [`write()`] writes the tiers of [`crate::design::tiers()`] (as the `.asc` writer does) on the
//! design's gear, in its file's units, with its index, titles, footnotes, symmetry, mirror,
//! gear, offset and instructions. Each facet's plane is computed from its angle, its index and
//! its distance as the `.asc` reader computes a plane, with the angle on a grid of 1e-10°,
//! the index on a grid of 1e-10 tooth and the distance to 12 significant digits: a design read from a `.asc` is written
//! with the very planes its `.asc` gives (its facets' angles and distances are its lines'),
//! any other cut with its own planes to about 1e-12 of its size (a `.gem` keeps each facet's
//! plane, where a `.asc` line writes one angle and distance for its facets), and a `.gem`
//! written by facetlab, read and written again, comes back byte for byte. A generated cut (no GemCad record) is written with the
//! record the `.asc` writer gives it ([`crate::cut::GemcadRecord::generated`]: gear 96, its name
//! as the title, its own symmetry, the index of diamond or of the material [`write_for`] names);
//! a design read without an index is written with 2.42 (GemCad needs one). More than four
//! titles or footnotes are joined into the fourth.
//!
//! ```
//! use facetlab::io::{gem, load_cut};
//!
//! let cut = load_cut("tolkowsky").unwrap();
//! let bytes = gem::write(&cut, 0).unwrap();
//! let back = gem::parse(&bytes, "t.gem").unwrap().to_cut("t").unwrap();
//! assert_eq!(back.solid.facets().len(), cut.solid.facets().len());
//! // Written again, the same bytes.
//! assert_eq!(gem::write(&back, 0).unwrap(), bytes);
//! // A file cut short is an error naming the byte where it ends.
//! let e = gem::parse(&bytes[..100], "t.gem").unwrap_err().to_string();
//! assert!(e.starts_with("t.gem: byte "), "{e}");
//! ```
//!
//! Files: `read.rs` (the reader, [`parse`] and [`read()`]), `write.rs` (the writer).
//!
//! [`AscDesign`]: crate::io::asc::AscDesign
//! [`Cut`]: crate::cut::Cut

mod read;
#[cfg(test)]
mod tests;
mod write;

pub use read::{parse, read};
pub use write::{write, write_for};

/// The `f64` that ends the facet records.
pub const END_OF_FACETS: f64 = -99999.0;

/// The `u32` GemCad writes between the index and the gear offset.
const CONSTANT: u32 = 0x7FFF;

/// Title and footnote slots of the trailer (each).
const TEXT_SLOTS: usize = 4;

/// A line's angle on the grid both the reader and the writer put it on (degrees, 1e-10).
fn snap_angle(a: f64) -> f64 {
    let s = (a * 1e10).round() / 1e10;
    if s == 0.0 {
        0.0f64.copysign(a)
    } else {
        s
    }
}

/// An index on a grid of 1e-10 tooth.
fn snap_index(i: f64) -> f64 {
    (i * 1e10).round() / 1e10
}

/// A distance to 12 significant digits.
fn snap_distance(d: f64) -> f64 {
    format!("{d:.11e}").parse().unwrap_or(d)
}
