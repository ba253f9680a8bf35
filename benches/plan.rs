//! Rough planning's cost (issue 26's targets): the containment program on the example rough
//! (`cuts/rough-octahedron.obj`, 2,048 triangles; its hull's planes) for a round brilliant
//! (target ≤ 1 ms), and whole plans over one family and over every default family with the
//! default search (12 starts; targets ≤ 20 s and ≤ 60 s), and the top 3 in symmetric
//! crystals (cube, octahedron) and the sphere; then a scanned pebble of 401,408 triangles
//! (`facetlab::plan::sample::scanned_pebble`, made here): its full convex hull (target ≤ 1 s),
//! the rough as the planner takes it (its hull stopped at `HULL_VERTICES`), and a plan of one
//! family (target ≤ 10 s), beside the example rough's in the same run; then layouts (issue
//! 54): 3 stones with two inclusions in the example rough, one family and every default family
//! (target ≤ 30 s on 2 cores), the same with a laser (one family), and 3 stones in the scanned
//! pebble. Run:
//! `cargo bench --bench plan` (`-- scan` for the scanned pebble alone, `-- hull` for its hull,
//! `-- layout` for the layouts alone; `FACETLAB_LAYOUTS=one,all,laser,pebble` picks some of
//! the layouts, all by default).

use facetlab::cut::Cut;
use facetlab::geometry::{hull, HullOptions};
use facetlab::plan::sample::{distorted_octahedron, scanned_pebble};
use facetlab::plan::{largest_copy, Cutter, Inclusion, LayoutPlanner, PlanConfig, Planner, Rough};
use glam::{DQuat, DVec3};
use std::collections::BTreeMap;
use std::time::Instant;

fn main() {
    if std::env::args().any(|a| a == "layout") {
        layout();
        return;
    }
    let scan_only = std::env::args().any(|a| a == "scan" || a == "hull");
    if !scan_only {
        small();
    }
    scan();
    if !scan_only {
        layout();
    }
}

/// A tetrahedron of size `r` mm at `c` (an inclusion's points).
fn speck(c: DVec3, r: f64) -> Vec<DVec3> {
    [
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ]
    .iter()
    .map(|p| c + r * DVec3::from_array(*p))
    .collect()
}

/// Layouts of 3 stones: the example rough with two inclusions (one family, every default
/// family), and the scanned pebble (one family).
fn layout() {
    let rough = Rough::from_trimesh("rough-octahedron", "bench", distorted_octahedron(16), None)
        .expect("example rough");
    let c = rough.solid.centroid();
    let inclusions = vec![
        Inclusion::from_points("a", "a", &speck(c + DVec3::new(0.4, 0.3, 0.5), 0.2), 0.3)
            .expect("inclusion"),
        Inclusion::from_points("b", "b", &speck(c + DVec3::new(-0.6, 0.2, -0.8), 0.15), 0.3)
            .expect("inclusion"),
    ];
    let mut config = PlanConfig {
        stones: 3,
        ..PlanConfig::default()
    };
    let picked = std::env::var("FACETLAB_LAYOUTS").unwrap_or_default();
    let wants = |name: &str| picked.is_empty() || picked.split(',').any(|p| p.trim() == name);
    let families = config.families.clone();
    for (name, fams) in [
        ("one", vec!["round-brilliant".to_string()]),
        ("all", families),
    ] {
        if !wants(name) {
            continue;
        }
        config.families = fams;
        let t = Instant::now();
        let l = LayoutPlanner::new(&rough, &config, 3.515, &inclusions)
            .plan(&|| {})
            .expect("layout");
        println!(
            "layout 3 stones, 2 inclusions, {} families: {:.2} s (target ≤ 30 s, {} threads), {} stones {:.4} ct, yield {:.2} %, kerf loss {:.2} mm³",
            config.families.len(),
            t.elapsed().as_secs_f64(),
            rayon::current_num_threads(),
            l.stones.len(),
            l.carats,
            100.0 * l.yield_fraction,
            l.kerf_loss_mm3
        );
    }
    config.families = vec!["round-brilliant".into()];
    if wants("laser") {
        laser(&rough, &config, &inclusions);
    }
    if wants("pebble") {
        pebble(&config);
    }
}

/// The example rough's layout with a laser (one family): the sawn layout, then its stones
/// regrown.
fn laser(rough: &Rough, config: &PlanConfig, inclusions: &[Inclusion]) {
    let mut config = config.clone();
    config.cutter = Cutter::Laser;
    let t = Instant::now();
    let l = LayoutPlanner::new(rough, &config, 3.515, inclusions)
        .plan(&|| {})
        .expect("layout");
    println!(
        "laser layout 3 stones, 2 inclusions, 1 family: {:.2} s, {} stones {:.4} ct, yield {:.2} %, kerf loss {:.2} mm³",
        t.elapsed().as_secs_f64(),
        l.stones.len(),
        l.carats,
        100.0 * l.yield_fraction,
        l.kerf_loss_mm3
    );
}

/// 3 stones of one family in the scanned pebble.
fn pebble(config: &PlanConfig) {
    let t = Instant::now();
    let mesh = scanned_pebble(224, 1);
    let triangles = mesh.triangles.len();
    let pebble = Rough::from_trimesh("pebble", "bench", mesh, None).expect("rough");
    let read_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let l = LayoutPlanner::new(&pebble, config, 3.515, &[])
        .plan(&|| {})
        .expect("layout");
    println!(
        "layout 3 stones in the scanned pebble ({triangles} triangles, made and read in {read_s:.2} s): {:.2} s, {} stones {:.4} ct, yield {:.2} %",
        t.elapsed().as_secs_f64(),
        l.stones.len(),
        l.carats,
        100.0 * l.yield_fraction
    );
}

/// The scanned pebble: its hull, the rough the planner takes, and one family planned.
fn scan() {
    let t = Instant::now();
    let mesh = scanned_pebble(224, 1);
    println!(
        "scanned pebble: {} triangles, {} vertices, made in {:.2} s",
        mesh.triangles.len(),
        mesh.vertices.len(),
        t.elapsed().as_secs_f64()
    );
    // Best of three: the machine is shared.
    let mut full_s = f64::INFINITY;
    let mut full = None;
    for _ in 0..3 {
        let t = Instant::now();
        full = Some(hull(&mesh.vertices, HullOptions::default()).expect("hull"));
        full_s = full_s.min(t.elapsed().as_secs_f64());
    }
    let full = full.expect("hull");
    println!(
        "full convex hull: {:.3} s (best of 3), {} vertices, {} planes (target ≤ 1 s)",
        full_s,
        full.vertices,
        full.planes.len()
    );
    if std::env::args().any(|a| a == "hull") {
        return;
    }
    let t = Instant::now();
    let rough = Rough::from_trimesh("pebble", "bench", mesh, None).expect("rough");
    println!(
        "rough (closed check, volume, hull of {} vertices, solid of {} planes): {:.3} s; the farthest vertex left out {:.2} µm outside, the hull's volume {:+.4} % of the mesh's",
        rough.hull_vertices,
        rough.solid.facets().len(),
        t.elapsed().as_secs_f64(),
        1000.0 * rough.left_out,
        100.0 * (rough.volume() / rough.mesh_volume.unwrap_or(f64::NAN) - 1.0)
    );
    let config = PlanConfig::default();
    let planner = Planner::new(&rough, &config, 3.515);
    let t = Instant::now();
    let best = planner
        .plan_family("round-brilliant", &|| {})
        .expect("plans");
    let scan_s = t.elapsed().as_secs_f64();
    // The example rough's plan in the same minutes, for a ratio.
    let example = Rough::from_trimesh("rough-octahedron", "bench", distorted_octahedron(16), None)
        .expect("example rough");
    let small_planner = Planner::new(&example, &config, 3.515);
    let t = Instant::now();
    small_planner
        .plan_family("round-brilliant", &|| {})
        .expect("plans");
    let small_s = t.elapsed().as_secs_f64();
    println!(
        "plan round-brilliant in the pebble ({} starts): {:.2} s (target ≤ 10 s; {:.2}× the example rough's {:.2} s), best {:.4} ct, yield {:.2} %",
        config.starts,
        scan_s,
        scan_s / small_s,
        small_s,
        best[0].carats,
        100.0 * best[0].yield_fraction
    );
}

/// The example rough: the containment program, one family, every family, the crystals.
fn small() {
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
