//! A ball rough and the smallest enclosing ball of a cut.
//!
//! Containment in a ball is not linear, but it needs no program: a copy `s·v + t` of a cut
//! lies in the ball of centre `c` and radius `R` exactly when the cut's smallest enclosing ball
//! (centre `m`, radius `r`) scaled by `s` does, so the largest copy has `s = R / r` and
//! `t = c − s·m` in every orientation (turning the cut turns its enclosing ball with it). The
//! smallest enclosing ball is Welzl's algorithm in its move-to-front form (Gärtner's
//! "miniball"): deterministic, linear in the number of points in practice, each ball through
//! at most four support points solved in closed form.

use crate::geometry::DVec3;

/// A ball.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball {
    /// Centre.
    pub centre: DVec3,
    /// Radius (negative for the empty ball).
    pub radius: f64,
}

/// Relative slack under which a point counts as inside a ball (cocircular and cospherical
/// points, common in a symmetric cut, then never enter a support set twice).
const SLACK: f64 = 1e-12;

impl Ball {
    const EMPTY: Ball = Ball {
        centre: DVec3::ZERO,
        radius: -1.0,
    };

    /// Whether `p` lies in the ball, up to a relative rounding slack.
    pub fn contains(&self, p: DVec3) -> bool {
        self.radius >= 0.0 && p.distance(self.centre) <= self.radius * (1.0 + SLACK) + 1e-300
    }

    /// The volume `4/3 π R³`.
    pub fn volume(&self) -> f64 {
        4.0 / 3.0 * std::f64::consts::PI * self.radius.powi(3)
    }

    /// The smallest ball with `pts` on its boundary (at most four points); for a degenerate
    /// set (three on a line, four in a plane) the smallest ball through a subset holding all.
    fn through(pts: &[DVec3]) -> Ball {
        match pts.len() {
            0 => Ball::EMPTY,
            1 => Ball {
                centre: pts[0],
                radius: 0.0,
            },
            2 => Ball {
                centre: 0.5 * (pts[0] + pts[1]),
                radius: 0.5 * pts[0].distance(pts[1]),
            },
            3 => {
                let (a, b, c) = (pts[0], pts[1], pts[2]);
                let (ab, ac) = (b - a, c - a);
                let n = ab.cross(ac);
                let nn = n.length_squared();
                if nn <= 1e-24 * ab.length_squared() * ac.length_squared() {
                    return Ball::smallest_of_subsets(pts);
                }
                let centre = a
                    + (ac.length_squared() * n.cross(ab) + ab.length_squared() * ac.cross(n))
                        / (2.0 * nn);
                Ball {
                    centre,
                    radius: centre.distance(a),
                }
            }
            _ => {
                let (a, b, c, d) = (pts[0], pts[1], pts[2], pts[3]);
                let (u, v, w) = (b - a, c - a, d - a);
                let det = u.dot(v.cross(w));
                let scale = u.length() * v.length() * w.length();
                if det.abs() <= 1e-12 * scale {
                    return Ball::smallest_of_subsets(pts);
                }
                // Solve 2·[u v w]ᵀ x = (|u|², |v|², |w|²) by Cramer's rule.
                let r = DVec3::new(u.length_squared(), v.length_squared(), w.length_squared());
                let x = (r.x * v.cross(w) + r.y * w.cross(u) + r.z * u.cross(v)) / (2.0 * det);
                let centre = a + x;
                Ball {
                    centre,
                    radius: x.length(),
                }
            }
        }
    }

    /// The smallest ball through a proper subset of `pts` that holds them all.
    fn smallest_of_subsets(pts: &[DVec3]) -> Ball {
        let n = pts.len();
        let mut best = Ball::EMPTY;
        for mask in 1..(1u32 << n) - 1 {
            let sub: Vec<DVec3> = (0..n)
                .filter(|i| mask & (1 << i) != 0)
                .map(|i| pts[i])
                .collect();
            if sub.len() >= n {
                continue;
            }
            let b = Ball::through(&sub);
            if pts.iter().all(|p| b.contains(*p)) && (best.radius < 0.0 || b.radius < best.radius) {
                best = b;
            }
        }
        best
    }
}

/// The smallest ball holding every point (the empty ball for none).
pub fn enclosing_ball(pts: &[DVec3]) -> Ball {
    let mut order = pts.to_vec();
    let mut support = Vec::with_capacity(4);
    move_to_front(&mut order, pts.len(), &mut support)
}

/// Welzl's recursion over the first `end` points with `support` on the boundary; a point that
/// forced a new ball moves to the front so later passes meet it first.
fn move_to_front(pts: &mut [DVec3], end: usize, support: &mut Vec<DVec3>) -> Ball {
    let mut ball = Ball::through(support);
    if support.len() == 4 {
        return ball;
    }
    for i in 0..end {
        let p = pts[i];
        if !ball.contains(p) {
            support.push(p);
            ball = move_to_front(pts, i, support);
            support.pop();
            pts[..=i].rotate_right(1);
        }
    }
    ball
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    /// Brute force: the smallest of the balls through every 2, 3 and 4 points that holds all.
    fn brute(pts: &[DVec3]) -> f64 {
        let n = pts.len();
        let mut best = f64::INFINITY;
        let mut consider = |b: Ball| {
            if b.radius < best && pts.iter().all(|p| p.distance(b.centre) <= b.radius + 1e-12) {
                best = b.radius;
            }
        };
        for i in 0..n {
            for j in i + 1..n {
                consider(Ball::through(&[pts[i], pts[j]]));
                for k in j + 1..n {
                    consider(Ball::through(&[pts[i], pts[j], pts[k]]));
                    for l in k + 1..n {
                        consider(Ball::through(&[pts[i], pts[j], pts[k], pts[l]]));
                    }
                }
            }
        }
        best
    }

    #[test]
    fn the_enclosing_ball_is_the_brute_force_one() {
        let mut rng = SmallRng::seed_from_u64(7);
        for case in 0..40 {
            let n = 5 + case % 11;
            let pts: Vec<DVec3> = (0..n)
                .map(|_| {
                    DVec3::new(
                        rng.random_range(-1.0..1.0),
                        rng.random_range(-2.0..2.0),
                        rng.random_range(-0.5..0.5),
                    )
                })
                .collect();
            let b = enclosing_ball(&pts);
            assert!(pts.iter().all(|p| b.contains(*p)), "case {case}");
            let r = brute(&pts);
            assert!(
                (b.radius - r).abs() < 1e-12,
                "case {case}: {} vs {r}",
                b.radius
            );
        }
    }

    /// Cospherical points in a symmetric set (a cube's corners, a regular polygon with its
    /// centre lifted): the degenerate support sets still give the right ball.
    #[test]
    fn symmetric_point_sets_give_their_balls() {
        let cube: Vec<DVec3> = (0..8)
            .map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
            .collect();
        let b = enclosing_ball(&cube);
        assert!((b.centre - DVec3::splat(0.5)).length() < 1e-12);
        assert!((b.radius - 0.75f64.sqrt()).abs() < 1e-12);
        let mut ring: Vec<DVec3> = (0..16)
            .map(|k| {
                let a = k as f64 * std::f64::consts::PI / 8.0;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        ring.push(DVec3::new(0.0, 0.0, 0.9));
        let b = enclosing_ball(&ring);
        assert!(
            (b.radius - 1.0).abs() < 1e-12 && b.centre.length() < 1e-12,
            "{b:?}"
        );
    }
}
