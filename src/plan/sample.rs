//! The example rough: a distorted octahedron as a scanned rough would come, its faces bulged,
//! its axes stretched and sheared, with one dent (so its convex hull adds a little volume).
//! `cuts/rough-octahedron.obj` is this mesh at `n = 16` (2,048 triangles); the tests and the
//! bench build it here. And a scanned pebble as large as real scans come (400,000 triangles,
//! nearly all of its vertices on its hull), for the bench.

use super::mesh::TriMesh;
use crate::geometry::DVec3;
use std::collections::HashMap;

/// The distorted octahedron, each face split into `n²` triangles, in mm (about 8 × 6.6 × 5.2).
pub fn distorted_octahedron(n: usize) -> TriMesh {
    let dent = DVec3::new(1.0, 0.3, 0.5).normalize() / 1.8;
    subdivided_octahedron(n, |p| {
        // Bulge the faces (their centres out by a fifteenth), dent one spot.
        let bulge = 1.0 + 0.2 * (1.0 - p.abs().max_element());
        let dip = 1.0 - 0.08 * (-(p - dent).length_squared() / 0.03).exp();
        let p = p * bulge * dip;
        DVec3::new(4.0 * p.x + 0.5 * p.z, 3.3 * p.y + 0.3 * p.x, 2.6 * p.z)
    })
}

/// A scanned pebble: a rounded rough about 8 × 6.6 × 5.2 mm, its surface smooth but for a
/// scanner's noise (seeded, up to 2 µm along the radius), as a closed mesh of `8 n²` triangles
/// (`n = 224`: 401,408 triangles, 200,706 vertices). Nearly every vertex is on its convex hull,
/// the hard case for a planner (`cargo bench --bench plan`).
pub fn scanned_pebble(n: usize, seed: u64) -> TriMesh {
    let mut state = seed ^ 0x9E37_79B9_7F4A_7C15;
    // SplitMix64: a uniform number in [-1, 1) per vertex.
    let mut noise = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    subdivided_octahedron(n, |p| {
        let u = p.normalize();
        // Two gentle lobes and a flat side, then the noise along the radius.
        let lobes = 1.0 + 0.06 * (3.0 * u.x).sin() * u.y + 0.04 * u.z * u.z - 0.03 * u.x.powi(4);
        let q = u * lobes;
        let r = DVec3::new(4.0 * q.x + 0.3 * q.z, 3.3 * q.y, 2.6 * q.z);
        r + u * (0.002 * noise())
    })
}

/// An octahedron with each face split into `n²` triangles, its lattice points (on
/// `|x| + |y| + |z| = 1`) moved by `place`, welded and wound outward.
fn subdivided_octahedron(n: usize, mut place: impl FnMut(DVec3) -> DVec3) -> TriMesh {
    let n = n.max(1) as i64;
    let mut mesh = TriMesh::default();
    let mut index: HashMap<[i64; 3], usize> = HashMap::new();
    let mut point = |k: [i64; 3], mesh: &mut TriMesh| -> usize {
        *index.entry(k).or_insert_with(|| {
            let p = DVec3::new(k[0] as f64, k[1] as f64, k[2] as f64) / n as f64;
            mesh.vertices.push(place(p));
            mesh.vertices.len() - 1
        })
    };
    for sx in [-1i64, 1] {
        for sy in [-1i64, 1] {
            for sz in [-1i64, 1] {
                let (a, mut b, mut c) = ([sx, 0, 0], [0, sy, 0], [0, 0, sz]);
                if sx * sy * sz < 0 {
                    std::mem::swap(&mut b, &mut c);
                }
                let at = |i: i64, j: i64| -> [i64; 3] {
                    let k = n - i - j;
                    [0, 1, 2].map(|d| i * a[d] + j * b[d] + k * c[d])
                };
                for i in 0..n {
                    for j in 0..n - i {
                        let t = [at(i, j), at(i + 1, j), at(i, j + 1)];
                        let tri = t.map(|k| point(k, &mut mesh));
                        mesh.triangles.push(tri);
                        if i + j + 1 < n {
                            let t = [at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                            let tri = t.map(|k| point(k, &mut mesh));
                            mesh.triangles.push(tri);
                        }
                    }
                }
            }
        }
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::Rough;

    /// The bundled example is this generator's output (set `FACETLAB_WRITE_SAMPLE=1` to write
    /// it again), closed, not quite convex, 2,048 triangles.
    #[test]
    fn the_bundled_example_rough_is_the_generated_one() {
        let mesh = distorted_octahedron(16);
        assert_eq!(mesh.triangles.len(), 2048);
        let text = mesh
            .to_obj("facetlab example rough: a distorted octahedron (src/plan/sample.rs, n = 16)");
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cuts/rough-octahedron.obj");
        if std::env::var_os("FACETLAB_WRITE_SAMPLE").is_some() {
            std::fs::write(path, &text).unwrap();
        }
        assert_eq!(std::fs::read_to_string(path).unwrap(), text);
        let rough = Rough::from_trimesh("r", "r", mesh, None).unwrap();
        let excess = rough.hull_excess();
        assert!(excess > 1e-4 && excess < 0.05, "{excess}");
    }

    /// A scan with more hull vertices than a rough keeps: the hull stops at the budget,
    /// inside the mesh's, and what it leaves out is what a brute-force check finds.
    #[test]
    fn a_large_scan_is_planned_in_a_hull_that_says_what_it_leaves_out() {
        let mesh = scanned_pebble(64, 1);
        assert_eq!(mesh.triangles.len(), 8 * 64 * 64);
        let rough = Rough::from_trimesh("p", "p", mesh.clone(), None).unwrap();
        assert_eq!(rough.hull_vertices, crate::plan::rough::HULL_VERTICES);
        assert!(
            rough.left_out > 0.0 && rough.left_out < 0.01,
            "{} mm",
            rough.left_out
        );
        let planes = rough.planes();
        let mut farthest = 0.0f64;
        for p in mesh.vertices.iter().step_by(5) {
            let out = planes.iter().map(|q| q.distance(*p)).fold(0.0, f64::max);
            farthest = farthest.max(out);
        }
        assert!(
            farthest <= rough.left_out * (1.0 + 1e-9),
            "{farthest} vs {}",
            rough.left_out
        );
        assert!(
            farthest > 0.5 * rough.left_out,
            "{farthest} vs {}",
            rough.left_out
        );
        // Inside the mesh's hull, and short of the mesh's volume by about its area times that.
        let short = 1.0 - rough.volume() / rough.mesh_volume.unwrap();
        assert!(short > -1e-3 && short < 0.01, "{short}");
    }
}
