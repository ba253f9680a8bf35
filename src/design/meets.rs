//! A design's meets and the depth solve that keeps them.
//!
//! A **meet** is a point where four or more facet planes pass within a tolerance of one point:
//! what "cut to the meet" leaves behind. A solid's ordinary vertex has three facets; a meet is
//! over-determined, so it survives a change of facet angles only if the depths move with it.
//!
//! For fixed facet normals every meet is a set of linear equations in the tiers' depths
//! (`n_i · p_m = d_t(i)` for each facet `i` through meet `m`; the meet's point `p_m` is
//! eliminated as the least-squares point of its planes, itself linear in the depths), so the depths that keep the meets come from one linear least-squares solve
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
    /// its thickness (vertical girdle facets alone do not fix a pavilion's height). Held weakly
    /// ([`HEIGHT_WEIGHT`]): where the meets leave a height free it stays as near its old value
    /// as it can, and where the file's rounded heights disagree the meets win.
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

/// Weight of the rows that hold a girdle meet's height: far below the meets' own rows (weight
/// 1), so a file's rounding never opens a meet; so the girdle's height is what a free shift of
/// the pavilion or crown keeps.
pub const HEIGHT_WEIGHT: f64 = 1e-3;

/// Solve for the tiers' depths that keep every meet of `p`: linear least squares in the free
/// tiers' depths (Householder QR with column pivoting, [`least_squares_frozen`]), one row per
/// facet of a meet — its distance from the meet's least-squares point, which is linear in the
/// depths — and a weak row per held height. A tier in no meet keeps its depth, and so does a
/// tier the meets barely fix ([`FREEZE`]).
///
/// The rows that hold a girdle meet's old height pull the solution off the meets by about
/// their weight squared times how far the meets move them. Passes of refinement, each holding
/// the heights at the last solution, take that pull away, so a keepable meet is kept to
/// rounding; a pass is kept only while it shrinks the largest gap tenfold (where the meets
/// themselves disagree, refining would only let the heights drift).
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
    // A tier in no meet keeps its depth: held, not solved.
    let mut in_meet = vec![false; nt];
    for &f in p.meets.iter().flatten() {
        in_meet[p.tier_of[f]] = true;
    }
    let mut col_of_tier = vec![usize::MAX; nt];
    let mut ncols = 0;
    for t in 0..nt {
        if !p.held[t] && in_meet[t] {
            col_of_tier[t] = ncols;
            ncols += 1;
        }
    }
    // Each meet's least-squares point is linear in its facets' depths, p = M⁻¹ Σ n_j d_j with
    // M = Σ n_j n_jᵀ; every facet's distance from it, n_i · p − d_i, is a row (the rows of a
    // meet have rank k − 3: its k − 3 conditions of concurrency).
    let mut rows: Vec<(Vec<f64>, f64)> = Vec::new();
    let mut row_of = |coef: &[(usize, f64)], weight: f64, target: f64| {
        let mut row = vec![0.0; ncols];
        let mut rhs = weight * target;
        for &(f, c) in coef {
            let t = p.tier_of[f];
            if col_of_tier[t] == usize::MAX {
                rhs -= weight * c * p.depths[t];
            } else {
                row[col_of_tier[t]] += weight * c;
            }
        }
        rows.push((row, rhs));
    };
    for (m, facets) in p.meets.iter().enumerate() {
        let minv = meet_inverse(p.normals, facets)?;
        for &i in facets {
            let ni = minv * p.normals[i];
            let coef: Vec<(usize, f64)> = facets
                .iter()
                .map(|&j| (j, ni.dot(p.normals[j]) - if i == j { 1.0 } else { 0.0 }))
                .collect();
            row_of(&coef, 1.0, 0.0);
        }
        if let Some(z) = p.held_z[m] {
            let ez = minv * DVec3::Z;
            let coef: Vec<(usize, f64)> =
                facets.iter().map(|&j| (j, ez.dot(p.normals[j]))).collect();
            row_of(&coef, HEIGHT_WEIGHT, z);
        }
    }
    let old: Vec<f64> = (0..nt)
        .filter(|&t| col_of_tier[t] != usize::MAX)
        .map(|t| p.depths[t])
        .collect();
    let x = least_squares_frozen(rows, ncols, &old, FREEZE);
    let depths: Vec<f64> = (0..nt)
        .map(|t| match col_of_tier[t] {
            usize::MAX => p.depths[t],
            c => x[c],
        })
        .collect();
    let mut points = Vec::with_capacity(p.meets.len());
    let mut gaps = Vec::with_capacity(p.meets.len());
    for facets in p.meets {
        let planes: Vec<(DVec3, f64)> = facets
            .iter()
            .map(|&f| (p.normals[f], depths[p.tier_of[f]]))
            .collect();
        let q = least_squares_point(&planes).unwrap_or(DVec3::ZERO);
        gaps.push(
            planes
                .iter()
                .map(|(n, d)| (n.dot(q) - d).abs())
                .fold(0.0, f64::max),
        );
        points.push(q);
    }
    Ok(DepthSolve {
        depths,
        points,
        gaps,
    })
}

/// `(Σ n nᵀ)⁻¹` over a meet's facets: an error when their normals do not span space.
fn meet_inverse(normals: &[DVec3], facets: &[usize]) -> Result<glam::DMat3> {
    let mut m = glam::DMat3::ZERO;
    for &f in facets {
        let n = normals[f];
        m += glam::DMat3::from_cols(n * n.x, n * n.y, n * n.z);
    }
    if m.determinant().abs() < 1e-12 {
        return Err(Error::Geometry(
            "depth solve: a meet's facets do not fix a point".into(),
        ));
    }
    Ok(m.inverse())
}

/// A free tier whose column's remaining norm falls below this share of the largest, in the
/// pivoted solve, keeps its depth: the meets barely fix it, and solving for it would move it
/// far (a file's rounding of 1e-8 closed by a move of 1e-3 along a near-free direction).
pub const FREEZE: f64 = 1e-5;

/// Minimise |A x − b| by Householder QR with column pivoting: the column with the largest
/// remaining norm first, until the largest left is below `freeze` of the largest at the start;
/// the columns left are **frozen** at their value in `fallback`, the others solved for. A
/// rank-deficient or ill-conditioned system so keeps the least-determined unknowns where they
/// were instead of moving them far to shave a rounding-sized residual.
pub fn least_squares_frozen(
    rows: Vec<(Vec<f64>, f64)>,
    ncols: usize,
    fallback: &[f64],
    freeze: f64,
) -> Vec<f64> {
    let m = rows.len();
    let mut a = vec![0.0; m * ncols];
    let mut b = vec![0.0; m];
    for (i, (row, rhs)) in rows.into_iter().enumerate() {
        for (j, v) in row.into_iter().enumerate() {
            a[j * m + i] = v;
        }
        b[i] = rhs;
    }
    let norm_from = |a: &[f64], j: usize, k: usize| -> f64 {
        a[j * m + k..(j + 1) * m]
            .iter()
            .map(|v| v * v)
            .sum::<f64>()
            .sqrt()
    };
    let scale = (0..ncols).map(|j| norm_from(&a, j, 0)).fold(0.0, f64::max);
    let mut order: Vec<usize> = (0..ncols).collect();
    let mut rank = 0;
    for k in 0..ncols.min(m) {
        // Pivot: the remaining column with the largest norm below row k.
        let (best, norm) = (k..ncols)
            .map(|c| (c, norm_from(&a, order[c], k)))
            .fold((k, -1.0), |acc, x| if x.1 > acc.1 { x } else { acc });
        if norm <= freeze * scale || norm <= 0.0 {
            break;
        }
        order.swap(k, best);
        let jk = order[k];
        let col = &a[jk * m..(jk + 1) * m];
        let alpha = if col[k] > 0.0 { -norm } else { norm };
        let mut v: Vec<f64> = col[k..].to_vec();
        v[0] -= alpha;
        let vv: f64 = v.iter().map(|x| x * x).sum();
        if vv > 0.0 {
            for &j in &order[k..] {
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
        rank = k + 1;
    }
    let mut x = fallback.to_vec();
    // The frozen columns' part of the right-hand side, then back substitution.
    for k in (0..rank).rev() {
        let mut s = b[k];
        for &j in &order[rank..] {
            s -= a[j * m + k] * x[j];
        }
        for &j in &order[k + 1..rank] {
            s -= a[j * m + k] * x[j];
        }
        x[order[k]] = s / a[order[k] * m + k];
    }
    x
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
        let x = least_squares_frozen(rows.clone(), n, &vec![0.0; n], 1e-12);
        for j in 0..n {
            let g: f64 = rows
                .iter()
                .map(|(a, b)| a[j] * (a.iter().zip(&x).map(|(p, q)| p * q).sum::<f64>() - b))
                .sum();
            assert!(g.abs() < 1e-12, "gradient {j}: {g}");
        }
        // A rank-deficient system keeps the column it cannot fix at its fallback and solves
        // the other: columns (1, 2) are parallel, so the larger one is solved for.
        let twice: Vec<(Vec<f64>, f64)> = (0..6).map(|i| (vec![1.0, 2.0], i as f64)).collect();
        let x = least_squares_frozen(twice.clone(), 2, &[0.25, 9.0], 1e-9);
        assert_eq!(x[0], 0.25);
        let g: f64 = twice
            .iter()
            .map(|(a, b)| a[1] * (a[0] * x[0] + a[1] * x[1] - b))
            .sum();
        assert!(g.abs() < 1e-12, "gradient {g}");
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
