//! A design's meets and the depth solve that keeps them.
//!
//! A **meet** is a point where four or more facet planes pass within a tolerance of one point:
//! what "cut to the meet" leaves behind. A solid's ordinary vertex has three facets; a meet is
//! over-determined, so it survives a change of facet angles only if the depths move with it.
//!
//! For fixed facet normals every meet is a set of linear equations in the tiers' depths
//! (`n_i · p_m = d_t(i)` for each facet `i` through meet `m`, with the meet's point `p_m`
//! unknown too), so the depths that keep the meets come from one linear least-squares solve
//! ([`solve_depths`]), with some tiers' depths held (the girdle's, which fixes the scale).
//! A meet the new normals cannot keep shows up as a residual: its planes no longer pass through
//! one point, and [`DepthSolve::gaps`] says by how much.

use crate::error::{Error, Result};
use crate::geometry::{DVec3, Polyhedron};

/// A meet of a solid: four or more facets through (nearly) one point.
#[derive(Clone, Debug, PartialEq)]
pub struct Meet {
    /// The least-squares point of the meet's planes.
    pub point: DVec3,
    /// The facets through it (indices into the solid's facets), ascending.
    pub facets: Vec<usize>,
    /// How far the farthest of its planes passes from `point` (0 for an exact meet).
    pub gap: f64,
}

/// The meets of `solid`: its vertices, with vertices closer than `tol` taken as one point,
/// where at least four facet planes pass within `tol` of the least-squares point of the
/// facets that touch them. `tol` is in the solid's length unit (the width W = 1 for cuts).
pub fn find_meets(solid: &Polyhedron, tol: f64) -> Vec<Meet> {
    let verts = solid.vertices();
    // Vertices closer than tol: one cluster (union–find; a solid has at most a few hundred).
    let mut parent: Vec<usize> = (0..verts.len()).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for i in 0..verts.len() {
        for j in i + 1..verts.len() {
            if verts[i].distance(verts[j]) <= tol {
                let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                parent[a.max(b)] = a.min(b);
            }
        }
    }
    let mut touching: Vec<Vec<usize>> = vec![Vec::new(); verts.len()];
    for (fi, f) in solid.facets().iter().enumerate() {
        for &v in &f.vertices {
            let r = root(&mut parent, v);
            if !touching[r].contains(&fi) {
                touching[r].push(fi);
            }
        }
    }
    let mut out = Vec::new();
    for (r, facets) in touching.into_iter().enumerate() {
        if facets.len() < 4 || root(&mut parent, r) != r {
            continue;
        }
        let planes: Vec<(DVec3, f64)> = facets
            .iter()
            .map(|&f| {
                (
                    solid.facets()[f].plane.normal,
                    solid.facets()[f].plane.offset,
                )
            })
            .collect();
        let Some(point) = least_squares_point(&planes) else {
            continue;
        };
        let mut kept: Vec<usize> = facets
            .iter()
            .zip(&planes)
            .filter(|(_, (n, d))| (n.dot(point) - d).abs() <= tol)
            .map(|(&f, _)| f)
            .collect();
        if kept.len() < 4 {
            continue;
        }
        kept.sort_unstable();
        let gap = planes
            .iter()
            .zip(&facets)
            .filter(|(_, f)| kept.contains(f))
            .map(|((n, d), _)| (n.dot(point) - d).abs())
            .fold(0.0, f64::max);
        out.push(Meet {
            point,
            facets: kept,
            gap,
        });
    }
    out
}

/// The point nearest (least squares) to the planes `n · p = d`; `None` when their normals do
/// not span space (fewer than three independent directions).
pub fn least_squares_point(planes: &[(DVec3, f64)]) -> Option<DVec3> {
    let mut a = [[0.0f64; 3]; 3];
    let mut b = [0.0f64; 3];
    for (n, d) in planes {
        let n = n.to_array();
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] += n[i] * n[j];
            }
            b[i] += n[i] * d;
        }
    }
    let m = glam::DMat3::from_cols_array_2d(&a).transpose();
    let det = m.determinant();
    // Normals of unit length: det of Σ n nᵀ is ~1 for well-spread normals.
    if det.abs() < 1e-12 {
        return None;
    }
    Some(m.inverse() * DVec3::from_array(b))
}

/// The problem [`solve_depths`] solves: facets grouped into tiers (each tier one depth), the
/// meets to keep, and which tiers' depths are held.
#[derive(Clone, Debug)]
pub struct DepthProblem<'a> {
    /// Every facet's outward unit normal (the new angles).
    pub normals: &'a [DVec3],
    /// Every facet's tier (index into `depths`).
    pub tier_of: &'a [usize],
    /// Each tier's current depth: the start of the solve, and the value of a held tier.
    pub depths: &'a [f64],
    /// Tiers whose depth is held (the girdle, which fixes the scale).
    pub held: &'a [bool],
    /// The meets to keep, each as the facets through it.
    pub meets: &'a [Vec<usize>],
    /// Meets whose height is held (`Some(z)`): the girdle's meets, so that the girdle keeps
    /// its thickness (vertical girdle facets alone do not fix a pavilion's height). Held as
    /// weakly as the free depths: where the meets leave a height free it stays as near its old
    /// value as it can, and where the file's rounded heights disagree the meets win.
    pub held_z: &'a [Option<f64>],
}

/// The depths that keep the meets, the meets' new points, and how well each meet is kept.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthSolve {
    /// Each tier's new depth (held tiers unchanged).
    pub depths: Vec<f64>,
    /// Each meet's new point.
    pub points: Vec<DVec3>,
    /// Each meet's gap: how far its farthest plane passes from its point (0 when kept).
    pub gaps: Vec<f64>,
}

/// Weight of the rows that hold a free tier near its current depth. They make the system
/// full-rank when a tier's depth is not fixed by any meet (it then keeps its depth) and move a
/// meet-fixed depth by ~WEIGHT² relative: far below any tolerance a design is checked at.
pub const PRIOR_WEIGHT: f64 = 1e-7;

/// Weight of the rows that hold a girdle meet's height: far below the meets' own rows (weight
/// 1), so a file's rounding never opens a meet, and far above [`PRIOR_WEIGHT`], so the
/// girdle's height, not a tier's old depth, is what a free shift of the pavilion or crown keeps.
pub const HEIGHT_WEIGHT: f64 = 1e-3;

/// Solve for the tiers' depths that keep every meet of `p` (linear least squares by
/// Householder QR): unknowns are each free tier's depth and each meet's point, equations
/// `n_i · p_m − d_t(i) = 0` for every facet `i` through meet `m`.
///
/// The weak rows (a free tier's old depth, a girdle meet's old height) pull the solution off
/// the meets by about their weight squared times how far the meets move them. Passes of
/// refinement, each holding the weak rows at the last solution, take that pull away, so a
/// keepable meet is kept to rounding; a pass is kept only while it shrinks the largest gap
/// tenfold (where the meets themselves disagree, refining would only let the heights drift).
pub fn solve_depths(p: &DepthProblem) -> Result<DepthSolve> {
    let worst = |s: &DepthSolve| s.gaps.iter().copied().fold(0.0, f64::max);
    let mut solve = solve_once(p)?;
    for _ in 0..3 {
        let held_z: Vec<Option<f64>> = p
            .held_z
            .iter()
            .zip(&solve.points)
            .map(|(z, q)| z.map(|_| q.z))
            .collect();
        let next = solve_once(&DepthProblem {
            depths: &solve.depths,
            held_z: &held_z,
            ..p.clone()
        })?;
        if worst(&next) >= 0.1 * worst(&solve) {
            break;
        }
        solve = next;
    }
    Ok(solve)
}

fn solve_once(p: &DepthProblem) -> Result<DepthSolve> {
    let nt = p.depths.len();
    if p.normals.len() != p.tier_of.len() || p.held.len() != nt || p.held_z.len() != p.meets.len() {
        return Err(Error::Geometry(
            "depth solve: facets, tiers and held flags disagree in length".into(),
        ));
    }
    if let Some(&t) = p.tier_of.iter().find(|&&t| t >= nt) {
        return Err(Error::Geometry(format!(
            "depth solve: tier {t} out of range"
        )));
    }
    // Columns: free tiers first, then 3 per meet.
    let mut col_of_tier = vec![usize::MAX; nt];
    let mut ncols = 0;
    for (col, &held) in col_of_tier.iter_mut().zip(p.held) {
        if !held {
            *col = ncols;
            ncols += 1;
        }
    }
    let free_tiers = ncols;
    let meet_col = |m: usize| free_tiers + 3 * m;
    ncols += 3 * p.meets.len();
    let mut rows: Vec<(Vec<f64>, f64)> = Vec::new();
    for (m, facets) in p.meets.iter().enumerate() {
        for &f in facets {
            let mut row = vec![0.0; ncols];
            let n = p.normals[f];
            row[meet_col(m)] = n.x;
            row[meet_col(m) + 1] = n.y;
            row[meet_col(m) + 2] = n.z;
            let t = p.tier_of[f];
            let rhs = if p.held[t] {
                p.depths[t]
            } else {
                row[col_of_tier[t]] = -1.0;
                0.0
            };
            rows.push((row, rhs));
        }
    }
    for (m, z) in p.held_z.iter().enumerate() {
        if let Some(z) = z {
            let mut row = vec![0.0; ncols];
            row[meet_col(m) + 2] = HEIGHT_WEIGHT;
            rows.push((row, HEIGHT_WEIGHT * z));
        }
    }
    for (t, &col) in col_of_tier.iter().enumerate() {
        if !p.held[t] {
            let mut row = vec![0.0; ncols];
            row[col] = PRIOR_WEIGHT;
            rows.push((row, PRIOR_WEIGHT * p.depths[t]));
        }
    }
    let x = least_squares(rows, ncols).ok_or_else(|| {
        Error::Geometry("depth solve: the meets do not fix the meet points".into())
    })?;
    let depths: Vec<f64> = (0..nt)
        .map(|t| {
            if p.held[t] {
                p.depths[t]
            } else {
                x[col_of_tier[t]]
            }
        })
        .collect();
    let points: Vec<DVec3> = (0..p.meets.len())
        .map(|m| DVec3::new(x[meet_col(m)], x[meet_col(m) + 1], x[meet_col(m) + 2]))
        .collect();
    let gaps = p
        .meets
        .iter()
        .zip(&points)
        .map(|(facets, &q)| {
            facets
                .iter()
                .map(|&f| (p.normals[f].dot(q) - depths[p.tier_of[f]]).abs())
                .fold(0.0, f64::max)
        })
        .collect();
    Ok(DepthSolve {
        depths,
        points,
        gaps,
    })
}

/// Minimise |A x − b| by Householder QR; `None` when A is rank-deficient (a pivot below 1e-12
/// of the largest column norm).
pub fn least_squares(rows: Vec<(Vec<f64>, f64)>, ncols: usize) -> Option<Vec<f64>> {
    let m = rows.len();
    if m < ncols {
        return None;
    }
    // Column-major copy for cache-friendly Householder sweeps.
    let mut a = vec![0.0; m * ncols];
    let mut b = vec![0.0; m];
    for (i, (row, rhs)) in rows.into_iter().enumerate() {
        for (j, v) in row.into_iter().enumerate() {
            a[j * m + i] = v;
        }
        b[i] = rhs;
    }
    let scale = (0..ncols)
        .map(|j| {
            a[j * m..(j + 1) * m]
                .iter()
                .map(|v| v * v)
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max);
    for k in 0..ncols {
        let col = &a[k * m..(k + 1) * m];
        let norm = col[k..].iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm <= 1e-12 * scale.max(f64::MIN_POSITIVE) {
            return None;
        }
        let alpha = if col[k] > 0.0 { -norm } else { norm };
        let mut v: Vec<f64> = col[k..].to_vec();
        v[0] -= alpha;
        let vv: f64 = v.iter().map(|x| x * x).sum();
        if vv > 0.0 {
            for j in k..ncols {
                let cj = &mut a[j * m + k..(j + 1) * m];
                let s = 2.0 * v.iter().zip(cj.iter()).map(|(x, y)| x * y).sum::<f64>() / vv;
                for (c, x) in cj.iter_mut().zip(&v) {
                    *c -= s * x;
                }
            }
            let s = 2.0 * v.iter().zip(&b[k..]).map(|(x, y)| x * y).sum::<f64>() / vv;
            for (c, x) in b[k..].iter_mut().zip(&v) {
                *c -= s * x;
            }
        }
    }
    // Back substitution on the upper triangle.
    let mut x = vec![0.0; ncols];
    for k in (0..ncols).rev() {
        let mut s = b[k];
        for j in k + 1..ncols {
            s -= a[j * m + k] * x[j];
        }
        x[k] = s / a[k * m + k];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{FacetPlane, Polyhedron};

    #[test]
    fn least_squares_meets_the_normal_equations() {
        // Optimality of a least-squares solution: A^T (A x - b) = 0.
        let mut r = crate::testkit::uniform(7);
        let (m, n) = (12, 5);
        let rows: Vec<(Vec<f64>, f64)> = (0..m)
            .map(|_| ((0..n).map(|_| r() - 0.5).collect(), r()))
            .collect();
        let x = least_squares(rows.clone(), n).unwrap();
        for j in 0..n {
            let g: f64 = rows
                .iter()
                .map(|(a, b)| a[j] * (a.iter().zip(&x).map(|(p, q)| p * q).sum::<f64>() - b))
                .sum();
            assert!(g.abs() < 1e-12, "gradient {j}: {g}");
        }
        // A rank-deficient system is refused.
        let twice: Vec<(Vec<f64>, f64)> = (0..6).map(|i| (vec![1.0, 2.0], i as f64)).collect();
        assert!(least_squares(twice, 2).is_none());
    }

    fn pyramid(shift: f64) -> Polyhedron {
        let mut planes = vec![FacetPlane::new(DVec3::NEG_Z, 0.0, "base", "base")];
        for k in 0..4 {
            let a = k as f64 * std::f64::consts::FRAC_PI_2;
            let n = DVec3::new(a.cos(), a.sin(), 1.0);
            let d = 0.5 / 2f64.sqrt() + if k == 0 { shift } else { 0.0 };
            planes.push(FacetPlane::new(n, d, format!("side-{k}"), "side"));
        }
        Polyhedron::from_planes(&planes).unwrap()
    }

    #[test]
    fn a_pyramids_apex_is_its_only_meet() {
        let p = pyramid(0.0);
        let meets = find_meets(&p, 1e-9);
        assert_eq!(meets.len(), 1, "{meets:?}");
        assert_eq!(meets[0].facets, vec![1, 2, 3, 4]);
        // Unit normals (1, 0, 1)/√2 at offset 1/4: the apex is at z = √2/4.
        let apex = DVec3::new(0.0, 0.0, 2f64.sqrt() / 4.0);
        assert!(
            meets[0].gap < 1e-12 && (meets[0].point - apex).length() < 1e-12,
            "{meets:?}"
        );
        // One side moved out by 1e-7: the apex opens into a short ridge, a meet within 1e-6,
        // none within 1e-9.
        let q = pyramid(1e-7);
        let loose = find_meets(&q, 1e-6);
        assert_eq!(loose.len(), 1);
        assert!(
            loose[0].gap > 1e-9 && loose[0].gap < 1e-6,
            "{}",
            loose[0].gap
        );
        assert!(find_meets(&q, 1e-9).is_empty());
    }
}
