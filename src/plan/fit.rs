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
//!
//! A scanned rough has thousands of planes, of which a handful bind. [`Containment`] solves
//! the same program over a few of them and adds the ones it breaks until it breaks none
//! (constraint generation): a placed vertex `p` is inside the rough exactly when it is inside
//! the plane through which the ray from an inside point `c` towards `p` leaves the rough, and
//! that plane is the one whose dual point `n_j / (d_j − n_j·c)` lies farthest along `p − c`
//! — a linear function over the dual polytope, whose vertices are the rough's planes and
//! whose edges are the rough's edges, so it is found by climbing from neighbour to neighbour
//! (on a convex polytope a linear function has no local maximum but the top), started from
//! the best of a few hundred precomputed directions. The answer is the full program's: the
//! smaller program's optimum is at least as large, and it is feasible for every plane.

use crate::geometry::{DVec3, Plane, Polyhedron};

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

/// Directions per side of the cube map of [`Containment`]'s starting points.
const CUBE: usize = 8;

/// A rough prepared for the containment program over many planes (see the module
/// documentation): its planes, a point inside, each plane's dual point and neighbours, and the
/// exit plane of a cube map of directions to start climbing from.
#[derive(Clone, Debug)]
pub struct Containment {
    planes: Vec<Plane>,
    inside: DVec3,
    dual: Vec<DVec3>,
    start: Vec<usize>,
    next: Vec<usize>,
    anchors: Vec<usize>,
}

impl Containment {
    /// Prepare `rough` (a convex solid; its centroid is the inside point).
    pub fn new(rough: &Polyhedron) -> Containment {
        let planes: Vec<Plane> = rough.facets().iter().map(|f| f.plane).collect();
        let inside = rough.centroid();
        let dual = planes
            .iter()
            .map(|p| p.normal / (p.offset - p.normal.dot(inside)))
            .collect();
        let mut pairs: Vec<(usize, usize)> = rough
            .edges()
            .iter()
            .flat_map(|e| [(e.facets[0], e.facets[1]), (e.facets[1], e.facets[0])])
            .collect();
        pairs.sort_unstable();
        pairs.dedup();
        let mut start = vec![0usize; planes.len() + 1];
        for &(a, _) in &pairs {
            start[a + 1] += 1;
        }
        for i in 0..planes.len() {
            start[i + 1] += start[i];
        }
        let mut c = Containment {
            planes,
            inside,
            dual,
            start,
            next: pairs.into_iter().map(|(_, b)| b).collect(),
            anchors: Vec::new(),
        };
        let mut from = 0;
        c.anchors = (0..6 * CUBE * CUBE)
            .map(|k| {
                from = c.climb(anchor_direction(k), from);
                from
            })
            .collect();
        c
    }

    /// The rough's planes.
    pub fn planes(&self) -> &[Plane] {
        &self.planes
    }

    /// The plane with the largest `dual · u`, climbing over neighbours from `from`.
    fn climb(&self, u: DVec3, mut from: usize) -> usize {
        let mut best = self.dual[from].dot(u);
        loop {
            let up = self.next[self.start[from]..self.start[from + 1]]
                .iter()
                .map(|&j| (j, self.dual[j].dot(u)))
                .filter(|&(_, h)| h > best)
                .max_by(|a, b| a.1.total_cmp(&b.1));
            match up {
                Some((j, h)) => (from, best) = (j, h),
                None => return from,
            }
        }
    }

    /// The plane through which the ray from the inside point along `u` leaves the rough.
    fn exit(&self, u: DVec3) -> usize {
        self.climb(u, self.anchors[anchor_of(u)])
    }

    /// [`largest_copy`] in this rough, by constraint generation (see the module
    /// documentation): the same scale, over a few of the planes.
    pub fn largest_copy(&self, verts: &[DVec3]) -> Option<Fit> {
        if verts.is_empty() || self.planes.is_empty() {
            return None;
        }
        let size = verts
            .iter()
            .map(|v| v.length())
            .fold(0.0, f64::max)
            .max(1e-300);
        // Start with the planes the cut's vertices face from the inside point.
        let mut work: Vec<usize> = verts.iter().map(|v| self.exit(*v)).collect();
        work.sort_unstable();
        work.dedup();
        let mut steps = 0;
        for _ in 0..64 {
            let sub: Vec<Plane> = work.iter().map(|&j| self.planes[j]).collect();
            let Some(fit) = largest_copy(&sub, verts, self.inside) else {
                break;
            };
            steps += fit.steps;
            let tol = 1e-12 * (fit.scale.abs() * size + fit.shift.length() + 1.0);
            let mut broken: Vec<usize> = verts
                .iter()
                .filter_map(|v| {
                    let p = fit.scale * *v + fit.shift;
                    let j = self.exit(p - self.inside);
                    (self.planes[j].distance(p) > tol).then_some(j)
                })
                .filter(|j| work.binary_search(j).is_err())
                .collect();
            if broken.is_empty() {
                return Some(Fit { steps, ..fit });
            }
            broken.sort_unstable();
            broken.dedup();
            work.extend(broken);
            work.sort_unstable();
        }
        // A program over too few planes to bound the scale, or too many rounds (never seen):
        // the whole program.
        largest_copy(&self.planes, verts, self.inside)
    }
}

/// The unit direction of cell `k` of the cube map (side, then row and column).
fn anchor_direction(k: usize) -> DVec3 {
    let (side, rest) = (k / (CUBE * CUBE), k % (CUBE * CUBE));
    let a = 2.0 * ((rest / CUBE) as f64 + 0.5) / CUBE as f64 - 1.0;
    let b = 2.0 * ((rest % CUBE) as f64 + 0.5) / CUBE as f64 - 1.0;
    let sign = if side % 2 == 0 { 1.0 } else { -1.0 };
    let v = match side / 2 {
        0 => DVec3::new(sign, a, b),
        1 => DVec3::new(a, sign, b),
        _ => DVec3::new(a, b, sign),
    };
    v.normalize()
}

/// The cube-map cell of direction `u` (any length; zero goes to cell 0).
fn anchor_of(u: DVec3) -> usize {
    let m = u.abs();
    let (axis, big) = if m.x >= m.y && m.x >= m.z {
        (0, u.x)
    } else if m.y >= m.z {
        (1, u.y)
    } else {
        (2, u.z)
    };
    if big == 0.0 || !big.is_finite() {
        return 0;
    }
    let (a, b) = match axis {
        0 => (u.y, u.z),
        1 => (u.x, u.z),
        _ => (u.x, u.y),
    };
    let cell = |c: f64| (((c / big.abs() + 1.0) * 0.5 * CUBE as f64) as usize).min(CUBE - 1);
    let side = 2 * axis + usize::from(big < 0.0);
    side * CUBE * CUBE + cell(a) * CUBE + cell(b)
}

#[cfg(test)]
mod tests;
