//! The beam tracer's overhead light return against an exact reference. Run:
//! `cargo bench --bench exact` (optionally `-- STONE...` from tolkowsky, gia-reference,
//! princess, octahedron; `--n N` cells per grid side (default 1000), `--grids R` jittered grids
//! (default 4), `--pol` to add the polarized figures).
//!
//! The reference ([`facetlab::beam::reference`]) shoots `R` jittered grids of about `N²` parallel
//! rays straight down over the stone, each split deterministically at every interface until
//! less than 1e-9 of its power is left; it shares no code with the beam tracer but the optics.
//! Its standard error is the grids' spread over √R. Printed in percentage points: the reference,
//! then the beam tracer at its default settings and at finer split thresholds, the finest being
//! the one `score` uses for its overhead light return (difference from the reference, in points
//! and in standard errors, and the time of one trace).

use facetlab::beam::reference::{overhead_light_return as reference, GridOptions};
use facetlab::beam::{Medium, Stone, TraceOptions};
use facetlab::geometry::{FacetPlane, Polyhedron};
use facetlab::metrics::{overhead_light_return_with, ScoreConfig};
use facetlab::optics::Material;
use glam::DVec3;
use std::time::Instant;

fn octahedron() -> Polyhedron {
    let mut planes = Vec::new();
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            for sz in [-1.0, 1.0] {
                let k = planes.len();
                planes.push(FacetPlane::new(
                    DVec3::new(sx, sy, sz),
                    0.5 * 3f64.sqrt(),
                    format!("o{k}"),
                    "o",
                ));
            }
        }
    }
    Polyhedron::from_planes(&planes).expect("octahedron")
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let flag = |name: &str, default: usize| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let grid = GridOptions {
        n: flag("--n", 1000),
        grids: flag("--grids", 4).max(2),
        ..Default::default()
    };
    let pol = args.iter().any(|a| a == "--pol");
    let known = ["tolkowsky", "gia-reference", "princess", "octahedron"];
    let mut names: Vec<&str> = known
        .iter()
        .copied()
        .filter(|k| args.iter().any(|a| a == k))
        .collect();
    if names.is_empty() {
        names = known.to_vec();
    }
    let ri = Material::diamond().ri(589.3);
    println!(
        "overhead light return, diamond n = {ri:.5} (589.3 nm), straight-down parallel light; \
         reference: {} jittered grids of {}² rays; percentage points",
        grid.grids,
        grid.n + 1
    );
    for name in names {
        let solid = if name == "octahedron" {
            octahedron()
        } else {
            facetlab::io::load_cut(name).expect("preset").solid
        };
        let stone = Stone::new(&solid);
        for p in if pol { vec![false, true] } else { vec![false] } {
            let t0 = Instant::now();
            let r = reference(
                &solid,
                ri,
                &GridOptions {
                    polarization: p,
                    ..grid
                },
            );
            let dt = t0.elapsed().as_secs_f64();
            let mut line = format!(
                "{name:>14} {}: reference {:.4} ± {:.4} (lost {:.0e}, {:.1} s)",
                if p { "polarized  " } else { "unpolarized" },
                100.0 * r.value,
                100.0 * r.stderr,
                r.lost,
                dt
            );
            // The tracer's default, fire's face-up traces, and the score's face-up trace at
            // the reference wavelength (where `score`'s overhead light return comes from).
            let scored = ScoreConfig::default().face_up_split_threshold;
            for split in [TraceOptions::SPLIT_THRESHOLD, 1e-5, scored] {
                let opts = TraceOptions {
                    polarization: p,
                    split_threshold: split,
                    ..Default::default()
                };
                let t1 = Instant::now();
                let b = overhead_light_return_with(&stone, &Medium::Isotropic(ri), &opts);
                let bt = t1.elapsed().as_secs_f64() * 1e3;
                let tag = if split == scored { " (score)" } else { "" };
                line += &format!(
                    "; beam split {split:.0e}{tag} {:.4} ({:+.4}, {:+.1} SE, {bt:.1} ms)",
                    100.0 * b,
                    100.0 * (b - r.value),
                    (b - r.value) / r.stderr
                );
            }
            println!("{line}");
        }
    }
}
