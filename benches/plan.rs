//! Rough planning's cost (issue 26's targets): the containment program on the example rough
//! (`cuts/rough-octahedron.obj`, 2,048 triangles; its hull's planes) for a round brilliant
//! (target ≤ 1 ms), and whole plans over one family and over every default family with the
//! default search (12 starts; targets ≤ 20 s and ≤ 60 s), and the top 3 in symmetric
//! crystals (cube, octahedron) and the sphere. Run: `cargo bench --bench plan`.

use facetlab::cut::Cut;
use facetlab::plan::sample::distorted_octahedron;
use facetlab::plan::{largest_copy, PlanConfig, Planner, Rough};
use glam::{DQuat, DVec3};
use std::collections::BTreeMap;
use std::time::Instant;

fn main() {
    let rough = Rough::from_trimesh("rough-octahedron", "bench", distorted_octahedron(16), None)
        .expect("example rough");
    let planes = rough.planes();
    let inside = rough.solid.centroid();
    println!(
        "rough: 2048 triangles, hull {} planes, {:.2} mm³ (the hull adds {:.2} %)",
        planes.len(),
        rough.volume(),
        100.0 * rough.hull_excess()
    );
    for family in ["round-brilliant", "princess", "oval"] {
        let cut = Cut::from_family(family, family, &BTreeMap::new()).expect("family");
        let n = 2000;
        let t = Instant::now();
        let mut steps = 0;
        for k in 0..n {
            let turn = DQuat::from_scaled_axis(DVec3::new(0.3, -0.2, 0.1) * (k as f64 * 0.01));
            let verts: Vec<DVec3> = cut.solid.vertices().iter().map(|v| turn * *v).collect();
            steps += largest_copy(&planes, &verts, inside).expect("fits").steps;
        }
        println!(
            "LP {family:<16} {} cut vertices: {:.1} µs per program ({:.1} steps)",
            cut.solid.vertices().len(),
            1e6 * t.elapsed().as_secs_f64() / n as f64,
            steps as f64 / n as f64
        );
    }
    let config = PlanConfig::default();
    let planner = Planner::new(&rough, &config, 3.515);
    let t = Instant::now();
    let best = planner
        .plan_family("round-brilliant", &|| {})
        .expect("plans");
    println!(
        "plan round-brilliant ({} starts): {:.2} s, best {:.4} ct, yield {:.2} %",
        config.starts,
        t.elapsed().as_secs_f64(),
        best[0].carats,
        100.0 * best[0].yield_fraction
    );
    let t = Instant::now();
    for f in &config.families {
        let best = planner.plan_family(f, &|| {}).expect("plans");
        println!(
            "  {f:<16} {:.4} ct, yield {:.2} %",
            best[0].carats,
            100.0 * best[0].yield_fraction
        );
    }
    println!(
        "plan all {} default families: {:.2} s ({} threads)",
        config.families.len(),
        t.elapsed().as_secs_f64(),
        rayon::current_num_threads()
    );
    // Symmetric crystals: the starts meet copies of one optimum, so the top 3 takes further
    // rounds with the table kept away from the plans found; the sphere needs no program.
    for form in ["cube", "octahedron", "sphere"] {
        let crystal = Rough::crystal(form, 6.0).expect("form");
        let planner = Planner::new(&crystal, &config, 3.515);
        let t = Instant::now();
        let plans = planner
            .plan_family("round-brilliant", &|| {})
            .expect("plans");
        let yields: Vec<String> = plans
            .iter()
            .map(|p| format!("{:.2} %", 100.0 * p.yield_fraction))
            .collect();
        println!(
            "plan {form} (6 mm) round-brilliant, top {}: {:.2} s, {} plans: {}",
            config.top,
            t.elapsed().as_secs_f64(),
            plans.len(),
            yields.join(", ")
        );
    }
}
