//! Designs that measure as GemCad's ratios say (issue 37): a table is GemCad's T/W, a tableless
//! crown's angle comes from the tier that meets the girdle, a split near-level top is a table,
//! and the girdle is measured at its thinnest point; and generated cuts are written with the
//! record GemCad needs (`I`, their real symmetry). Each design is written here.

use super::{parse, write, write_for};
use crate::cut::{Cut, GemcadRecord};
use crate::geometry::DVec3;

fn design(text: &str) -> Cut {
    parse(text.as_bytes(), "t.asc")
        .unwrap()
        .to_cut("t")
        .unwrap()
}

/// A checkered crown with no table (Van Sant's Round Trichecker-12, released into the public
/// domain): a centre tier C at 10° holding the top, and two tiers that come down to the
/// girdle, A at 29.73° (12 triangles) and B at 25° (6 heptagons, facing the width squarely).
const TRICHECKER: &str = "GemCad 5.0
g 96 0.0
y 6 y
I 1.72
H Round Trichecker-12
a -41.000000 0.64991234 92 84 76 68 60 52 44 36 28 20 12 4
a -90.000000 1.07325092 92 84 76 68 60 52 44 36 28 20 12 4
a 29.730000 0.65249790 4 12 20 28 36 44 52 60 68 76 84 92
a 25.000000 0.59508784 96 16 32 48 64 80
a 10.000000 0.48799664 96 16 32 48 64 80
";

#[test]
fn a_tableless_crown_is_measured_at_the_tier_meeting_the_girdle() {
    let cut = design(TRICHECKER);
    let p = cut.proportions();
    // Not the centre tier C (10°) that holds the top: a tier meeting the girdle, B.
    assert!(
        (p.crown_angle - 25.0).abs() < 1e-6,
        "crown {}",
        p.crown_angle
    );
    // Its girdle, 3 % thick where the crown meets it; the parts add up.
    assert!((p.girdle - 0.03).abs() < 2e-3, "girdle {}", p.girdle);
    assert!((p.crown_height + p.girdle + p.pavilion_depth - p.total_depth).abs() < 1e-12);
    assert!((p.pavilion_angle - 41.0).abs() < 1e-6);
    assert_eq!(p.table, 0.0);
    assert_eq!(cut.ratios().t_w, 0.0);
}

/// An elongated design read from its GemCad file: an oval brilliant 1.5 × 1 W (table 0.56 of
/// the width across it) written as `.asc` and read back, so it is measured as a design.
fn long_design() -> Cut {
    let mut v = std::collections::BTreeMap::new();
    v.insert("length_width".to_string(), 1.5);
    v.insert("table".to_string(), 0.56);
    let oval = Cut::from_family("long", "oval", &v).unwrap();
    design(&write(&oval, 0))
}

#[test]
fn a_fancy_table_is_gemcads_t_w() {
    let cut = long_design();
    assert!(cut.family.is_none() && cut.record.is_some());
    let (s, p, r) = (&cut.solid, cut.proportions(), cut.ratios());
    // The table facet by brute force: its extent across the width, over the width.
    let table = s
        .facets()
        .iter()
        .find(|f| f.plane.normal.z > 1.0 - 1e-12)
        .unwrap();
    let ext = |vals: Vec<f64>| {
        vals.iter().copied().fold(f64::MIN, f64::max)
            - vals.iter().copied().fold(f64::MAX, f64::min)
    };
    let (wx, wy) = (
        ext(s.vertices().iter().map(|v| v.x).collect()),
        ext(s.vertices().iter().map(|v| v.y).collect()),
    );
    let across_y = wy < wx;
    assert!(wx.max(wy) > 1.4 * wx.min(wy), "the design is long");
    let t: Vec<f64> = table
        .vertices
        .iter()
        .map(|&v| {
            if across_y {
                s.vertices()[v].y
            } else {
                s.vertices()[v].x
            }
        })
        .collect();
    let want = ext(t) / wx.min(wy);
    assert!(
        (p.table - want).abs() < 1e-9,
        "table {} T/W {want}",
        p.table
    );
    assert!((r.t_w - p.table).abs() < 1e-12);
    // The family's own table, across the width (not its corner-to-corner over the length).
    assert!((p.table - 0.56).abs() < 1e-6, "table {}", p.table);
}

/// A bar on a flat back (like the Shah replica): walls ±y and ±x, a roof of two facets 2° off
/// level, and a 60° slope cutting down the +x end, so the girdle's walls are thinnest there.
const BAR: &str = "GemCad 5.0
g 64 64.0
y 1 n
I 1.54
H Bar test
a -90 0.5 0 32
a -90 1.0 16 48
a 0 -0.4 64
a 2 0.35 16 48
a 60 0.8 16
";

#[test]
fn a_split_level_top_is_a_table_and_the_girdle_is_at_its_thinnest() {
    let cut = design(BAR);
    let p = cut.proportions();
    // The roof spans the whole width: T/W 1.
    assert!((p.table - 1.0).abs() < 1e-9, "table {}", p.table);
    // The +x wall runs from the back (−0.4) up to the slope at x = 1:
    // z = (0.8 − sin 60°) / cos 60°.
    let slope = (0.8 - 60f64.to_radians().sin()) / 60f64.to_radians().cos();
    assert!(
        (p.girdle - (slope + 0.4)).abs() < 1e-9,
        "girdle {}",
        p.girdle
    );
    assert_eq!(p.pavilion_depth, 0.0);
    assert!((p.crown_height + p.girdle + p.pavilion_depth - p.total_depth).abs() < 1e-12);
    // The crown angle: the end slope, the one crown facet that meets both the table and the
    // girdle (never a near-vertical wall).
    assert!(
        (p.crown_angle - 60.0).abs() < 1e-6,
        "crown {}",
        p.crown_angle
    );
}

#[test]
fn generated_cuts_are_written_with_their_index_and_symmetry() {
    for (preset, sym) in [
        ("tolkowsky", "y 8 y"),
        ("princess", "y 4 y"),
        ("oval", "y 2 y"),
        ("emerald", "y 2 y"),
        ("pear", "y 1 n"),
    ] {
        let cut = crate::io::load_cut(preset).unwrap();
        let text = write(&cut, 0);
        assert!(text.contains(&format!("\n{sym}\n")), "{preset}:\n{text}");
        assert!(text.contains("\nI 2.417\n"), "{preset}");
        // Read back: the symmetry written is one the solid has (every facet's turn and, with
        // a mirror, its mirror through index 0 land on facets), and the index survives.
        let back = parse(text.as_bytes(), "x.asc")
            .unwrap()
            .to_cut("x")
            .unwrap();
        let rec = back.record.as_ref().unwrap();
        assert_eq!(rec.ri, Some(2.417));
        let planes: Vec<(DVec3, f64)> = back
            .solid
            .facets()
            .iter()
            .map(|f| (f.plane.normal, f.plane.offset))
            .collect();
        let has = |m: glam::DMat3| {
            planes.iter().all(|&(n, o)| {
                planes
                    .iter()
                    .any(|&(q, d)| (q - m * n).length() < 1e-7 && (d - o).abs() < 1e-7)
            })
        };
        let turn = glam::DMat3::from_rotation_z(std::f64::consts::TAU / f64::from(rec.symmetry));
        assert!(has(turn), "{preset}: {} is not a symmetry", rec.symmetry);
        // GemCad's mirror: across the line through index 0 (the y axis).
        let mirror = glam::DMat3::from_diagonal(DVec3::new(-1.0, 1.0, 1.0));
        assert_eq!(has(mirror), rec.mirror, "{preset}");
    }
    // Another material's index; a design keeps its own record.
    let cut = crate::io::load_cut("tolkowsky").unwrap();
    assert!(write_for(&cut, 0, 1.5442).contains("\nI 1.5442\n"));
    let tri = design(TRICHECKER);
    let rec = GemcadRecord::for_file(&tri, 0, 2.417);
    assert_eq!((rec.symmetry, rec.mirror, rec.ri), (6, true, Some(1.72)));
}
