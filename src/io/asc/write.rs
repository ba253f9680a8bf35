//! The GemCad writer: a cut's tiers ([`crate::design::tiers()`]) as `a` lines, on the design's
//! gear and in its file's units, with the design's record (index, titles, notes, symmetry,
//! instructions).

use super::read::generated_tier;
use crate::cut::record::DIAMOND_RI;
use crate::cut::{Cut, GemcadRecord};
use crate::design::{fixed, tiers, token, Gear, Tier, ANGLE_DECIMALS, DEPTH_DECIMALS};
use std::fmt::Write as _;

/// A number with at most `max` decimals: the fewest (at least `min`) that come within `tol`
/// of `x`, else `max`. `-0` is written `0`.
pub(super) fn fmt_short(x: f64, min: usize, max: usize, tol: f64) -> String {
    let x = if x == 0.0 { 0.0 } else { x };
    for d in min..max {
        let t = fixed(x, d);
        if t.parse::<f64>().is_ok_and(|v| (v - x).abs() <= tol) {
            return t;
        }
    }
    fixed(x, max)
}

/// A gear index: a whole number when the azimuth is on the gear (within 1e-6 of a tooth),
/// else the fewest decimals (up to 10) that give the azimuth within 1e-9 of a tooth.
fn fmt_index(i: f64) -> String {
    let r = i.round();
    if (i - r).abs() < 1e-6 {
        format!("{r:.0}")
    } else {
        fmt_short(i, 1, 10, 1e-9)
    }
}

/// The tier name the reader generates for an unnamed line (see [`generated_tier`]), for the
/// angle and distance as written.
pub(super) fn reader_tier(angle: &str, dist: &str) -> String {
    let a: f64 = angle.parse().unwrap_or(0.0);
    let d: f64 = dist.parse().unwrap_or(0.0);
    let crown = !a.is_sign_negative() && !angle.starts_with('-');
    generated_tier(a.abs(), crown != (d < 0.0))
}

/// Whether `name` is what the reader makes of an unnamed facet of tier `tier` (`tier` or
/// `tier-K`).
pub(in crate::io) fn derived_name(name: &str, tier: &str) -> bool {
    name == tier
        || name
            .strip_prefix(tier)
            .and_then(|r| r.strip_prefix('-'))
            .is_some_and(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()))
}

/// One `a` line as written: tier, angle and distance, and the facets' (index text, facet
/// name).
pub(super) struct Line {
    pub(super) tier: String,
    pub(super) angle: String,
    pub(super) dist: String,
    pub(super) facets: Vec<(String, String)>,
}

impl Line {
    /// A tier as its `a` line writes it.
    fn of(t: &Tier) -> Line {
        Line {
            tier: t.name.clone(),
            angle: fixed(t.angle, ANGLE_DECIMALS),
            dist: fixed(t.depth, DEPTH_DECIMALS),
            facets: t
                .facets
                .iter()
                .map(|f| (fmt_index(f.index), f.name.clone()))
                .collect(),
        }
    }
}

/// The GemCad record to write with ([`GemcadRecord::for_file`]: a generated cut's for the
/// index `ri`), the gear, and the `a` lines: the cut's tiers on the gear, distances in the
/// record's file units.
pub(super) fn gear_lines(cut: &Cut, gear: u32, ri: f64) -> (GemcadRecord, Gear, Vec<Line>) {
    let record = GemcadRecord::for_file(cut, gear, ri);
    let gear = Gear::for_record(&record, gear);
    let unit = if record.scale.is_finite() && record.scale > 0.0 {
        record.scale
    } else {
        1.0
    };
    let lines = tiers(cut, gear, unit).iter().map(Line::of).collect();
    (record, gear, lines)
}

/// Write `cut` as a GemCad `.asc` design on a gear of `gear` teeth; `0` means the design's
/// own gear (and offset) when the cut came from a design file ([`Cut::record`]), else 96. A
/// generated cut is written for diamond ([`write_for`] names another index).
///
/// A design read from a file keeps its record: `I` (index), `H` (titles), `F` (footnotes),
/// `y` (symmetry and mirror), `g` (gear and offset) and each line's `G` instructions, and its
/// distances are written back in the file's own units ([`GemcadRecord::scale`]). A generated
/// cut is written with the record of [`GemcadRecord::generated`]: `g 96 0.0`, its real
/// symmetry (`y 8 y` for a round brilliant), `I` its material's index, its name as the title,
/// distances in girdle widths (W = 1).
///
/// Facets are grouped into one `a` line per (tier, angle, distance) as written, in order of
/// first appearance (the tiers of [`crate::design::tiers()`]); a tier's angle is written once,
/// with 6 decimals as GemCad does (pavilion negative, girdle −90; a culet GemCad's way, as
/// angle 0 with a negative distance), distances with 8. Each azimuth becomes an index (`i = offset + g · (azimuth + 90°) /
/// 360°`, index 0 written as the tooth count): a whole number when the azimuth is on the gear,
/// else the fewest decimals that keep it (a fractional index, as GemCad allows). The tier is
/// written as `n TIER` after the first index unless it is the name the reader would generate
/// anyway (`table`, `girdle`, `crown-34.00` …); a facet with a name of its own (not `TIER` or
/// `TIER-K`) gets `n NAME` after its index. Planes through or behind the origin cannot be
/// expressed in GemCad's convention and do not read back the same ([`check`] refuses them).
///
/// A round trip through the text:
///
/// ```
/// use facetlab::io::{asc, load_cut};
///
/// let cut = load_cut("gia-reference").unwrap();
/// let text = asc::write(&cut, 96);
/// assert!(text.starts_with("GemCad"));
/// let back = asc::parse(text.as_bytes(), "gia.asc").unwrap().to_cut("gia").unwrap();
/// assert_eq!(back.solid.facets().len(), cut.solid.facets().len());
/// assert!((back.proportions().crown_angle - 34.0).abs() < 1e-6);
/// ```
pub fn write(cut: &Cut, gear: u32) -> String {
    write_for(cut, gear, DIAMOND_RI)
}

/// [`write()`], a generated cut written for the index `ri` (its material's n_D: its `I` line);
/// a design keeps its own record.
pub fn write_for(cut: &Cut, gear: u32, ri: f64) -> String {
    let (record, gear, lines) = gear_lines(cut, gear, ri);
    let mut out = String::new();
    let _ = writeln!(out, "GemCad 5.0");
    let _ = writeln!(
        out,
        "g {} {}",
        fmt_short(gear.teeth, 0, 6, 1e-9),
        fmt_short(gear.offset, 1, 6, 1e-9)
    );
    let _ = writeln!(
        out,
        "y {} {}",
        record.symmetry.max(1),
        if record.mirror { "y" } else { "n" }
    );
    if let Some(ri) = record.ri {
        let _ = writeln!(out, "I {}", fmt_short(ri, 2, 6, 1e-9));
    }
    for t in &record.title {
        let _ = writeln!(out, "H {t}");
    }
    for l in &lines {
        let _ = write!(out, "a {} {}", l.angle, l.dist);
        let generated = l.tier.is_empty() || l.tier == reader_tier(&l.angle, &l.dist);
        for (k, (index, name)) in l.facets.iter().enumerate() {
            let _ = write!(out, " {index}");
            if generated {
                continue;
            }
            if k == 0 {
                let _ = write!(out, " n {}", l.tier);
            } else if !derived_name(name, &l.tier) {
                let _ = write!(out, " n {}", token(name));
            }
        }
        if let Some(text) = l
            .facets
            .iter()
            .find_map(|(_, name)| record.instructions.get(name))
        {
            let _ = write!(out, " G {text}");
        }
        out.push('\n');
    }
    for f in &record.footnotes {
        let _ = writeln!(out, "F {f}");
    }
    out
}

/// Refuse a cut a `.asc` cannot hold, before [`write()`]: GemCad gives each facet its distance
/// from the origin (the stone's axis in its girdle plane) and tells a culet from a table by
/// that distance's sign, so every facet plane must pass outside the origin, at a distance
/// the file's 8 decimals keep (a millionth of the farthest facet's). A mesh whose lowest
/// facet lies in its girdle plane was written as a `.asc` that read back unbounded.
pub fn check(cut: &Cut) -> crate::error::Result<()> {
    let planes = cut.solid.facet_planes();
    let far = planes
        .iter()
        .map(|p| p.plane.offset.abs())
        .fold(0.0, f64::max);
    match planes.iter().find(|p| p.plane.offset.partial_cmp(&(1e-6 * far)) != Some(std::cmp::Ordering::Greater)) {
        None => Ok(()),
        Some(p) => Err(crate::error::Error::invalid(
            "output",
            format!(
                "facet {} of {} passes through or behind the origin in the girdle plane, which a GemCad .asc cannot hold (.gem, .toml, .obj and .stl can)",
                p.name, cut.name
            ),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cut::units::outline_size;
    use crate::geometry::FacetPlane;
    use crate::io::asc::{parse, AscDesign};
    use crate::testkit::asc::{messy, same_planes, MINI, STAR80};
    use std::collections::{BTreeMap, HashSet};

    fn round_trip(gear: u32) {
        let cut = Cut::from_family("r", "round-brilliant", &BTreeMap::new()).unwrap();
        let text = write(&cut, gear);
        let back = parse(text.as_bytes(), "r.asc")
            .unwrap()
            .to_cut("r")
            .unwrap();
        let s = 1.0 / outline_size(cut.solid.vertices()).1;
        let want: Vec<FacetPlane> = cut
            .solid
            .facet_planes()
            .into_iter()
            .map(|mut p| {
                p.plane.offset *= s;
                p
            })
            .collect();
        same_planes(&want, &back.solid.facet_planes(), 1e-7)
            .unwrap_or_else(|e| panic!("gear {gear}: {e}\n{text}"));
        // Tiers survive.
        let tiers: HashSet<&str> = back
            .solid
            .facets()
            .iter()
            .map(|f| f.tier.as_str())
            .collect();
        for t in [
            "table",
            "bezel",
            "star",
            "upper-half",
            "girdle",
            "pavilion-main",
            "lower-half",
        ] {
            assert!(tiers.contains(t), "tier {t} lost");
        }
    }

    #[test]
    fn asc_write_read_round_trip() {
        round_trip(96);
        // On an 80 gear the halves sit between teeth: fractional indices.
        round_trip(80);
        let cut = Cut::from_family("r", "round-brilliant", &BTreeMap::new()).unwrap();
        let text = write(&cut, 80);
        assert!(text.contains(" 22.5"), "{text}");
        let text = write(&cut, 96);
        assert!(text.starts_with("GemCad 5.0\ng 96 0.0\n"), "{text}");
        assert!(text.contains("a 0.000000 "), "{text}");
    }

    #[test]
    fn asc_design_keeps_its_record_and_comes_back_byte_for_byte() {
        let d = parse(STAR80.as_bytes(), "star80.asc").unwrap();
        let cut = d.to_cut("star80").unwrap();
        let rec = cut.record.as_ref().unwrap();
        assert_eq!((rec.gear, rec.gear_offset), (80.0, 0.0));
        assert_eq!((rec.symmetry, rec.mirror, rec.ri), (5, true, Some(1.61)));
        assert_eq!(rec.title, vec!["Test Star 80", "by facetlab tests"]);
        assert_eq!(rec.footnotes, vec!["Leave the table polished"]);
        assert_eq!(
            rec.instructions.get("P-1").map(String::as_str),
            Some("Cut to a point")
        );
        assert_eq!(rec.instructions.len(), 4);
        assert_eq!(cut.design_ri(), Some(1.61));
        // Its own gear, whole indices, its own distances, one line per tier: the same text.
        assert_eq!(write(&cut, 0), STAR80);
        // Asked for another gear, the azimuths keep their places: 80-gear index 8 is 9.6 on 96.
        let on96 = write(&cut, 96);
        assert!(
            on96.contains("g 96 0.0") && on96.contains(" 9.6 n Q"),
            "{on96}"
        );
        let back = parse(on96.as_bytes(), "x").unwrap();
        same_planes(&d.planes, &back.planes, 1e-9).unwrap();
    }

    #[test]
    fn asc_designs_survive_asc_to_asc() {
        // MINI (gear 96, a culet written `a 0 -d`, `n G` as a name), the messy variant and a
        // design on a gear with an offset and a fractional index.
        let shifted = "g 64 64.0\ny 1 n\nI 1.54\nH Shifted\na -90.00 1.00000 16 48\n\
                       a -90.00 0.9 0 32\na -42 0.75 0 16 32 48\na 0.00 -0.6 0\n\
                       a 38.5 0.85 0 16 32 48 8.5\na 0 0.4 0\nF note\n";
        for (name, bytes) in [
            ("mini", MINI.as_bytes().to_vec()),
            ("messy", messy()),
            ("shifted", shifted.as_bytes().to_vec()),
        ] {
            let d = parse(&bytes, name).unwrap();
            let cut = d.to_cut(name).unwrap();
            let text = write(&cut, 0);
            let e = parse(text.as_bytes(), name).unwrap();
            same_planes(&d.planes, &e.planes, 1e-7)
                .unwrap_or_else(|m| panic!("{name}: {m}\n{text}"));
            assert_eq!(
                (&d.title, &d.footnotes, d.ri, d.gear, d.symmetry, d.mirror),
                (&e.title, &e.footnotes, e.ri, e.gear, e.symmetry, e.mirror),
                "{name}"
            );
            assert_eq!(
                d.gear_offset.rem_euclid(d.gear),
                e.gear_offset.rem_euclid(e.gear)
            );
            let tiers = |x: &AscDesign| {
                let mut t: Vec<String> = x.planes.iter().map(|p| p.tier.clone()).collect();
                t.sort();
                t.dedup();
                t
            };
            assert_eq!(tiers(&d), tiers(&e), "{name}");
            assert_eq!(d.instructions, e.instructions, "{name}");
            let names: Vec<&str> = d.planes.iter().map(|p| p.name.as_str()).collect();
            let names2: Vec<&str> = e.planes.iter().map(|p| p.name.as_str()).collect();
            let (mut a, mut b) = (names.clone(), names2.clone());
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b, "{name}");
            // Written again: the same text.
            assert_eq!(write(&e.to_cut(name).unwrap(), 0), text, "{name}");
        }
    }

    #[test]
    fn asc_tier_angle_written_once_at_cutters_precision() {
        for preset in [
            "tolkowsky",
            "gia-reference",
            "princess",
            "marquise",
            "emerald",
        ] {
            let cut = crate::io::load_cut(preset).unwrap();
            let text = write(&cut, 0);
            let mut seen: Vec<(String, String, String)> = Vec::new();
            for l in text.lines().filter(|l| l.starts_with("a ")) {
                let w: Vec<&str> = l.split_whitespace().collect();
                let decimals = w[1].split('.').nth(1).map_or(0, str::len);
                assert!(decimals <= 6, "{preset}: {l}");
                let tier = l
                    .split(" n ")
                    .nth(1)
                    .map_or("", |t| t.split(' ').next().unwrap_or(""));
                let key = (tier.to_string(), w[1].to_string(), w[2].to_string());
                assert!(!seen.contains(&key), "{preset}: tier split: {l}");
                seen.push(key);
            }
            if preset == "tolkowsky" || preset == "gia-reference" {
                // One line per tier: one angle, one distance.
                for t in ["bezel", "star", "upper-half", "pavilion-main", "lower-half"] {
                    assert_eq!(seen.iter().filter(|k| k.0 == t).count(), 1, "{t}\n{text}");
                }
            }
            // Indices on the gear are whole numbers.
            if preset == "tolkowsky" {
                assert!(!text.contains(".5 ") && text.contains(" 93"), "{text}");
            }
        }
    }

    #[test]
    fn asc_culet_round_trips_as_gemcad_writes_it() {
        let mut v = BTreeMap::new();
        v.insert("culet".to_string(), 0.03);
        let cut = Cut::from_family("r", "round-brilliant", &v).unwrap();
        let text = write(&cut, 96);
        // The culet is written GemCad's way, `a 0 -d`, and named `culet` again when read.
        let culet = text.lines().find(|l| l.starts_with("a 0.000000 -"));
        assert!(culet.is_some(), "{text}");
        let back = parse(text.as_bytes(), "r.asc")
            .unwrap()
            .to_cut("r")
            .unwrap();
        assert_eq!(back.solid.facets().len(), cut.solid.facets().len());
    }
}
