//! Tests of a design as a cut space (issue 23's checks 1–4), on every bundled preset written
//! to `.asc` and on designs written here with meets at the girdle, on a keel and at a culet;
//! with the brute-force vertex enumeration the checks use, independent of `Polyhedron`.

use super::reangle::adjacency;
use super::{DesignSpace, OpenMeets, MEET_TOL};
use crate::cut::{Cut, CutSpace};
use crate::geometry::{DVec3, FacetPlane, Polyhedron};
use std::collections::{BTreeMap, BTreeSet};

/// Every vertex of the solid of `planes` by brute force (each three planes' intersection
/// inside all the others), with the names of the facets through it (within 1e-9).
pub(crate) fn brute_vertices(planes: &[FacetPlane]) -> Vec<(DVec3, BTreeSet<String>)> {
    let mut out: Vec<(DVec3, BTreeSet<String>)> = Vec::new();
    let n = planes.len();
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let (a, b, c) = (&planes[i].plane, &planes[j].plane, &planes[k].plane);
                let m = glam::DMat3::from_cols(a.normal, b.normal, c.normal).transpose();
                if m.determinant().abs() < 1e-9 {
                    continue;
                }
                let p = m.inverse() * DVec3::new(a.offset, b.offset, c.offset);
                if planes
                    .iter()
                    .any(|q| q.plane.normal.dot(p) - q.plane.offset > 1e-9)
                {
                    continue;
                }
                if out.iter().any(|(q, _)| q.distance(p) < 1e-9) {
                    continue;
                }
                let on = planes
                    .iter()
                    .filter(|q| (q.plane.normal.dot(p) - q.plane.offset).abs() < 1e-9)
                    .map(|q| q.name.clone())
                    .collect();
                out.push((p, on));
            }
        }
    }
    out
}

/// Every vertex of `a` within `tol` of a vertex of `b`, and as many of them.
pub(crate) fn same_vertices(a: &Polyhedron, b: &Polyhedron, tol: f64) {
    assert_eq!(a.vertices().len(), b.vertices().len());
    for p in a.vertices() {
        let d = b
            .vertices()
            .iter()
            .map(|q| q.distance(*p))
            .fold(f64::MAX, f64::min);
        assert!(d < tol, "vertex {p} is {d} from the other solid");
    }
}

/// Every facet of `a` has a facet of the same name in `b` with its plane within `tol`.
fn same_facets(a: &Polyhedron, b: &Polyhedron, tol: f64) {
    assert_eq!(a.facets().len(), b.facets().len());
    for f in a.facets() {
        let g = b
            .facets()
            .iter()
            .find(|g| g.name == f.name)
            .unwrap_or_else(|| panic!("facet {} is missing", f.name));
        let d = f.plane.normal.distance(g.plane.normal) + (f.plane.offset - g.plane.offset).abs();
        assert!(d < tol, "facet {} moved by {d}", f.name);
    }
}

/// A design made here: a girdle of vertical facets (azimuth in degrees, distance), girdle
/// half-thickness `g`, each girdle facet with a crown facet through its top edge at `crown`°
/// and a pavilion facet through its bottom edge at `pavilion(k)`°, and a table at height `t`.
/// Tiers: `G{tier}`, `C{tier}`, `P{tier}` by each girdle facet's `tier` number, and `T`.
fn made(
    girdle: &[(f64, f64, u32)],
    g: f64,
    crown: f64,
    pavilion: &dyn Fn(u32) -> f64,
    t: f64,
) -> Cut {
    let mut planes = Vec::new();
    for (k, &(az, off, tier)) in girdle.iter().enumerate() {
        let (s, c) = az.to_radians().sin_cos();
        planes.push(FacetPlane::new(
            DVec3::new(c, s, 0.0),
            off,
            format!("G{tier}-{k}"),
            format!("G{tier}"),
        ));
        let a = crown.to_radians();
        let n = DVec3::new(a.sin() * c, a.sin() * s, a.cos());
        let d = n.dot(DVec3::new(off * c, off * s, g));
        planes.push(FacetPlane::new(
            n,
            d,
            format!("C{tier}-{k}"),
            format!("C{tier}"),
        ));
        let b = pavilion(tier).to_radians();
        let n = DVec3::new(b.sin() * c, b.sin() * s, -b.cos());
        let d = n.dot(DVec3::new(off * c, off * s, -g));
        planes.push(FacetPlane::new(
            n,
            d,
            format!("P{tier}-{k}"),
            format!("P{tier}"),
        ));
    }
    planes.push(FacetPlane::new(DVec3::Z, t, "T", "T"));
    Cut::from_planes("made", &planes).unwrap()
}

/// An octagon: crown and pavilion facets through the girdle's edges (every girdle corner a
/// meet of four), the eight pavilion facets meeting at a point culet (a meet of eight).
fn octagon() -> Cut {
    let girdle: Vec<(f64, f64, u32)> = (0..8).map(|k| (45.0 * k as f64, 0.5, 1)).collect();
    made(&girdle, 0.015, 38.0, &|_| 42.0, 0.17)
}

/// An elongated hexagon (two long sides, four ends at ±37.5° on the 96 gear): every girdle
/// corner a meet of four, and the two long pavilion facets meeting in a keel whose ends are
/// meets of four (the long pair and an end pair, mirror images).
fn keel() -> Cut {
    let mut girdle = vec![(90.0, 0.5, 1), (270.0, 0.5, 1)];
    for az in [37.5, -37.5, 142.5, 217.5] {
        girdle.push((az, 0.62, 2));
    }
    made(
        &girdle,
        0.012,
        36.0,
        &|t| if t == 1 { 43.0 } else { 41.0 },
        0.15,
    )
}

/// `cut` written to `.asc` (on the 96 gear) and read back.
fn through_asc(cut: &Cut) -> Cut {
    let text = crate::io::asc::write(cut, 96);
    crate::io::asc::parse(text.as_bytes(), "t.asc")
        .unwrap()
        .to_cut(&cut.name)
        .unwrap()
}

fn space(cut: &Cut) -> DesignSpace {
    DesignSpace::new(cut, MEET_TOL, OpenMeets::Refuse).unwrap()
}

/// The designs of check 1: every preset, and the three made here, through `.asc`.
fn designs() -> Vec<(String, Cut)> {
    let mut out: Vec<(String, Cut)> = crate::io::presets::names()
        .iter()
        .map(|n| (n.to_string(), through_asc(&crate::io::load_cut(n).unwrap())))
        .collect();
    out.push(("octagon".into(), through_asc(&octagon())));
    out.push(("keel".into(), through_asc(&keel())));
    out
}

#[test]
fn a_design_replayed_at_its_own_angles_is_the_same_solid() {
    for (name, cut) in designs() {
        let s = space(&cut);
        // Adopting the meets moves nothing by more than the file's rounding (it welds the
        // clusters of vertices that rounding split each meet into) …
        for p in cut.solid.vertices() {
            let d = s
                .base()
                .solid
                .vertices()
                .iter()
                .map(|q| q.distance(*p))
                .fold(f64::MAX, f64::min);
            assert!(d < 1e-6, "{name}: vertex {p} moved {d}");
        }
        // … and the adopted design replays to itself, every vertex and facet within 1e-9.
        let again = s.build(&name, &BTreeMap::new()).unwrap();
        same_vertices(&s.base().solid, &again.solid, 1e-9);
        same_facets(&s.base().solid, &again.solid, 1e-9);
        assert_eq!(
            adjacency(&s.base().solid),
            adjacency(&again.solid),
            "{name}"
        );
        assert!(!s.keys().is_empty(), "{name}");
    }
    // The made designs have the meets they were made with.
    let count = |cut: &Cut, n: usize| {
        space(&through_asc(cut))
            .meets()
            .iter()
            .filter(|m| m.facets.len() == n)
            .count()
    };
    assert_eq!(
        count(&octagon(), 4),
        16,
        "8 top and 8 bottom girdle corners"
    );
    assert_eq!(count(&octagon(), 8), 1, "the culet");
    assert_eq!(
        count(&keel(), 4),
        12 + 2,
        "12 girdle corners and the keel's two ends"
    );
}

/// The names of the facets through each meet of `s`'s base.
fn meet_names(s: &DesignSpace) -> Vec<BTreeSet<String>> {
    s.meets()
        .iter()
        .map(|m| {
            m.facets
                .iter()
                .map(|&f| s.base().solid.facets()[f].name.clone())
                .collect()
        })
        .collect()
}

#[test]
fn turned_tiers_keep_every_meet_by_brute_force() {
    let cases: Vec<(Cut, Vec<(&str, f64)>)> = vec![
        (octagon(), vec![("P1", 41.0)]),
        (octagon(), vec![("C1", 35.0), ("P1", 43.5)]),
        (keel(), vec![("P1", 44.0)]),
        (keel(), vec![("P2", 39.5), ("C2", 33.0)]),
        (
            crate::io::load_cut("tolkowsky").unwrap(),
            vec![("pavilion-main", 41.3), ("upper-half", 41.5)],
        ),
    ];
    for (cut, turns) in cases {
        let s = space(&through_asc(&cut));
        let values: BTreeMap<String, f64> =
            turns.iter().map(|(k, v)| (k.to_string(), *v)).collect();
        let free: Vec<(String, f64, f64)> = values
            .iter()
            .map(|(k, v)| (k.clone(), v - 1.0, v + 1.0))
            .collect();
        assert!(s.unkeepable(&free).unwrap().is_empty(), "{turns:?}");
        let turned = s.build("t", &values).unwrap();
        // The angles asked for (on GemCad's grid) …
        for (k, v) in &values {
            assert_eq!(turned.params[k], *v);
        }
        // … every meet still a meet of all its facets, found by brute force …
        let brute = brute_vertices(&turned.solid.facet_planes());
        for names in meet_names(&s) {
            assert!(
                brute.iter().any(|(_, on)| names.is_subset(on)),
                "{turns:?}: meet {names:?} opened"
            );
        }
        assert!(s.gaps(&turned).iter().all(|g| *g < 1e-9), "{turns:?}");
        // … the same facets and the same facet adjacency, by brute force too.
        assert_eq!(turned.solid.facets().len(), s.base().solid.facets().len());
        assert_eq!(brute.len(), turned.solid.vertices().len(), "{turns:?}");
        assert_eq!(adjacency(&s.base().solid), adjacency(&turned.solid));
        for f in turned.solid.facets() {
            assert!(brute.iter().filter(|(_, on)| on.contains(&f.name)).count() >= 3);
        }
    }
}

#[test]
fn the_design_path_lands_on_the_family() {
    // The mapping: the family's `pavilion_angle` is the mains' angle; its `lower_half` is a
    // length, and the lower halves' angle follows from it and the mains'. A design's angles
    // live on GemCad's grid (6 decimals), so the family is taken at pavilion_angle 41.25 and
    // the `lower_half` (found by bisection) that puts its lower halves on the grid too. Then
    // tolkowsky's mains and lower halves turned to those angles by the design path land on the
    // family's solid: read from the preset directly to rounding (1e-9); through `.asc`,
    // whose depths carry 8 decimals, to the file's rounding (1e-8).
    let preset = crate::io::load_cut("tolkowsky").unwrap();
    let at = |lower: f64| {
        let cut = preset
            .with_params(&BTreeMap::from([
                ("pavilion_angle".to_string(), 41.25),
                ("lower_half".to_string(), lower),
            ]))
            .unwrap();
        let a = super::TierModel::of_cut(&cut, MEET_TOL).unwrap();
        let t = a.names.iter().position(|n| n == "lower-half").unwrap();
        (cut, a.angles()[t])
    };
    let target = (at(preset.params["lower_half"]).1 * 1e6).round() / 1e6;
    let (mut lo, mut hi) = (0.6, 0.95);
    let rising = at(hi).1 > at(lo).1;
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if (at(mid).1 < target) == rising {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (family, halves) = at(0.5 * (lo + hi));
    assert!((halves - target).abs() < 1e-12, "{halves} {target}");
    let turns = BTreeMap::from([
        ("pavilion-main".to_string(), 41.25),
        ("lower-half".to_string(), halves),
    ]);
    for (cut, tol) in [(preset.clone(), 1e-9), (through_asc(&preset), 1e-8)] {
        let s = space(&cut);
        let turned = s.build("t", &turns).unwrap();
        same_vertices(&family.solid, &turned.solid, tol);
        assert_eq!(adjacency(&family.solid), adjacency(&turned.solid));
    }
}

#[test]
fn the_written_design_reads_back_as_the_cut_that_was_scored() {
    let s = space(&through_asc(&keel()));
    let turned = s
        .build("t", &BTreeMap::from([("P1".to_string(), 44.123456789)]))
        .unwrap();
    // Angles are built on GemCad's grid, so the file says exactly what was built.
    assert_eq!(turned.params["P1"], 44.123457);
    let note = &turned.record.as_ref().unwrap().footnotes;
    assert!(
        note.iter().any(|n| n.contains("P1 44.12 (was 43.00)")),
        "{note:?}"
    );
    let back = through_asc(&turned);
    let again = space(&back);
    same_vertices(&turned.solid, &again.base().solid, 1e-9);
    same_facets(&turned.solid, &again.base().solid, 1e-9);
    let config = crate::metrics::ScoreConfig::fast();
    let a = crate::metrics::score(&turned.solid, &config);
    let b = crate::metrics::score(&again.base().solid, &config);
    for (name, x, y) in [
        ("brilliance", a.brilliance, b.brilliance),
        ("fire", a.fire, b.fire),
        ("scintillation", a.scintillation, b.scintillation),
        (
            "light return",
            a.overhead_light_return,
            b.overhead_light_return,
        ),
    ] {
        assert!((x - y).abs() < 1e-7, "{name}: {x} against {y}");
    }
}

#[test]
fn a_mesh_of_a_preset_has_the_presets_tiers() {
    // A mesh carries no GemCad lines: its tiers are the facets its symmetry maps onto each
    // other (one tier name, one angle, one depth, within the mesh's rounding).
    for name in ["tolkowsky", "princess", "oval"] {
        let cut = crate::io::load_cut(name).unwrap();
        let obj = crate::io::mesh::write_obj(&cut);
        let mesh = crate::io::parse_cut("obj", obj.as_bytes(), name, "t.obj").unwrap();
        let (a, b) = (space(&cut), space(&mesh));
        let sizes = |s: &DesignSpace| {
            let mut n: Vec<usize> = (0..s.model().names.len())
                .map(|t| s.model().tier_of.iter().filter(|&&x| x == t).count())
                .collect();
            n.sort_unstable();
            n
        };
        assert_eq!(sizes(&a), sizes(&b), "{name}");
        assert_eq!(a.keys().len(), b.keys().len(), "{name}");
        assert_eq!(a.meets().len(), b.meets().len(), "{name}");
        let again = b.build(name, &BTreeMap::new()).unwrap();
        same_vertices(&b.base().solid, &again.solid, 1e-9);
    }
}

#[test]
fn an_index_just_past_the_gears_zero_stays_itself() {
    use crate::design::Gear;
    use crate::geometry::facet_normal;
    let g = Gear {
        teeth: 96.0,
        offset: 0.0,
    };
    // Index i is azimuth −90° + 3.75° i: 0.0745 of a tooth past index 0 (= 96) stays 0.0745;
    // within 1e-6 of a tooth either side it is 96, as GemCad writes index 0.
    for (i, want) in [
        (0.0745, 0.0745),
        (95.93, 95.93),
        (1e-8, 96.0),
        (96.0 - 1e-8, 96.0),
        (48.0, 48.0),
    ] {
        let n = facet_normal(40.0, -90.0 + 3.75 * i, true);
        assert!((g.index(n) - want).abs() < 1e-9, "{i}: {}", g.index(n));
    }
}

/// A 57-facet brilliant for quartz whose eight pavilion mains are cut as two tiers, `P1` and
/// `P1b`, at one angle and depth: they meet at the culet, so neither turns alone (the culet
/// would open) and both, tied, do: the bundled example `optim/quartz-split.asc`.
pub(crate) const SPLIT: &str = include_str!("../../optim/quartz-split.asc");

fn split() -> DesignSpace {
    let cut = crate::io::asc::parse(SPLIT.as_bytes(), "split.asc")
        .unwrap()
        .to_cut("split")
        .unwrap();
    DesignSpace::new(&cut, MEET_TOL, OpenMeets::Refuse).unwrap()
}

/// Every meet of `space` is a point of `cut`'s planes by brute force: its facets (by name) all
/// pass through one vertex of the solid within 1e-9 of W.
fn meets_kept_by_brute_force(space: &DesignSpace, cut: &Cut) {
    let brute = brute_vertices(&cut.solid.facet_planes());
    for meet in space.meets() {
        let names: BTreeSet<String> = meet
            .facets
            .iter()
            .map(|&f| space.model().solid.facets()[f].name.clone())
            .collect();
        assert!(
            brute.iter().any(|(_, on)| names.is_subset(on)),
            "meet {names:?} is open"
        );
    }
}

#[test]
fn a_rigid_pair_of_tiers_turns_as_a_tie_and_not_alone() {
    let space = split();
    // Alone, either main tier opens the culet; the refusal names the tie that keeps it.
    for key in ["P1", "P1b"] {
        let e = space
            .build("s", &BTreeMap::from([(key.to_string(), 42.0)]))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("P1·P1b") && e.contains("tie it: `P1+P1b`") && e.contains("-1.00°"),
            "{e}"
        );
        assert_eq!(space.tie_for(key, 42.0).as_deref(), Some("P1+P1b"));
    }
    // Tied, by one change or to one angle: the same cut, every meet kept, the same design.
    let together = space
        .build("s", &BTreeMap::from([("P1+P1b".to_string(), -1.0)]))
        .unwrap();
    let equal = space
        .build("s", &BTreeMap::from([("P1=P1b".to_string(), 42.0)]))
        .unwrap();
    assert_eq!(
        (together.params["P1"], together.params["P1b"]),
        (42.0, 42.0)
    );
    same_facets(&together.solid, &equal.solid, 1e-12);
    assert!(
        space.gaps(&together).iter().all(|g| *g <= super::KEPT),
        "{:?}",
        space.gaps(&together)
    );
    meets_kept_by_brute_force(&space, &together);
    assert_eq!(
        together.solid.facets().len(),
        space.base().solid.facets().len()
    );
    assert_eq!(adjacency(&together.solid), adjacency(&space.base().solid));
    // The tie is a parameter like any other: its range keeps both tiers in (0, 90), its
    // default is no change; a tier may not be in two ties, nor an unknown tier in one.
    let r = space.range("P1+P1b").unwrap();
    assert_eq!((r.default, r.min, r.max), (0.0, -43.0, 47.0));
    assert_eq!(space.range("P1=P1b").unwrap().default, 43.0);
    let e = space
        .complete(&BTreeMap::from([
            ("P1+P1b".to_string(), 0.5),
            ("P1b=C1".to_string(), 40.0),
        ]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("tier P1b is also in `P1+P1b`"), "{e}");
    let e = space
        .complete(&BTreeMap::from([("P1+Z".to_string(), 0.5)]))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("P1+Z:") && e.contains("no tier `Z`"), "{e}");
    assert!(space
        .complete(&BTreeMap::from([("P1+P1b".to_string(), 50.0)]))
        .is_err());
    // The free-range probe: tied, nothing opens; alone, the culet.
    assert!(space
        .unkeepable(&[("P1+P1b".into(), -2.0, 0.5)])
        .unwrap()
        .is_empty());
    let opened = space.unkeepable(&[("P1".into(), 41.0, 43.5)]).unwrap();
    assert!(
        opened.iter().any(|o| o.name.starts_with("P1·P1b at (")),
        "{opened:?}"
    );
    assert!(
        opened.iter().all(|o| o.by == vec!["P1".to_string()]),
        "{opened:?}"
    );
}

#[test]
fn the_tie_found_is_the_smallest_that_keeps_the_meets() {
    // A square crown of two tiers meeting at an apex over a girdle: the tie is A+B.
    let asc = "g 96 0.0\na -90 0.5 96 24 48 72 n G\na 40 0.35969603 96 48 n A\n\
               a 40 0.35969603 24 72 n B\na 0 -0.3 96 n U\n";
    let cut = crate::io::asc::parse(asc.as_bytes(), "p")
        .unwrap()
        .to_cut("p")
        .unwrap();
    let space = DesignSpace::new(&cut, MEET_TOL, OpenMeets::Refuse).unwrap();
    assert_eq!(space.tie_for("A", 41.0).as_deref(), Some("A+B"));
    assert_eq!(space.tie_for("B", 39.0).as_deref(), Some("A+B"));
    // A tier that turns alone needs no tie.
    assert_eq!(split().tie_for("C1", 41.0), None);
    // The split brilliant's tie has two tiers, and no single other tier than P1b helps P1.
    let space = split();
    for other in ["P2", "C1", "C2", "C3"] {
        let key = format!("P1+{other}");
        assert!(
            space
                .build("s", &BTreeMap::from([(key.clone(), -1.0)]))
                .is_err(),
            "{key} keeps the culet"
        );
    }
}

#[test]
fn a_free_range_where_a_facet_vanishes_is_found_with_its_angle() {
    // The split brilliant's crown mains C1 alone: somewhere below 40° a facet or an edge goes.
    let space = split();
    let start = space.defaults();
    let b = space.breaches(&[("C1".into(), 20.0, 44.0)], &start);
    assert_eq!(b.len(), 1, "{b:?}");
    let b = &b[0];
    assert!(
        b.at < 40.0 && b.holds.0 > b.at && b.holds.0 - b.at <= 0.0051,
        "{b:?}"
    );
    // Independently, by brute force: the base's facets all touch the solid at the bound that
    // holds, and at the angle found some facet's plane no longer does, or the edges differ.
    let touching = |angle: f64| -> (usize, BTreeSet<(String, String)>) {
        let planes = {
            // Built with the open-meets rule off and no adjacency check: the raw planes.
            let r = space.model().reangled(&{
                let mut a = vec![None; space.model().names.len()];
                let t = space.model().names.iter().position(|n| n == "C1").unwrap();
                a[t] = Some(angle);
                a
            });
            r.unwrap().planes
        };
        let brute = brute_vertices(&planes);
        let on: BTreeSet<&String> = brute.iter().flat_map(|(_, on)| on.iter()).collect();
        let pairs = match Polyhedron::from_planes(&planes) {
            Ok(s) => super::reangle::adjacency_over(&s, MEET_TOL),
            Err(_) => BTreeSet::new(),
        };
        (on.len(), pairs)
    };
    let (n_ok, adj_ok) = touching(b.holds.0);
    let (n_bad, adj_bad) = touching(b.at);
    let all = space.base().solid.facets().len();
    assert_eq!(n_ok, all);
    assert_eq!(
        adj_ok,
        super::reangle::adjacency_over(&space.base().solid, MEET_TOL)
    );
    assert!(
        n_bad < all || adj_bad != adj_ok,
        "{b:?}: nothing changed at {}",
        b.at
    );
    // A range that holds throughout has no breach; a tie walks like a tier.
    assert!(space
        .breaches(&[("C1".into(), 39.0, 41.0)], &start)
        .is_empty());
    assert!(space
        .breaches(&[("P1+P1b".into(), -1.0, 0.5)], &start)
        .is_empty());
}
