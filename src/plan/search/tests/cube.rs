//! The best pose of the default round brilliant inside a cube (issue 26's check 1, the cube).
//!
//! In a cube of side a with faces across x, y and z, the containment program splits by axis:
//! the planes ±e_k give `s·(h₊ + h₋) <= a`, the cut's width along e_k times s, and the shift
//! centres it, so W = a / max_k w_k and the yield is `V / (max_k w_k)³` (V and w_k at W = 1).
//! The best pose is the one whose largest width along the cube's edges is least.

use super::*;

/// The cut's widths along x, y and z once turned by `q`.
fn widths(verts: &[DVec3], q: DQuat) -> [f64; 3] {
    let p: Vec<DVec3> = verts.iter().map(|v| q * *v).collect();
    [DVec3::X, DVec3::Y, DVec3::Z].map(|u| {
        let (lo, hi) = p.iter().fold((f64::MAX, f64::MIN), |(lo, hi), v| {
            (lo.min(v.dot(u)), hi.max(v.dot(u)))
        });
        hi - lo
    })
}

fn largest(verts: &[DVec3], q: DQuat) -> f64 {
    let w = widths(verts, q);
    w[0].max(w[1]).max(w[2])
}

/// The pose with the cube's diagonal mirror plane x = y as a mirror of the cut too: the
/// cut's direction at azimuth `a` (its frame) goes down the plane, and its table normal to
/// `(sin θ/√2, sin θ/√2, cos θ)`.
fn mirrored_pose(theta: f64, a: f64) -> DQuat {
    let s2 = std::f64::consts::FRAC_1_SQRT_2;
    let (s, c) = theta.sin_cos();
    let n = DVec3::new(s * s2, s * s2, c);
    let m = DVec3::new(c * s2, c * s2, -s);
    DQuat::from_mat3(&DMat3::from_cols(m, n.cross(m), n)) * DQuat::from_rotation_z(-a)
}

/// The optimum's yield and polar angle (degrees) in [`mirrored_pose`] at a = 11.25°.
const CUBE_YIELD: f64 = 0.365_134_542_820;
const CUBE_THETA_DEG: f64 = 55.673_467_219;

/// **The optimum, derived.** With the cut's own mirror through the middle of a girdle flat
/// (azimuth 11.25° from a girdle point) lying in the cube's diagonal mirror plane x = y, the
/// widths along x and y are equal for every tilt θ of the table normal in that plane, and
/// the best θ is where they equal the width along z: θ = 55.673467219° from +z (the first of
/// two mirror-image optima on [0°, 180°]), found exactly by bisection on `w_x − w_z`. The
/// table normal is then (0.583955, 0.583955, 0.563909): 0.938° off the body diagonal
/// (1, 1, 1)/√3, tilted in the diagonal plane away from z, towards the edge direction
/// (1, 1, 0); as a turn from the cut's frame, 64.40° about (−0.41309, 0.77285, 0.48173).
/// All three widths are 0.824066728 W, so W = 1.213494 a and the yield is **36.5134543 %** (against 35.6 % with the table exactly across the
/// diagonal and 21.7 % upright). It is a local optimum of the max of the three widths: the
/// pieces of the three widths (one per pair of extreme vertices; along z a mirror pair ties)
/// have gradients over turns with 0 in their convex hull (checked), and an exhaustive search (8,000 seeded orientations, the best 40 refined by a pattern search
/// over turns; the 48 symmetries of the cube and 16 of the cut make that set cover the
/// orientation sphere many times over) finds nothing better. The planner's own search, the
/// proportions fixed at the defaults, reaches it to 1e-6 of yield.
#[test]
fn in_a_cube_the_best_pose_is_the_derived_one() {
    let cut = round();
    let verts = cut.solid.vertices().to_vec();
    let v = cut.solid.volume();
    let a = 11.25f64.to_radians();
    // The 1-D problem: the least largest width over θ, then the crossing w_x = w_z beside it.
    let n = 20_000;
    let best = (0..=n)
        .map(|i| PI * i as f64 / n as f64)
        .min_by(|x, y| {
            largest(&verts, mirrored_pose(*x, a)).total_cmp(&largest(&verts, mirrored_pose(*y, a)))
        })
        .unwrap();
    let g = |t: f64| {
        let w = widths(&verts, mirrored_pose(t, a));
        assert!((w[0] - w[1]).abs() < 1e-12);
        w[0] - w[2]
    };
    let (mut lo, mut hi) = (best - PI / n as f64, best + PI / n as f64);
    assert!(g(lo) * g(hi) < 0.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if (g(mid) > 0.0) == (g(lo) > 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let q = mirrored_pose(lo, a);
    let f = largest(&verts, q);
    let optimum = v / f.powi(3);
    let up = q * DVec3::Z;
    let diagonal = DVec3::new(1.0, 1.0, up.z.signum()).normalize();
    println!(
        "cube optimum: θ {:.9}°, yield {optimum:.12}, widths {f:.12}, W = {:.6} a, table {up:.6} ({:.4}° off the diagonal), turn {:?}",
        lo.to_degrees(),
        1.0 / f,
        up.angle_between(diagonal).to_degrees(),
        q.to_axis_angle()
    );
    assert!((optimum - CUBE_YIELD).abs() < 1e-11, "{optimum}");
    assert!((lo.to_degrees() - CUBE_THETA_DEG).abs() < 1e-8);
    // First order: each width is the largest of its pieces, one per pair of extreme vertices
    // (along z a mirror pair ties); the pieces' gradients over small turns `p ← exp(ω)·p`,
    // `(p_top − p_bottom) × e`, must have 0 in their convex hull.
    let p: Vec<DVec3> = verts.iter().map(|x| q * *x).collect();
    let mut grads: Vec<DVec3> = Vec::new();
    for e in [DVec3::X, DVec3::Y, DVec3::Z] {
        let extreme = |sign: f64| {
            let top = p.iter().map(|x| sign * x.dot(e)).fold(f64::MIN, f64::max);
            p.iter()
                .filter(|x| sign * x.dot(e) > top - 1e-9)
                .copied()
                .collect::<Vec<_>>()
        };
        for t in extreme(1.0) {
            for b in extreme(-1.0) {
                grads.push((t - b).cross(e));
            }
        }
    }
    println!("{} pieces: {grads:?}", grads.len());
    assert!(zero_in_hull(&grads), "{grads:?}");
    // The containment program agrees with the widths.
    let rough = Rough::crystal("cube", 5.0).unwrap();
    let config = PlanConfig {
        starts: 8,
        max_iterations: 400,
        top: 1,
        ..PlanConfig::default()
    };
    let planner = Planner::new(&rough, &config, 3.515);
    let placed = planner.place(&cut, q).unwrap();
    assert!((placed.yield_fraction - optimum).abs() < 1e-9);
    // Exhaustive: nothing better anywhere on the orientation sphere.
    let mut rng = SmallRng::seed_from_u64(48);
    let mut poses: Vec<(f64, DQuat)> = (0..8000)
        .map(|_| {
            let q = random_turn(&mut rng);
            (largest(&verts, q), q)
        })
        .collect();
    poses.sort_by(|x, y| x.0.total_cmp(&y.0));
    let axes = [
        DVec3::X,
        DVec3::Y,
        DVec3::Z,
        DVec3::ONE.normalize(),
        DVec3::new(1.0, -1.0, 0.5).normalize(),
    ];
    let refined = poses
        .iter()
        .take(40)
        .map(|&(mut fq, mut q)| {
            let mut step = 0.02;
            while step > 1e-10 {
                let mut moved = false;
                for axis in axes {
                    for s in [step, -step] {
                        let q2 = (DQuat::from_scaled_axis(axis * s) * q).normalize();
                        let f2 = largest(&verts, q2);
                        if f2 < fq {
                            (q, fq, moved) = (q2, f2, true);
                        }
                    }
                }
                if !moved {
                    step *= 0.5;
                }
            }
            fq
        })
        .fold(f64::MAX, f64::min);
    println!("exhaustive: best {:.12}", v / refined.powi(3));
    assert!(v / refined.powi(3) <= optimum + 1e-12);
    // The planner reaches it.
    let plan = &planner.plan_family("round-brilliant", &|| {}).unwrap()[0];
    println!("planner: {:.12}", plan.yield_fraction);
    assert!(
        (plan.yield_fraction - optimum).abs() < 1e-6,
        "{}",
        plan.yield_fraction
    );
}

/// Whether 0 is a convex combination of three or four of `g` (to 1e-9 of their size).
fn zero_in_hull(g: &[DVec3]) -> bool {
    let n = g.len();
    let size = g.iter().map(|x| x.length()).fold(0.0, f64::max);
    for mask in 0u32..1 << n {
        let idx: Vec<usize> = (0..n).filter(|i| mask & (1 << i) != 0).collect();
        if !(2..=4).contains(&idx.len()) {
            continue;
        }
        // Least squares on [g_i; 1]·λ = [0; 1] by the normal equations.
        let rows: Vec<glam::DVec4> = idx.iter().map(|&i| g[i].extend(1.0)).collect();
        let m = rows.len();
        let mut a = [[0.0; 5]; 4];
        for r in 0..m {
            for c in 0..m {
                a[r][c] = rows[r].dot(rows[c]);
            }
            a[r][4] = 1.0; // rows[r] · (0, 0, 0, 1)
        }
        // Gauss–Jordan.
        let mut ok = true;
        for c in 0..m {
            let piv = (c..m)
                .max_by(|x, y| a[*x][c].abs().total_cmp(&a[*y][c].abs()))
                .unwrap();
            if a[piv][c].abs() < 1e-14 {
                ok = false;
                break;
            }
            a.swap(c, piv);
            for r in 0..m {
                if r != c {
                    let f = a[r][c] / a[c][c];
                    let pivot_row = a[c];
                    for (x, p) in a[r].iter_mut().zip(pivot_row) {
                        *x -= f * p;
                    }
                }
            }
        }
        if !ok {
            continue;
        }
        let lambda: Vec<f64> = (0..m).map(|r| a[r][4] / a[r][r]).collect();
        let sum: DVec3 = idx.iter().zip(&lambda).map(|(&i, l)| *l * g[i]).sum();
        let total: f64 = lambda.iter().sum();
        if lambda.iter().all(|l| *l >= -1e-12)
            && (total - 1.0).abs() < 1e-9
            && sum.length() < 1e-9 * size
        {
            return true;
        }
    }
    false
}
