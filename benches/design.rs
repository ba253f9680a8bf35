//! The design path's own cost: adopting a design's meets (`DesignSpace::new`) and building it
//! at new tier angles (`CutSpace::build`: the depth solve, the solid, the adjacency check),
//! against a full default score of the same cut. Run: `cargo bench --bench design`.
//!
//! Each design is a bundled preset written to `.asc` and read back, so it is what a faceter's
//! file gives; the build turns every tier by +0.3°. Then the checks a design config costs
//! before its search: loading `optim/design-quartz.toml` and `optim/design-tied.toml` with
//! their free ranges walked (the default) and with `facet_changes = "skip"`, and the smallest
//! tie found for a tier that cannot turn alone.

mod common;

use common::median;
use facetlab::cut::CutSpace;
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
}
