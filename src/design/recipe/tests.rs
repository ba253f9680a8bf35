//! Recipes: the bundled designs rebuilt from inferred recipes, placements against closed
//! forms, and every error a faceter should understand.

use super::*;
use crate::cut::Cut;
use crate::geometry::Polyhedron;

/// Whether two solids have the same facet planes (each plane of one within 1e-9 of a plane
/// of the other) and volumes within 1e-9.
pub(crate) fn same_solid(a: &Polyhedron, b: &Polyhedron) -> std::result::Result<(), String> {
    if a.facets().len() != b.facets().len() {
        return Err(format!(
            "{} facets against {}",
            a.facets().len(),
            b.facets().len()
        ));
    }
    for f in a.facets() {
        let found = b.facets().iter().any(|g| {
            f.plane.normal.distance(g.plane.normal) < 1e-9
                && (f.plane.offset - g.plane.offset).abs() < 1e-9
        });
        if !found {
            return Err(format!("facet {} ({:?}) has no twin", f.name, f.plane));
        }
    }
    let (va, vb) = (a.volume(), b.volume());
    if (va - vb).abs() > 1e-9 {
        return Err(format!("volume {va} against {vb}"));
    }
    Ok(())
}

fn round_trip(cut: &Cut) -> Inferred {
    let inf = infer(cut).unwrap_or_else(|e| panic!("{}: {e}", cut.name));
    let text = crate::io::recipe::write(&inf.recipe);
    let back = crate::io::recipe::parse(&text, "r.toml", "r").unwrap();
    assert_eq!(
        back, inf.recipe,
        "{}: the TOML reads back to the same recipe",
        cut.name
    );
    let built = back
        .build()
        .unwrap_or_else(|e| panic!("{}: {e}\n{text}", cut.name));
    if let Err(e) = same_solid(&built.cut.solid, &cut.solid) {
        panic!("{}: {e}\n{text}", cut.name);
    }
    inf
}

#[test]
fn every_preset_rebuilds_from_its_inferred_recipe() {
    for name in crate::io::presets::names() {
        let cut = crate::io::presets::load(name).unwrap().unwrap();
        let inf = round_trip(&cut);
        eprintln!("{name}: {}", inf.notes.join("; "));
    }
}

/// GemCad designs as faceters write them (two written for the `.asc` reader's tests, a
/// 96-gear brilliant and an 80-gear five-fold star, and the two quartz designs of `optim/`)
/// rebuild from their inferred recipes, tiers named as in the file.
#[test]
fn gemcad_designs_rebuild_from_their_inferred_recipes() {
    use crate::testkit::asc::{MINI, STAR80};
    let mut cuts: Vec<Cut> = [("mini", MINI), ("star80", STAR80)]
        .iter()
        .map(|(n, t)| {
            crate::io::asc::parse(t.as_bytes(), n)
                .unwrap()
                .to_cut(n)
                .unwrap()
        })
        .collect();
    for f in ["quartz-brilliant", "quartz-split"] {
        let path = format!("{}/optim/{f}.asc", env!("CARGO_MANIFEST_DIR"));
        cuts.push(crate::io::load_cut(&path).unwrap());
    }
    for cut in &cuts {
        let inf = round_trip(cut);
        let names: Vec<&str> = inf.recipe.tiers.iter().map(|t| t.name.as_str()).collect();
        let record = cut.record.as_ref().unwrap();
        assert_eq!(inf.recipe.gear as f64, record.gear.abs(), "{}", cut.name);
        assert!(
            !inf.notes.iter().any(|n| n.contains("renamed")),
            "{}: {names:?}",
            cut.name
        );
        eprintln!("{}: {names:?} {}", cut.name, inf.notes.join("; "));
    }
}

/// A simple round: mains to the centre point, a level girdle on the mains' indices, crown
/// mains leaving a girdle, a table.
fn simple() -> Recipe {
    let mut r = Recipe::new("simple", 96, 8, true, 1.54);
    r.add(RecipeTier::new("P1", -42.0, &[96.0], Place::Centre));
    r.add(RecipeTier::new("G1", 90.0, &[96.0], Place::Depth(0.9)));
    r.add(RecipeTier::new("C1", 38.0, &[96.0], Place::Girdle(0.03)));
    r.add(RecipeTier::new("T", 0.0, &[], Place::Table(0.55)));
    r
}

fn err(r: &Recipe) -> String {
    r.build().map(|_| ()).unwrap_err().to_string()
}

/// Each placement does what it says, measured on the built solid: the mains meet in one
/// point on the axis; the girdle left is `girdle` of the width between the pavilion's highest
/// and the crown's lowest point on it; the table is `table` of the width (T/W); a meet
/// passes through a vertex of the named tiers; an angle expression equals its value; the
/// recipe's units do not matter.
#[test]
fn placements_do_what_they_say() {
    let b = simple().build().unwrap();
    let s = &b.cut.solid;
    let on = |tier: &str, p: crate::geometry::DVec3| {
        s.facets()
            .iter()
            .filter(|f| f.tier == tier && f.plane.distance(p).abs() < 1e-9)
            .count()
    };
    let apex = s
        .vertices()
        .iter()
        .find(|v| on("P1", **v) == 8)
        .expect("the mains meet in one point");
    assert!(apex.x.abs() < 1e-12 && apex.y.abs() < 1e-12, "{apex:?}");
    let girdle: Vec<_> = s.vertices().iter().filter(|v| on("G1", **v) > 0).collect();
    let pav_top = girdle
        .iter()
        .filter(|v| on("P1", ***v) > 0)
        .map(|v| v.z)
        .fold(f64::MIN, f64::max);
    let crown_low = girdle
        .iter()
        .filter(|v| on("C1", ***v) > 0)
        .map(|v| v.z)
        .fold(f64::MAX, f64::min);
    assert!(
        (crown_low - pav_top - 0.03).abs() < 1e-9,
        "{crown_low} - {pav_top}"
    );
    assert!((b.cut.ratios().t_w - 0.55).abs() < 1e-9);
    // GemCad's standard round brilliant as its user's guide cuts it: mains to the centre
    // point, girdle, pavilion halves to meet, crown halves leaving a girdle, bezels (at an
    // expression of the halves' angle) meeting two girdle facets, stars meeting two crown
    // halves, the table meeting bezels and stars. Each meet leaves a vertex on the tier and
    // on the tiers named (as often as named).
    let mut r = Recipe::new("srb", 96, 8, true, 1.54);
    let meet = |m: &[&str]| Place::Meet(m.iter().map(|s| s.to_string()).collect());
    r.add(RecipeTier::new("1", -42.5, &[3.0], Place::Centre));
    r.add(RecipeTier::new("G", 90.0, &[3.0], Place::Scale(1.2)));
    r.add(RecipeTier::new("2", -41.5, &[96.0], meet(&["1", "G"])));
    r.add(RecipeTier::new("A", 34.0, &[3.0], Place::Girdle(0.015)));
    let mut bezel = RecipeTier::new("B", 0.0, &[96.0], meet(&["G", "G"]));
    bezel.angle = Angle::Expr("=A-6".into());
    r.add(bezel);
    r.add(RecipeTier::new("C", 16.0, &[6.0], meet(&["A", "A"])));
    r.add(RecipeTier::new("T", 0.0, &[], meet(&["B", "C"])));
    let b = r.build().unwrap();
    let s = &b.cut.solid;
    assert_eq!(s.facets().len(), 73);
    for t in &r.tiers {
        let Place::Meet(named) = &t.place else {
            continue;
        };
        let hit = s.vertices().iter().any(|v| {
            let on = |tier: &str| {
                s.facets()
                    .iter()
                    .filter(|f| f.tier == tier && f.plane.distance(*v).abs() < 1e-9)
                    .count()
            };
            on(&t.name) > 0
                && named
                    .iter()
                    .all(|n| on(n) >= named.iter().filter(|m| *m == n).count())
        });
        assert!(hit, "{} passes through a vertex of {named:?}", t.name);
    }
    let bezel = b.steps.iter().find(|s| s.tier == "B").unwrap();
    assert!((bezel.angle - 28.0).abs() < 1e-12, "{bezel:?}");
    assert_eq!(bezel.indices.len(), 8);
    assert_eq!(bezel.instruction, "meet G-G");
    // The same solid whatever the recipe's units: every absolute depth doubled.
    let mut c = simple();
    c.tiers[0].place = Place::Depth(42f64.to_radians().cos());
    let a = c.build().unwrap().cut.solid;
    c.tiers[0].place = Place::Depth(2.0 * 42f64.to_radians().cos());
    c.tiers[1].place = Place::Depth(1.8);
    same_solid(&a, &c.build().unwrap().cut.solid).unwrap();
    same_solid(&a, &simple().build().unwrap().cut.solid).unwrap();
}

/// A recipe turned on its gear (every index and the offset moved by the same teeth) is the
/// same stone turned: the same volume and ratios.
#[test]
fn a_recipe_turned_on_its_gear_is_the_same_stone() {
    let a = simple().build().unwrap().cut;
    let mut r = simple();
    r.offset = 5.0;
    for t in &mut r.tiers {
        for x in &mut t.indices {
            *x = (*x + 5.0) % 96.0;
        }
    }
    let b = r.build().unwrap().cut;
    assert!((a.solid.volume() - b.solid.volume()).abs() < 1e-12);
    let (ra, rb) = (a.ratios(), b.ratios());
    assert!((ra.h_w - rb.h_w).abs() < 1e-12 && (ra.t_w - rb.t_w).abs() < 1e-12);
}

/// Every error a faceter should understand: one line naming the tier, with the fix where
/// one is obvious (and the fix works).
#[test]
fn errors_name_the_tier_and_the_fix() {
    // A tier that never touches the stone.
    let mut r = simple();
    r.tiers
        .insert(2, RecipeTier::new("P2", -45.0, &[6.0], Place::Depth(5.0)));
    let e = err(&r);
    assert!(e.starts_with("tier P2: never touches"), "{e}");
    // A tier cut away entirely by a later one, and the angle that keeps it.
    let mut r = simple();
    r.tiers.pop();
    r.add(RecipeTier::new("C2", 30.0, &[96.0], Place::Girdle(0.02)));
    let e = err(&r);
    assert!(e.contains("tier C1 is cut away entirely by C2"), "{e}");
    assert!(e.contains(" C2 to "), "{e}");
    let fix: f64 = e
        .split("C2 to ")
        .nth(1)
        .and_then(|t| t.split('°').next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("no fix in {e}"));
    r.tiers[3].angle = Angle::Degrees(fix);
    let after = r.build().map(|_| ()).map_err(|e| e.to_string());
    assert!(
        after.as_ref().err().is_none_or(|e| !e.contains("cut away")),
        "the suggested {fix}° keeps C1: {after:?}"
    );
    // A meet naming a tier not cut yet; a meet whose tiers do not meet.
    let mut r = simple();
    r.tiers[2].place = Place::Meet(vec!["P1".into(), "T".into()]);
    assert!(
        err(&r).contains("T, which is not a tier cut before C1"),
        "{}",
        err(&r)
    );
    r.tiers[2].place = Place::Meet(vec!["P1".into(), "P1".into(), "P1".into(), "G1".into()]);
    let e = err(&r);
    assert!(e.contains("tier C1") && e.contains("do not meet"), "{e}");
    // A first tier with nothing to anchor it.
    let mut r = simple();
    r.tiers[0].place = Place::Meet(vec!["G1".into()]);
    assert!(err(&r).contains("nothing to meet"), "{}", err(&r));
    // Open stones: no crown, no pavilion, a tier that does not go around.
    let mut r = simple();
    r.tiers.truncate(2);
    assert!(err(&r).contains("open above"), "{}", err(&r));
    let mut r = Recipe::new("side", 96, 1, false, 1.54);
    r.add(RecipeTier::new(
        "P1",
        -42.0,
        &[96.0, 24.0, 48.0],
        Place::Centre,
    ));
    r.add(RecipeTier::new(
        "C1",
        40.0,
        &[96.0, 24.0, 48.0],
        Place::Depth(0.3),
    ));
    r.add(RecipeTier::new("T", 0.0, &[], Place::Depth(0.1)));
    assert!(err(&r).contains("open at the side"), "{}", err(&r));
    let mut r = Recipe::new("up", 96, 8, true, 1.54);
    r.add(RecipeTier::new("G1", 90.0, &[96.0], Place::Depth(1.0)));
    r.add(RecipeTier::new("C1", 40.0, &[96.0], Place::Depth(1.0)));
    assert!(err(&r).contains("open below"), "{}", err(&r));
    // No centre point yet on the pavilion.
    let mut r = Recipe::new("c", 96, 8, true, 1.54);
    r.add(RecipeTier::new("G1", 90.0, &[96.0], Place::Depth(1.0)));
    r.add(RecipeTier::new("P1", -41.0, &[96.0], Place::Centre));
    assert!(
        err(&r).contains("no centre point on the pavilion"),
        "{}",
        err(&r)
    );
    // Indices off the gear.
    let mut r = simple();
    r.tiers[2].indices = vec![3.5];
    let e = err(&r);
    assert!(
        e.contains("tier C1") && e.contains("off the 96 gear") && e.contains("3 or 4"),
        "{e}"
    );
    r.tiers[2].indices = vec![97.0];
    assert!(err(&r).contains("off the 96 gear"));
    r.fractional = true;
    r.tiers[2].indices = vec![3.5];
    assert!(r.build().is_ok());
    // A table width on a sloping tier; a girdle thickness with no girdle.
    let mut r = simple();
    r.tiers[2].place = Place::Table(0.5);
    assert!(
        err(&r).contains("tier C1: a table width places a flat crown tier"),
        "{}",
        err(&r)
    );
    let mut r = simple();
    r.tiers.remove(1);
    assert!(err(&r).contains("needs a girdle tier"), "{}", err(&r));
    // Design-level: a symmetry that does not divide the gear.
    let mut r = simple();
    r.symmetry = 5;
    assert!(err(&r).starts_with("symmetry"), "{}", err(&r));
}

/// Findings: a pavilion below the critical angle (with the angle that fixes it) and a facet
/// under 1 % of the width.
#[test]
fn findings_name_leaks_and_tiny_facets() {
    let mut r = simple();
    r.tiers[0].angle = Angle::Degrees(-38.0);
    let b = r.build().unwrap();
    let f = b
        .findings
        .iter()
        .find(|f| f.kind == FindingKind::BelowCritical)
        .expect("a leak");
    assert!(
        f.message.contains("tier P1") && f.message.contains("40.49"),
        "{}",
        f.message
    );
    let fix: f64 = f
        .message
        .split("steepen P1 to ")
        .nth(1)
        .and_then(|t| t.split('°').next())
        .and_then(|t| t.parse().ok())
        .unwrap();
    r.tiers[0].angle = Angle::Degrees(-fix);
    let b = r.build().unwrap();
    assert!(
        !b.findings
            .iter()
            .any(|f| f.kind == FindingKind::BelowCritical),
        "{fix}"
    );
    // A culet about 0.5 % of the width: cut just above the mains' point (at 1 below the
    // girdle plane, the unit of the first tier cut to centre).
    let mut r = simple();
    let mut k = RecipeTier::new("K", 0.0, &[], Place::Depth(0.999));
    k.side = Some(Side::Pavilion);
    r.tiers.insert(2, k);
    let b = r.build().unwrap();
    let f = b
        .findings
        .iter()
        .find(|f| f.kind == FindingKind::SmallFacet)
        .expect("a tiny culet");
    assert!(f.message.starts_with("tier K: facet K is"), "{}", f.message);
}

/// The bundled recipes (`cuts/recipes/`) rebuild the bundled designs they were written for,
/// facet for facet, volume within 1e-9.
#[test]
fn bundled_recipes_rebuild_the_bundled_designs() {
    let dir = format!("{}/cuts/recipes", env!("CARGO_MANIFEST_DIR"));
    for (file, preset) in [
        ("srb", "tolkowsky"),
        ("princess", "princess"),
        ("oval", "oval"),
        ("step", "emerald"),
    ] {
        let r = crate::io::load_cut(&format!("{dir}/{file}.toml")).unwrap();
        let p = crate::io::load_cut(preset).unwrap();
        same_solid(&r.solid, &p.solid).unwrap_or_else(|e| panic!("{file}: {e}"));
    }
}
