//! The design path's own cost: adopting a design's meets (`DesignSpace::new`) and building it
//! at new tier angles (`CutSpace::build`: the depth solve, the solid, the adjacency check),
//! against a full default score of the same cut. Run: `cargo bench --bench design`.
//!
//! Each design is a bundled preset written to `.asc` and read back, so it is what a faceter's
//! file gives; the build turns every tier by +0.3°. Then the checks a design config costs
//! before its search: loading `optim/design-quartz.toml` and `optim/design-tied.toml` with
//! their free ranges walked (the default) and with `facet_changes = "skip"`, and the smallest
//! tie found for a tier that cannot turn alone.
//!
//! Recipes (issue 53): building a recipe tier by tier — the bundled round brilliant
//! (`cuts/recipes/srb.toml`) and a 100-tier recipe (a 96-facet girdle cut one tier per index,
//! mains, pavilion halves, crown and table; target ≤ 50 ms) — and inferring a recipe from a
//! design (`--from`).

mod common;

use common::median;
use facetlab::cut::CutSpace;
use facetlab::design::recipe::{infer, Place, Recipe, RecipeTier};
use facetlab::design::{DesignSpace, OpenMeets, MEET_TOL};
use facetlab::metrics::{score, ScoreConfig};
use std::collections::BTreeMap;

fn main() {
    println!(
        "{:<14} {:>6} {:>6} {:>11} {:>11} {:>11} {:>8}",
        "design", "facets", "meets", "adopt (ms)", "build (ms)", "score (ms)", "build/score"
    );
    for name in ["tolkowsky", "princess", "emerald", "oval", "cushion"] {
        let cut = facetlab::io::load_cut(name).expect("preset");
        let text = facetlab::io::asc::write(&cut, 96);
        let cut = facetlab::io::asc::parse(text.as_bytes(), "bench.asc")
            .and_then(|d| d.to_cut(name))
            .expect("asc round trip");
        let adopt = median(21, || {
            DesignSpace::new(&cut, MEET_TOL, OpenMeets::Allow).expect("adopts");
        });
        let space = DesignSpace::new(&cut, MEET_TOL, OpenMeets::Allow).expect("adopts");
        let turned: BTreeMap<String, f64> = space
            .keys()
            .iter()
            .map(|k| (k.to_string(), space.range(k).unwrap().default + 0.3))
            .collect();
        let build = median(21, || {
            let _ = space.build(name, &turned);
        });
        let config = ScoreConfig::default();
        let scored = median(5, || {
            score(&space.base().solid, &config);
        });
        println!(
            "{name:<14} {:>6} {:>6} {:>11.3} {:>11.3} {:>11.1} {:>8.3}",
            cut.solid.facets().len(),
            space.meets().len(),
            adopt * 1e3,
            build * 1e3,
            scored * 1e3,
            build / scored
        );
    }
    let optim = concat!(env!("CARGO_MANIFEST_DIR"), "/optim");
    for name in ["design-quartz", "design-tied"] {
        let path = format!("{optim}/{name}.toml");
        let text = std::fs::read_to_string(&path).expect("bundled config");
        let skip = text.replacen("[cut]", "[cut]\nfacet_changes = \"skip\"", 1);
        let walked = median(5, || {
            facetlab::optimize::Config::from_str(&text, &path).expect("loads");
        });
        let skipped = median(5, || {
            facetlab::optimize::Config::from_str(&skip, &path).expect("loads");
        });
        println!(
            "{name}.toml: loaded with its free ranges walked {:.1} ms, without {:.1} ms (walk {:.1} ms)",
            walked * 1e3,
            skipped * 1e3,
            (walked - skipped) * 1e3
        );
    }
    let split = facetlab::io::load_cut(&format!("{optim}/quartz-split.asc")).expect("design");
    let space = DesignSpace::new(&split, MEET_TOL, OpenMeets::Refuse).expect("adopts");
    let tie = median(5, || {
        assert_eq!(space.tie_for("P1", 42.0).as_deref(), Some("P1+P1b"));
    });
    println!(
        "quartz-split.asc: the tie for P1 found in {:.1} ms",
        tie * 1e3
    );
    recipes();
}

/// A 100-tier recipe: mains to the centre point, 96 girdle tiers of one facet each (one per
/// index), pavilion halves meeting the mains and the girdle, crown mains leaving a girdle,
/// a table.
fn hundred_tiers() -> Recipe {
    let mut r = Recipe::new("hundred", 96, 1, false, 1.54);
    let mains: Vec<f64> = (0..16).map(|k| 3.0 + 6.0 * f64::from(k)).collect();
    r.add(RecipeTier::new("P1", -42.5, &mains, Place::Centre));
    for i in 1..=96 {
        r.add(RecipeTier::new(
            &format!("G{i}"),
            90.0,
            &[f64::from(i)],
            Place::Depth(1.2),
        ));
    }
    r.add(RecipeTier::new("C1", 34.0, &mains, Place::Girdle(0.02)));
    r.add(RecipeTier::new("T", 0.0, &[], Place::Table(0.55)));
    let halves: Vec<f64> = (1..=8).map(|k| 12.0 * f64::from(k)).collect();
    r.add(RecipeTier::new(
        "P2",
        -41.5,
        &halves,
        Place::Meet(vec!["P1".into(), "G96".into()]),
    ));
    r
}

fn recipes() {
    println!(
        "\n{:<22} {:>6} {:>6} {:>11}",
        "recipe", "tiers", "facets", "build (ms)"
    );
    let srb = concat!(env!("CARGO_MANIFEST_DIR"), "/cuts/recipes/srb.toml");
    let text = std::fs::read_to_string(srb).expect("bundled recipe");
    let srb = facetlab::io::recipe::parse(&text, "srb.toml", "srb").expect("parses");
    for (name, r) in [
        ("cuts/recipes/srb.toml", srb),
        ("100 tiers", hundred_tiers()),
    ] {
        let facets = r.build().expect("builds").cut.solid.facets().len();
        let t = median(11, || {
            r.build().expect("builds");
        });
        println!(
            "{name:<22} {:>6} {facets:>6} {:>11.2}",
            r.tiers.len(),
            t * 1e3
        );
    }
    for name in ["tolkowsky", "emerald", "oval"] {
        let cut = facetlab::io::load_cut(name).expect("preset");
        let t = median(11, || {
            infer(&cut).expect("infers");
        });
        println!(
            "infer {name:<16} {:>6} {:>6} {:>11.2}",
            infer(&cut).unwrap().recipe.tiers.len(),
            cut.solid.facets().len(),
            t * 1e3
        );
    }
}
