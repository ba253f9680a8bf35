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
    use crate::io::asc::fixtures::{MINI, STAR80};
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
