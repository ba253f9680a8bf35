//! Exact containment: the largest copy of a convex cut inside a convex rough, for one
//! orientation and one set of proportions, as a linear program in the scale and translation.
//!
//! The cut's vertices `v_i` (already turned to the orientation) go to `s·v_i + t`; the rough is
//! `n_j · x <= d_j`. Every vertex inside every half-space is `s·(n_j·v_i) + n_j·t <= d_j` for
//! all `i, j`; for one `j` the tightest of these is the vertex with the largest `n_j·v_i`, the
//! cut's support `h_j = max_i n_j·v_i` (a linear function over a polytope peaks at a vertex),
//! so the program is exactly
//!
//! ```text
//! maximise s   subject to   s·h_j + n_j·t <= d_j   for every rough plane j
//! ```
//!
//! in four unknowns `(s, t)` with one constraint per rough plane. It is solved by the primal
//! active-set method (the simplex method seen from the constraints): start at `s = 0` with `t`
//! at a point inside the rough (every constraint slack), climb along the objective projected
//! onto the working set's null space until a constraint blocks and joins the set, and when the
//! projected direction vanishes read the multipliers and let the most useless constraint go
//! (the lowest-numbered one with a negative multiplier: Bland's rule, so degenerate vertices do
//! not cycle). At most four constraints are ever active, so each step costs one pass over the
//! rough's planes and a 4×4 solve. At the optimum the vertex is recomputed from its four
//! constraints to clear the rounding of the path.

use crate::geometry::{DVec3, Plane};

/// The largest copy: `s·v + t` for the cut's (turned) vertices `v`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// Scale `s` (mm per unit of the cut: the cut's width W in mm).
    pub scale: f64,
    /// Translation `t` (mm).
    pub shift: DVec3,
    /// Steps the active-set method took.
    pub steps: usize,
}

type V4 = [f64; 4];

fn dot(a: &V4, b: &V4) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
}

/// Solve the `k`×`k` system `g·x = r` by Gaussian elimination with partial pivoting; `None`
/// if singular.
fn solve(k: usize, mut g: [V4; 4], mut r: V4) -> Option<V4> {
    for col in 0..k {
        let piv = (col..k).max_by(|&a, &b| g[a][col].abs().total_cmp(&g[b][col].abs()))?;
        if g[piv][col].abs() < 1e-300 {
            return None;
        }
        g.swap(col, piv);
        r.swap(col, piv);
        let pivot_row = g[col];
        for row in col + 1..k {
            let f = g[row][col] / pivot_row[col];
            for (x, p) in g[row][col..k].iter_mut().zip(&pivot_row[col..k]) {
                *x -= f * p;
            }
            r[row] -= f * r[col];
        }
    }
    let mut x = [0.0; 4];
    for row in (0..k).rev() {
        let mut acc = r[row];
        for c in row + 1..k {
            acc -= g[row][c] * x[c];
        }
        x[row] = acc / g[row][row];
    }
    Some(x)
}

/// The support numbers `h_j = max_i n_j·v_i` of the vertices over the planes' normals.
pub fn supports(rough: &[Plane], verts: &[DVec3]) -> Vec<f64> {
    rough
        .iter()
        .map(|p| {
            verts
                .iter()
                .map(|v| p.normal.dot(*v))
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .collect()
}

/// The largest `s` and a `t` with `s·v_i + t` inside every plane of `rough` (see the module
/// documentation). `inside` must be a point strictly inside the rough (its centroid). `None`
/// when there is no such copy (no vertices, or a rough that does not bound the scale).
pub fn largest_copy(rough: &[Plane], verts: &[DVec3], inside: DVec3) -> Option<Fit> {
    if verts.is_empty() || rough.is_empty() {
        return None;
    }
    let h = supports(rough, verts);
    // Rows a_j = (h_j, n_j), b_j = d_j, normalised so that tolerances are distances.
    let mut a: Vec<V4> = Vec::with_capacity(rough.len());
    let mut b: Vec<f64> = Vec::with_capacity(rough.len());
    for (p, hj) in rough.iter().zip(&h) {
        let row = [*hj, p.normal.x, p.normal.y, p.normal.z];
        let len = dot(&row, &row).sqrt();
        a.push(row.map(|c| c / len));
        b.push(p.offset / len);
    }
    let objective: V4 = [1.0, 0.0, 0.0, 0.0];
    let mut x: V4 = [0.0, inside.x, inside.y, inside.z];
    let mut work: Vec<usize> = Vec::with_capacity(4);
    let max_steps = 64 + 8 * rough.len();
    let mut steps = 0;
    let mut optimal = false;
    while steps < max_steps {
        steps += 1;
        let k = work.len();
        let mut g = [[0.0; 4]; 4];
        let mut r = [0.0; 4];
        for p in 0..k {
            for q in 0..k {
                g[p][q] = dot(&a[work[p]], &a[work[q]]);
            }
            r[p] = dot(&a[work[p]], &objective);
        }
        let lambda = if k == 0 { [0.0; 4] } else { solve(k, g, r)? };
        let mut d = objective;
        for p in 0..k {
            for c in 0..4 {
                d[c] -= lambda[p] * a[work[p]][c];
            }
        }
        // With four independent constraints active the direction is zero up to rounding.
        if k < 4 && dot(&d, &d).sqrt() > 1e-12 {
            let mut best: Option<(f64, usize)> = None;
            for (j, row) in a.iter().enumerate() {
                let rate = dot(row, &d);
                if rate <= 1e-14 || work.contains(&j) {
                    continue;
                }
                let step = ((b[j] - dot(row, &x)) / rate).max(0.0);
                if best.is_none_or(|(s, _)| step < s) {
                    best = Some((step, j));
                }
            }
            let (step, j) = best?;
            for c in 0..4 {
                x[c] += step * d[c];
            }
            work.push(j);
        } else {
            match (0..k)
                .filter(|&p| lambda[p] < -1e-12)
                .min_by_key(|&p| work[p])
            {
                Some(p) => {
                    work.remove(p);
                }
                None => {
                    optimal = true;
                    break;
                }
            }
        }
    }
    if !optimal {
        return None;
    }
    if work.len() == 4 {
        let mut g = [[0.0; 4]; 4];
        let mut r = [0.0; 4];
        for (p, &j) in work.iter().enumerate() {
            g[p] = a[j];
            r[p] = b[j];
        }
        if let Some(v) = solve(4, g, r) {
            x = v;
        }
    }
    Some(Fit {
        scale: x[0],
        shift: DVec3::new(x[1], x[2], x[3]),
        steps,
    })
}

#[cfg(test)]
mod tests;
