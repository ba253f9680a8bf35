//! The `.gem` writer: the cut's tiers ([`crate::design::tiers()`]) as facet records on the
//! design's gear, each plane computed from its facet's angle, index and distance on fixed
//! grids (see the module docs), the vertices of the solid those planes make, and the trailer.

use super::{snap_angle, snap_distance, snap_index, CONSTANT, END_OF_FACETS, TEXT_SLOTS};
use crate::cut::record::{GemcadRecord, DIAMOND_RI};
use crate::cut::Cut;
use crate::design::{tiers, token, Gear};
use crate::error::{Error, Result};
use crate::geometry::{facet_normal, DVec3, FacetPlane, Polyhedron};
use crate::io::asc::decode::encode_cp1252;
use crate::io::asc::{derived_name, generated_tier};
use std::collections::HashMap;

/// The index written for a cut without one (a generated cut): diamond's, the material
/// facetlab traces such a cut in.
pub const DEFAULT_RI: f64 = 2.42;

/// One facet as written: its line (from 0), its plane in the file's units (facetlab's frame)
/// and its label.
struct Facet {
    line: usize,
    plane: FacetPlane,
    label: String,
}

/// Write `cut` as a GemCad `.gem` design on a gear of `gear` teeth; `0` means the design's own
/// gear (and offset) when the cut came from a design file ([`Cut::record`]), else 96 — as
/// [`crate::io::asc::write`] does. See the module docs for what is written.
///
/// Errors: a gear that is not a whole tooth count (a `.gem` keeps an `i32`), or planes that no
/// longer make the solid once put on the file's grids (never seen: they move by less than
/// 1e-11 of the stone).
pub fn write(cut: &Cut, gear: u32) -> Result<Vec<u8>> {
    write_for(cut, gear, DIAMOND_RI)
}

/// [`write()`], a generated cut written for the index `ri` (its material's n_D) with the record
/// [`GemcadRecord::for_file`] gives it, as [`crate::io::asc::write_for`] does; a design keeps
/// its own record.
pub fn write_for(cut: &Cut, gear: u32, ri: f64) -> Result<Vec<u8>> {
    let record = GemcadRecord::for_file(cut, gear, ri);
    let gear = Gear::for_record(&record, gear);
    let teeth = gear.teeth;
    if !(teeth.fract() == 0.0 && teeth != 0.0 && teeth.abs() <= f64::from(i32::MAX)) {
        return Err(Error::invalid(
            format!("{}: gear", cut.name),
            format!("{teeth} teeth cannot be written to a .gem, which keeps a whole tooth count; write a .asc instead"),
        ));
    }
    let unit = if record.scale.is_finite() && record.scale > 0.0 {
        record.scale
    } else {
        1.0
    };
    let mut facets: Vec<Facet> = Vec::new();
    let planes = cut.solid.facet_planes();
    let by_name: HashMap<&str, &FacetPlane> = planes.iter().map(|p| (p.name.as_str(), p)).collect();
    for (k, t) in tiers(cut, gear, unit).iter().enumerate() {
        let generated = t.name.is_empty() || {
            let crown = !t.angle.is_sign_negative();
            t.name == generated_tier(snap_angle(t.angle).abs(), crown != (t.depth < 0.0))
        };
        let instructions = t
            .facets
            .iter()
            .find_map(|f| record.instructions.get(&f.name))
            .map(|s| s.replace('\t', " "))
            .unwrap_or_default();
        for (j, f) in t.facets.iter().enumerate() {
            let Some(own) = by_name.get(f.name.as_str()) else {
                continue;
            };
            // The facet's own angle and distance (its line's to GemCad's precision), as the
            // `.asc` reader makes a plane of them: a negative angle on the pavilion, a culet
            // `0` with a negative distance.
            let n0 = own.plane.normal;
            let tilt = n0.x.hypot(n0.y).atan2(n0.z.abs()).to_degrees();
            let culet = n0.x.hypot(n0.y) <= 1e-12 && n0.z <= 1e-12;
            let angle = snap_angle(if n0.z > 1e-12 || culet { tilt } else { -tilt });
            let depth = snap_distance(own.plane.offset * unit * if culet { -1.0 } else { 1.0 });
            let crown = !angle.is_sign_negative();
            let index = snap_index(f.index);
            let az = -90.0 + 360.0 * (index - gear.offset) / teeth;
            let n = facet_normal(angle.abs(), az, crown);
            let name = if generated {
                String::new()
            } else if j == 0 {
                t.name.clone()
            } else if !derived_name(&f.name, &t.name) {
                token(&f.name)
            } else {
                String::new()
            };
            facets.push(Facet {
                line: k,
                plane: FacetPlane::new(
                    if depth < 0.0 { -n } else { n },
                    depth.abs(),
                    &f.name,
                    &t.name,
                ),
                label: format!("{name}\t{instructions}"),
            });
        }
    }
    let polygons = polygons(cut, &facets)?;
    let mut out = Vec::with_capacity(64 + facets.len() * 200);
    for (f, poly) in facets.iter().zip(&polygons) {
        // p · x = 1 on the facet, in GemCad's frame (y turned over).
        let p = f.plane.plane.normal / f.plane.plane.offset;
        for v in [p.x, -p.y, p.z] {
            out.extend_from_slice(&v.to_le_bytes());
        }
        let line = i32::try_from(f.line + 1).unwrap_or(i32::MAX);
        out.extend_from_slice(&line.to_le_bytes());
        string(&mut out, &f.label);
        for v in poly {
            out.extend_from_slice(&1i32.to_le_bytes());
            for c in [v.x, -v.y, v.z] {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        out.extend_from_slice(&0i32.to_le_bytes());
    }
    out.extend_from_slice(&END_OF_FACETS.to_le_bytes());
    let symmetry = i32::try_from(record.symmetry.max(1)).unwrap_or(i32::MAX);
    out.extend_from_slice(&symmetry.to_le_bytes());
    out.extend_from_slice(&i32::from(record.mirror).to_le_bytes());
    // Whole and within i32 (checked above).
    out.extend_from_slice(&(teeth as i32).to_le_bytes());
    out.extend_from_slice(&record.ri.unwrap_or(DEFAULT_RI).to_le_bytes());
    out.extend_from_slice(&CONSTANT.to_le_bytes());
    out.extend_from_slice(&gear.offset.to_le_bytes());
    for s in slots(&record.title).iter().chain(&slots(&record.footnotes)) {
        string(&mut out, s);
    }
    Ok(out)
}

/// Each facet's polygon in the file's units and facetlab's frame, counter-clockwise seen from
/// outside once turned into GemCad's frame: the solid of the written planes (not of the cut's
/// own, so that the bytes depend only on what is written).
fn polygons(cut: &Cut, facets: &[Facet]) -> Result<Vec<Vec<DVec3>>> {
    // Built at unit size (the clipping box is fixed), scaled back.
    let big = facets
        .iter()
        .map(|f| f.plane.plane.offset.abs())
        .fold(0.0, f64::max);
    let big = if big.is_finite() && big > 0.0 {
        big
    } else {
        1.0
    };
    let planes: Vec<FacetPlane> = facets
        .iter()
        .map(|f| {
            let mut p = f.plane.clone();
            p.plane.offset /= big;
            p
        })
        .collect();
    let solid = Polyhedron::from_planes(&planes).map_err(|e| {
        e.context(&format!(
            "{}: its planes on the .gem's grids do not make its solid",
            cut.name
        ))
    })?;
    Ok((0..solid.facets().len())
        .map(|i| {
            // The y turn reverses the turning sense: reverse the order to keep it.
            solid
                .facet_polygon(i)
                .into_iter()
                .rev()
                .map(|v| v * big)
                .collect()
        })
        .collect())
}

/// Title or footnote lines in the trailer's four slots: empty ones after the last line, the
/// lines past the fourth joined to it.
fn slots(lines: &[String]) -> Vec<String> {
    let mut out: Vec<String> = lines.iter().take(TEXT_SLOTS - 1).cloned().collect();
    if lines.len() >= TEXT_SLOTS {
        out.push(lines[TEXT_SLOTS - 1..].join(" "));
    }
    out.resize(TEXT_SLOTS, String::new());
    out
}

/// A length-prefixed Windows-1252 string: one length byte below 255, else MFC's `0xFF` and a
/// `u16` (below 0xFFFE), else `0xFF 0xFFFF` and a `u32`.
fn string(out: &mut Vec<u8>, s: &str) {
    let bytes = encode_cp1252(s);
    let n = bytes.len();
    if n < 0xFF {
        out.push(n as u8);
    } else if n < 0xFFFE {
        out.push(0xFF);
        out.extend_from_slice(&(n as u16).to_le_bytes());
    } else {
        out.push(0xFF);
        out.extend_from_slice(&0xFFFFu16.to_le_bytes());
        out.extend_from_slice(&u32::try_from(n).unwrap_or(u32::MAX).to_le_bytes());
    }
    out.extend_from_slice(&bytes);
}
