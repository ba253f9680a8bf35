//! The library's one home of test helpers (test builds only). Here: shared test solids —
//! boxes, the cube, slabs, octahedra, the Tolkowsky preset, the GIA reference round brilliant
//! and a plane-built square brilliant. One copy here instead of one per test module.
//! `cuts.rs`: the family tests' helpers (building with overrides, tier counts, symmetry,
//! widths, parameter sweeps); `asc.rs`: the test designs of the GemCad reader's, writer's and
//! instructions' tests.
//!
//! All are centred at the origin, z up. Box faces are named `+x`, `-x`, `+y`, `-y`, `top`,
//! `bottom` (tier `side`); octahedron faces `o0`…`o7` (tier `o`), ordered by the signs of
//! their normals' (x, y, z) with x slowest, `−` before `+`.

use crate::geometry::{facet_normal, DVec3, FacetPlane, Polyhedron};

pub(crate) mod asc;
pub(crate) mod cuts;

/// The six planes of a box of half-sizes (hx, hy, hz).
pub(crate) fn box_planes(hx: f64, hy: f64, hz: f64) -> Vec<FacetPlane> {
    [
        (DVec3::X, hx, "+x"),
        (DVec3::NEG_X, hx, "-x"),
        (DVec3::Y, hy, "+y"),
        (DVec3::NEG_Y, hy, "-y"),
        (DVec3::Z, hz, "top"),
        (DVec3::NEG_Z, hz, "bottom"),
    ]
    .into_iter()
    .map(|(n, h, name)| FacetPlane::new(n, h, name, "side"))
    .collect()
}

/// A box of half-sizes (hx, hy, hz).
pub(crate) fn boxed(hx: f64, hy: f64, hz: f64) -> Polyhedron {
    Polyhedron::from_planes(&box_planes(hx, hy, hz)).unwrap()
}

/// The six planes of a cube of half-size `h`.
pub(crate) fn cube_planes(h: f64) -> Vec<FacetPlane> {
    box_planes(h, h, h)
}

/// The unit cube: edge 1, volume 1.
pub(crate) fn cube() -> Polyhedron {
    boxed(0.5, 0.5, 0.5)
}

/// A flat square slab: half-width `half_width` in x and y, thickness `2 · half_thickness`.
pub(crate) fn slab(half_width: f64, half_thickness: f64) -> Polyhedron {
    boxed(half_width, half_width, half_thickness)
}

/// A small deterministic generator of uniform numbers in [0, 1) for tests (a 64-bit linear
/// congruential generator, its top 53 bits): the same sequence for the same seed everywhere.
pub(crate) fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut seed = seed;
    move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The eight planes of the octahedron |x| + |y| + |z| ≤ `r` (vertices at distance `r`).
pub(crate) fn octahedron_planes(r: f64) -> Vec<FacetPlane> {
    let mut planes = Vec::new();
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            for sz in [-1.0, 1.0] {
                let k = planes.len();
                planes.push(FacetPlane::new(
                    DVec3::new(sx, sy, sz),
                    r,
                    format!("o{k}"),
                    "o",
                ));
            }
        }
    }
    planes
}

/// The octahedron |x| + |y| + |z| ≤ `r`.
pub(crate) fn octahedron_of(r: f64) -> Polyhedron {
    Polyhedron::from_planes(&octahedron_planes(r)).unwrap()
}

/// The tracer tests' octahedron: vertices at √3/2, on the unit cube's circumsphere.
pub(crate) fn octahedron() -> Polyhedron {
    octahedron_of(0.5 * 3f64.sqrt())
}

/// The `tolkowsky` preset's solid.
pub(crate) fn tolkowsky() -> Polyhedron {
    crate::io::load_cut("tolkowsky").unwrap().solid
}

/// The GIA reference round brilliant (table 57 %, crown 34°, girdle 2.5 %, stars 50 %,
/// lower halves 80 %) at pavilion angle `pavilion_deg` (the reference's is 40.7°), named
/// `name`.
pub(crate) fn gia_round(name: &str, pavilion_deg: f64) -> crate::cut::Cut {
    let v: std::collections::BTreeMap<String, f64> = [
        ("table", 0.57),
        ("crown_angle", 34.0),
        ("pavilion_angle", pavilion_deg),
        ("girdle", 0.025),
        ("star", 0.5),
        ("lower_half", 0.8),
    ]
    .iter()
    .map(|(k, v)| (k.to_string(), *v))
    .collect();
    crate::cut::Cut::from_family(name, "round-brilliant", &v).unwrap()
}

/// A princess-like square brilliant built from planes: square girdle, table, 4 bezels and 4
/// corner crown facets, 4 pavilion break facets, 4 pavilion mains and 4 corner pavilion facets.
pub(crate) fn princess() -> Polyhedron {
    let h = 0.5;
    let zg = 0.01;
    let mut p = Vec::new();
    let mut add = |n: DVec3, through: DVec3, tier: &str| {
        let k = p.len();
        p.push(FacetPlane::new(
            n,
            n.normalize().dot(through) * n.length(),
            format!("{tier}-{k}"),
            tier,
        ));
    };
    for k in 0..4 {
        let az = 90.0 * k as f64;
        let a = az.to_radians();
        let n = DVec3::new(a.cos(), a.sin(), 0.0);
        add(n, n * h, "girdle");
        add(facet_normal(34.0, az, true), n * h + DVec3::Z * zg, "bezel");
        add(
            facet_normal(50.0, az, false),
            n * h - DVec3::Z * zg,
            "pavilion-break",
        );
        add(
            facet_normal(41.0, az, false),
            n * h - DVec3::Z * (zg + 0.06),
            "pavilion-main",
        );
        let c = DVec3::new(a.cos() - a.sin(), a.sin() + a.cos(), 0.0) * h;
        add(
            facet_normal(22.0, az + 45.0, true),
            c + DVec3::Z * zg,
            "corner-crown",
        );
        add(
            facet_normal(35.0, az + 45.0, false),
            c - DVec3::Z * zg,
            "corner-pavilion",
        );
    }
    add(DVec3::Z, DVec3::Z * (zg + 0.15), "table");
    Polyhedron::from_planes(&p).unwrap()
}

#[test]
fn kit_solids_have_their_volumes() {
    let near = |got: f64, want: f64| assert!((got / want - 1.0).abs() < 1e-9, "{got} vs {want}");
    near(cube().volume(), 1.0);
    near(boxed(1.0, 2.0, 3.0).volume(), 48.0);
    near(slab(40.0, 0.05).volume(), 80.0 * 80.0 * 0.1);
    // |x|+|y|+|z| ≤ r: volume 4r³/3.
    near(octahedron_of(1.0).volume(), 4.0 / 3.0);
    near(octahedron().volume(), 0.5 * 3f64.sqrt());
    assert_eq!(princess().facets().len(), 25);
    assert_eq!(cube().facets()[5].name, "bottom");
}
