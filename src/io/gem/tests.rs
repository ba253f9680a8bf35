//! Tests of the `.gem` reader and writer: a file built byte by byte here (by GemCad's frame, not
//! the writer's code) read as its `.asc` twin, chiral so that a wrong index direction shows;
//! every preset and the `.asc` tests' designs through `.gem` and back, byte for byte and to the
//! same solid; and files cut short, oversized or garbled.

use super::*;
use crate::cut::record::DIAMOND_RI;
use crate::cut::Cut;
use crate::geometry::{facet_normal, FacetPlane};
use crate::io::asc::{self, AscDesign};
use crate::testkit::asc::{messy, same_planes, MINI, STAR80};

/// One line of the chiral test design: angle, distance, indices on gear 96 (offset 0), the
/// tier name, one facet's own name (by position), the instructions.
struct Line {
    angle: f64,
    dist: f64,
    idx: Vec<f64>,
    name: &'static str,
    own: Option<(usize, &'static str)>,
    instructions: &'static str,
}

/// A design that is not its own mirror image: girdle at the mains, pavilion facets 5 teeth
/// and crown facets 7 teeth past them (mirrored, the pavilion would be at 7 and the crown at
/// 5), a table.
fn chiral() -> Vec<Line> {
    let ring = |start: f64| {
        (0..8)
            .map(|k| start + 12.0 * f64::from(k))
            .collect::<Vec<_>>()
    };
    vec![
        Line {
            angle: -90.0,
            dist: 1.0,
            idx: ring(12.0),
            name: "G",
            own: None,
            instructions: "Size the girdle",
        },
        Line {
            angle: -42.0,
            dist: 0.75,
            idx: ring(5.0),
            name: "P",
            own: None,
            instructions: "Cut to the centre",
        },
        Line {
            angle: 35.0,
            dist: 0.8,
            idx: ring(7.0),
            name: "C",
            own: Some((3, "Cx")),
            instructions: "",
        },
        Line {
            angle: 0.0,
            dist: 0.35,
            idx: vec![96.0],
            name: "T",
            own: None,
            instructions: "Polish last",
        },
    ]
}

/// Index `i` of gear 96 (offset 0) on gear `g` with offset `o`: the same azimuth.
fn on_gear(i: f64, g: f64, o: f64) -> f64 {
    let j = (o + g * i / 96.0).rem_euclid(g.abs());
    if j == 0.0 {
        g.abs()
    } else {
        j
    }
}

/// The chiral design as a `.asc` on gear `g` with offset `o`.
fn chiral_asc(g: f64, o: f64) -> String {
    let mut s =
        format!("GemCad 5.0\ng {g} {o:.1}\ny 8 n\nI 1.54\nH Chiral test\nH by facetlab tests\n");
    for l in chiral() {
        s += &format!("a {:.6} {:.8}", l.angle, l.dist);
        for (k, &i) in l.idx.iter().enumerate() {
            s += &format!(" {}", on_gear(i, g, o));
            if k == 0 {
                s += &format!(" n {}", l.name);
            } else if let Some((_, own)) = l.own.filter(|(at, _)| *at == k) {
                s += &format!(" n {own}");
            }
        }
        if !l.instructions.is_empty() {
            s += &format!(" G {}", l.instructions);
        }
        s.push('\n');
    }
    s + "F First note\n"
}

/// A length-prefixed string as GemCad writes it (short strings only).
fn push_str(b: &mut Vec<u8>, s: &str) {
    b.push(u8::try_from(s.len()).unwrap());
    b.extend_from_slice(s.as_bytes());
}

/// The chiral design as a `.gem` built byte by byte, by GemCad's frame: index `i` at azimuth
/// `sign · (90° − 360° (i − o) / g)` in the file (`sign` −1 builds the mirror image), each
/// facet with three made-up vertices (the reader must not use them).
fn chiral_gem(g: f64, o: f64, sign: f64) -> Vec<u8> {
    let mut b = Vec::new();
    for (t, l) in chiral().iter().enumerate() {
        for (k, &i96) in l.idx.iter().enumerate() {
            let i = on_gear(i96, g, o);
            let az = sign * (90.0 - 360.0 * (i - o) / g);
            let p = facet_normal(l.angle.abs(), az, l.angle >= 0.0) / l.dist;
            for v in [p.x, p.y, p.z] {
                b.extend_from_slice(&v.to_le_bytes());
            }
            b.extend_from_slice(&(t as i32 + 1).to_le_bytes());
            let name = match (k, l.own) {
                (0, _) => l.name,
                (_, Some((at, own))) if at == k => own,
                _ => "",
            };
            push_str(&mut b, &format!("{name}\t{}", l.instructions));
            for v in 0..3 {
                b.extend_from_slice(&1i32.to_le_bytes());
                for c in [1.0, 2.0, f64::from(v)] {
                    b.extend_from_slice(&(c * 7.5f64).to_le_bytes());
                }
            }
            b.extend_from_slice(&0i32.to_le_bytes());
        }
    }
    b.extend_from_slice(&(-99999.0f64).to_le_bytes());
    b.extend_from_slice(&8i32.to_le_bytes());
    b.extend_from_slice(&0i32.to_le_bytes());
    b.extend_from_slice(&(g as i32).to_le_bytes());
    b.extend_from_slice(&1.54f64.to_le_bytes());
    b.extend_from_slice(&0x7FFFu32.to_le_bytes());
    b.extend_from_slice(&o.to_le_bytes());
    for s in [
        "Chiral test",
        "by facetlab tests",
        "",
        "",
        "First note",
        "",
        "",
        "",
    ] {
        push_str(&mut b, s);
    }
    b
}

/// The metadata a design keeps, compared as a whole.
fn meta(d: &AscDesign) -> (Vec<String>, Vec<String>, f64, f64, u32, bool, Option<f64>) {
    (
        d.title.clone(),
        d.footnotes.clone(),
        d.gear,
        d.gear_offset.rem_euclid(d.gear.abs()),
        d.symmetry,
        d.mirror,
        d.ri,
    )
}

fn sorted_names(planes: &[FacetPlane]) -> Vec<(String, String)> {
    let mut v: Vec<(String, String)> = planes
        .iter()
        .map(|p| (p.name.clone(), p.tier.clone()))
        .collect();
    v.sort();
    v
}

#[test]
fn gem_built_byte_by_byte_reads_as_its_asc_twin_and_not_as_its_mirror() {
    for (g, o) in [(96.0, 0.0), (-96.0, 48.0), (64.0, 16.0)] {
        let asc = asc::parse(chiral_asc(g, o).as_bytes(), "chiral.asc").unwrap();
        let gem = parse(&chiral_gem(g, o, 1.0), "chiral.gem").unwrap();
        same_planes(&asc.planes, &gem.planes, 1e-12)
            .unwrap_or_else(|e| panic!("gear {g}/{o}: {e}"));
        assert_eq!(sorted_names(&asc.planes), sorted_names(&gem.planes));
        assert!(gem.planes.iter().any(|p| p.name == "Cx"));
        assert_eq!(meta(&asc), meta(&gem), "gear {g}/{o}");
        assert_eq!(asc.instructions, gem.instructions);
        assert_eq!(gem.instructions.len(), 3);
        // Each line's indices as the `.asc` gives them.
        for (a, b) in asc.tiers.iter().zip(&gem.tiers) {
            assert_eq!((a.angle, a.name.as_deref()), (b.angle, b.name.as_deref()));
            assert!((a.distance - b.distance).abs() < 1e-14);
            for ((i, _), (j, _)) in a.indices.iter().zip(&b.indices) {
                assert!(
                    (i.rem_euclid(96.0) - j.rem_euclid(96.0)).abs() < 1e-9,
                    "{i} {j}"
                );
            }
        }
        let (a, b) = (asc.to_cut("a").unwrap(), gem.to_cut("b").unwrap());
        same_planes(&a.solid.facet_planes(), &b.solid.facet_planes(), 1e-9).unwrap();
        assert_eq!(a.record, b.record);
        // The mirror image is another solid: the index direction is not a matter of taste.
        let mirror = parse(&chiral_gem(g, o, -1.0), "m.gem").unwrap();
        assert!(same_planes(&asc.planes, &mirror.planes, 1e-6).is_err());
    }
}

/// The designs of the round trips: the `.asc` tests' designs, the chiral one on three gears
/// (on gear 64 its indices are fractional), and every preset written to `.asc` and read back.
fn designs() -> Vec<(String, Cut)> {
    let mut out: Vec<(String, Vec<u8>)> = vec![
        ("mini".into(), MINI.as_bytes().to_vec()),
        ("star80".into(), STAR80.as_bytes().to_vec()),
        ("messy".into(), messy()),
        ("chiral".into(), chiral_asc(96.0, 0.0).into_bytes()),
        ("chiral-ccw".into(), chiral_asc(-96.0, 48.0).into_bytes()),
        ("chiral-64".into(), chiral_asc(64.0, 16.0).into_bytes()),
    ];
    for name in crate::io::presets::names() {
        let cut = crate::io::presets::load(name).unwrap().unwrap();
        out.push((format!("{name}.asc"), asc::write(&cut, 0).into_bytes()));
    }
    // Each as its .asc writes it (indices and distances on the .asc's own grid).
    out.into_iter()
        .map(|(n, b)| {
            let cut = asc::parse(&b, &n).unwrap().to_cut(&n).unwrap();
            let text = asc::write(&cut, 0);
            (
                n.clone(),
                asc::parse(text.as_bytes(), &n).unwrap().to_cut(&n).unwrap(),
            )
        })
        .collect()
}

#[test]
fn designs_go_asc_to_gem_and_back_to_the_same_solid_and_the_same_asc() {
    for (name, x) in designs() {
        let bytes = write(&x, 0).unwrap();
        let y = parse(&bytes, &name).unwrap().to_cut(&name).unwrap();
        // The same solid at W = 1, facet by facet (1e-9 of W).
        same_planes(&x.solid.facet_planes(), &y.solid.facet_planes(), 1e-9)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(
            sorted_names(&x.solid.facet_planes()),
            sorted_names(&y.solid.facet_planes())
        );
        // What the .asc writer keeps, kept: the same .asc, line for line (a design without an
        // index comes back with the 2.42 the writer gives it).
        let (ax, ay) = (asc::write(&x, 0), asc::write(&y, 0));
        let no_default_ri = |s: &str| s.replace("I 2.42\n", "");
        if x.record.as_ref().is_some_and(|r| r.ri.is_some()) {
            assert_eq!(ax, ay, "{name}");
        } else {
            assert_eq!(no_default_ri(&ax), no_default_ri(&ay), "{name}");
        }
        // .gem → .gem byte for byte, and .gem → .asc → .gem too.
        assert_eq!(write(&y, 0).unwrap(), bytes, "{name}: .gem → .gem");
        let z = asc::parse(ay.as_bytes(), &name)
            .unwrap()
            .to_cut(&name)
            .unwrap();
        assert_eq!(asc::write(&z, 0), ay, "{name}: .asc → .asc");
        same_planes(&y.solid.facet_planes(), &z.solid.facet_planes(), 1e-9)
            .unwrap_or_else(|e| panic!("{name} .gem → .asc: {e}"));
        assert_eq!(write(&z, 0).unwrap(), bytes, "{name}: .gem → .asc → .gem");
    }
}

#[test]
fn every_preset_goes_to_gem_and_back_byte_for_byte_and_to_its_own_solid() {
    for name in crate::io::presets::names() {
        let cut = crate::io::presets::load(name).unwrap().unwrap();
        let bytes = write(&cut, 0).unwrap();
        let back = parse(&bytes, name).unwrap().to_cut(name).unwrap();
        same_planes(&cut.solid.facet_planes(), &back.solid.facet_planes(), 1e-9)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let rec = back.record.as_ref().unwrap();
        assert_eq!(rec.title, vec![cut.name.clone()]);
        // The record the .asc writer gives a generated cut: gear 96, diamond's index, the
        // cut's own symmetry and mirror.
        let want = crate::cut::GemcadRecord::generated(&cut, 0, DIAMOND_RI);
        assert_eq!(
            (rec.gear, rec.gear_offset, rec.ri, rec.symmetry, rec.mirror),
            (96.0, 0.0, Some(DIAMOND_RI), want.symmetry, want.mirror),
            "{name}"
        );
        // Written for another material, its index.
        let quartz = parse(&write_for(&cut, 0, 1.5442).unwrap(), name).unwrap();
        assert_eq!(quartz.ri, Some(1.5442), "{name}");
        assert_eq!(write(&back, 0).unwrap(), bytes, "{name}");
        // Asked for another gear, the azimuths keep their places (fractional indices).
        let on80 = write(&cut, 80).unwrap();
        let b80 = parse(&on80, name).unwrap().to_cut(name).unwrap();
        same_planes(&cut.solid.facet_planes(), &b80.solid.facet_planes(), 1e-8)
            .unwrap_or_else(|e| panic!("{name} on 80: {e}"));
        assert_eq!(write(&b80, 0).unwrap(), on80, "{name} on 80");
    }
}

#[test]
fn gem_text_long_strings_windows_1252_and_more_than_four_titles() {
    let mut cut = asc::parse(STAR80.as_bytes(), "s")
        .unwrap()
        .to_cut("s")
        .unwrap();
    let long = "Meet P, G, then polish. ".repeat(20);
    let huge = "x".repeat(70_000);
    {
        let r = cut.record.as_mut().unwrap();
        r.title = vec![
            "Caf\u{e9} \u{2013} \u{20ac}5".into(),
            huge.clone(),
            "three".into(),
            "four".into(),
            "five".into(),
        ];
        r.footnotes = vec![long.trim().to_string()];
        r.instructions.insert("P-1".into(), long.trim().to_string());
    }
    let bytes = write(&cut, 0).unwrap();
    let d = parse(&bytes, "s.gem").unwrap();
    assert_eq!(
        d.title,
        vec!["Caf\u{e9} \u{2013} \u{20ac}5", &huge, "three", "four five"]
    );
    assert_eq!(d.footnotes, vec![long.trim()]);
    assert_eq!(d.instructions["P-1"], long.trim());
    assert!(bytes.windows(4).any(|w| w == b"Caf\xe9"));
    let back = d.to_cut("s").unwrap();
    assert_eq!(write(&back, 0).unwrap(), bytes);
}

/// A written `.gem` of the chiral design with a preform after it, and every way to break it.
#[test]
fn gem_cut_short_oversized_or_garbled_is_one_line_naming_file_and_byte() {
    let x = asc::parse(chiral_asc(96.0, 0.0).as_bytes(), "c")
        .unwrap()
        .to_cut("c")
        .unwrap();
    let good = write(&x, 0).unwrap();
    let want = parse(&good, "c.gem").unwrap();
    // A preform after the footnotes is skipped.
    let mut pre = good.clone();
    push_str(&mut pre, "preform");
    pre.extend_from_slice(&good[..200]);
    assert_eq!(parse(&pre, "c.gem").unwrap(), want);
    let byte_of = |e: &str| -> usize {
        let rest = e
            .strip_prefix("c.gem: byte ")
            .unwrap_or_else(|| panic!("{e}"));
        rest.split(':').next().unwrap().parse().unwrap()
    };
    // Every prefix: an error at or before the cut, one line.
    for n in 0..good.len() {
        let e = parse(&good[..n], "c.gem").unwrap_err().to_string();
        assert!(!e.contains('\n'), "{e}");
        assert!(byte_of(&e) <= n, "cut at {n}: {e}");
    }
    // Each byte garbled: parsed and built, or a one-line error naming the file (or the cut).
    let (mut built, mut failed) = (0, 0);
    for n in 0..good.len() {
        let mut g = good.clone();
        g[n] = g[n].wrapping_mul(7).wrapping_add(0x81);
        match parse(&g, "c.gem").and_then(|d| d.to_cut("garbled-cut")) {
            Ok(_) => built += 1,
            Err(e) => {
                let e = e.to_string();
                assert!(!e.contains('\n'), "{e}");
                assert!(
                    e.starts_with("c.gem: byte ") || e.contains("garbled-cut"),
                    "{e}"
                );
                failed += 1;
            }
        }
    }
    assert!(built > 0 && failed > 0, "{built} built, {failed} failed");
    // A label claiming 4 GB: refused before anything is read or allocated.
    let label = 3 * 8 + 4;
    let mut big = good[..label].to_vec();
    big.extend_from_slice(&[0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF]);
    big.extend_from_slice(&good[label + 1..]);
    let e = parse(&big, "c.gem").unwrap_err().to_string();
    assert!(
        e.starts_with(&format!("c.gem: byte {label}: "))
            && e.contains("4294967295 bytes runs past the end"),
        "{e}"
    );
    // Field by field.
    let end = good
        .windows(8)
        .rposition(|w| w == (-99999.0f64).to_le_bytes())
        .unwrap();
    let marker = label + 1 + usize::from(good[label]);
    let mut cases: Vec<(usize, Vec<u8>, &str)> = vec![
        (
            marker,
            7i32.to_le_bytes().to_vec(),
            "expected a vertex marker",
        ),
        (
            end + 12,
            2i32.to_le_bytes().to_vec(),
            "mirror flag 2 is not allowed",
        ),
        (
            end + 16,
            0i32.to_le_bytes().to_vec(),
            "gear 0 is not allowed",
        ),
        (
            end + 20,
            (-1.0f64).to_le_bytes().to_vec(),
            "refractive index -1 is not allowed",
        ),
        (
            end + 8,
            (-3i32).to_le_bytes().to_vec(),
            "symmetry -3 is not allowed",
        ),
        (0, f64::NAN.to_le_bytes().to_vec(), "is not a plane"),
    ];
    cases.push((label, vec![0xFF, 0xFE, 0xFF], "Unicode"));
    for (at, bytes, what) in cases {
        let mut g = good.clone();
        g[at..at + bytes.len()].copy_from_slice(&bytes);
        let e = parse(&g, "c.gem").unwrap_err().to_string();
        assert!(
            e.starts_with(&format!("c.gem: byte {at}: ")) && e.contains(what),
            "{what}: {e}"
        );
    }
    let mut junk = good.clone();
    junk.extend_from_slice(b"\x03abcdef");
    let e = parse(&junk, "c.gem").unwrap_err().to_string();
    assert!(
        e.starts_with(&format!(
            "c.gem: byte {}: 7 bytes after the footnotes",
            good.len()
        )),
        "{e}"
    );
}

#[test]
fn gem_is_read_wherever_a_cut_is() {
    let dir = tempfile::tempdir().unwrap();
    let x = asc::parse(MINI.as_bytes(), "m")
        .unwrap()
        .to_cut("m")
        .unwrap();
    let bytes = write(&x, 0).unwrap();
    let path = dir.path().join("My Design.gem");
    std::fs::write(&path, &bytes).unwrap();
    let cut = crate::io::load_cut(path.to_str().unwrap()).unwrap();
    assert_eq!(cut.name, "My Design");
    same_planes(&x.solid.facet_planes(), &cut.solid.facet_planes(), 1e-9).unwrap();
    let up = crate::io::parse_cut("gem", &bytes, "up", "upload").unwrap();
    assert_eq!(up.solid.facets().len(), x.solid.facets().len());
    let e = crate::io::parse_cut("gem", &bytes[..50], "up", "upload").unwrap_err();
    assert!(e.to_string().starts_with("upload: byte "), "{e}");
    let e = read(&dir.path().join("missing.gem"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("missing.gem") && e.contains("no such file"),
        "{e}"
    );
}
