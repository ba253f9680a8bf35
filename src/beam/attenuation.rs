//! Beer–Lambert attenuation over a footprint, in closed form: how the beam tracer absorbs body
//! colour ([`TraceOptions::absorption`](super::TraceOptions::absorption)).
//!
//! Inside a convex stone every ray of a parallel beam has travelled a path length that is an
//! affine function of where it sits in the beam's cross-section (the footprint's coordinates,
//! the footprint map of `src/beam/footprint.rs`), so the light a beam keeps after absorption `α` is
//! `∫_P exp(−α · L(x)) dA` over the footprint polygon `P`, with `L` affine. For an affine
//! exponent `φ(x)` this integral is exact: split `P` into a fan of triangles, and over a
//! triangle with vertex values `φ0, φ1, φ2`
//!
//! `∫_T e^φ dA = 2 · area(T) · e[φ0, φ1, φ2]`,
//!
//! the second divided difference of `exp` at the three values (Hermite–Genocchi). The divided
//! difference is computed without cancellation: by its power series when the values are close,
//! by differences of first divided differences (`expm1`) when they are far apart.
//!
//! ```
//! use facetlab::beam::attenuation::exp_integral;
//! use glam::{DVec2, DVec3};
//!
//! // A unit square, exponent −x: ∫∫ e^−x dx dy = 1 − e^−1.
//! let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
//! let v = exp_integral(&square, DVec2::new(-1.0, 0.0), 0.0);
//! assert!((v - (1.0 - (-1.0f64).exp())).abs() < 1e-15);
//! ```

use glam::{DVec2, DVec3};

/// `∫_P exp(g · x + c) dA` over the polygon `P` (vertices in order, either orientation; the
/// result is positive for a counter-clockwise polygon and its negative for a clockwise one).
pub fn exp_integral(polygon: &[DVec2], g: DVec2, c: f64) -> f64 {
    if polygon.len() < 3 {
        return 0.0;
    }
    let p0 = polygon[0];
    let phi = |p: DVec2| g.dot(p) + c;
    let f0 = phi(p0);
    polygon[1..]
        .windows(2)
        .map(|w| {
            let twice_area = (w[0] - p0).perp_dot(w[1] - p0);
            twice_area * exp_dd2(f0, phi(w[0]), phi(w[1]))
        })
        .sum()
}

/// The mean of `exp(g · x + c)` over the polygon: [`exp_integral`] over its area (1 for a
/// polygon without area and `g = 0`, `c = 0`; `exp(c)` at its first vertex when it has none).
pub fn exp_mean(polygon: &[DVec2], g: DVec2, c: f64) -> f64 {
    let area: f64 = if polygon.len() < 3 {
        0.0
    } else {
        polygon[1..]
            .windows(2)
            .map(|w| 0.5 * (w[0] - polygon[0]).perp_dot(w[1] - polygon[0]))
            .sum()
    };
    if area.abs() <= 1e-300 {
        return polygon.first().map_or(c.exp(), |p| (g.dot(*p) + c).exp());
    }
    exp_integral(polygon, g, c) / area
}

/// The mean of `exp(φ)` over a planar polygon in space (vertices in order, on a plane with
/// normal `normal`), `φ` affine on that plane and given by its values at the vertices. The
/// mean is that of any affine image of the polygon, so it is the footprint's mean too.
/// `exp(φ)` at the first vertex for a polygon without area.
pub(crate) fn exp_mean_planar(polygon: &[DVec3], normal: DVec3, phi: &[f64]) -> f64 {
    if polygon.len() < 3 || phi.len() != polygon.len() {
        return phi.first().map_or(1.0, |f| f.exp());
    }
    let p0 = polygon[0];
    let (mut sum, mut twice_area) = (0.0f64, 0.0f64);
    for i in 1..polygon.len() - 1 {
        let t = normal.dot((polygon[i] - p0).cross(polygon[i + 1] - p0));
        sum += t * exp_dd2(phi[0], phi[i], phi[i + 1]);
        twice_area += t;
    }
    if twice_area.abs() <= 1e-300 || !sum.is_finite() {
        return phi[0].exp();
    }
    2.0 * sum / twice_area
}

/// The first divided difference of `exp`: `(e^b − e^a) / (b − a)`, `e^a` when `a = b`.
pub fn exp_dd1(a: f64, b: f64) -> f64 {
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    let d = hi - lo;
    if d == 0.0 {
        lo.exp()
    } else {
        lo.exp() * d.exp_m1() / d
    }
}

/// The second divided difference of `exp` at `a, b, c` (any order, equal values allowed):
/// `∫∫_{s,t ≥ 0, s+t ≤ 1} exp(a + s(b − a) + t(c − a)) ds dt`, so that a triangle's integral
/// of `e^φ` is twice its area times this at its vertex values.
pub fn exp_dd2(a: f64, b: f64, c: f64) -> f64 {
    let mut v = [a, b, c];
    v.sort_by(f64::total_cmp);
    let [x0, x1, x2] = v;
    let spread = x2 - x0;
    if spread > 1.0 {
        // Far apart: the outer first differences differ by a factor of at least e^(spread/2)
        // over their own size, so their difference keeps its precision.
        return (exp_dd1(x1, x2) - exp_dd1(x0, x1)) / spread;
    }
    // Close: e[x0, x1, x2] = e^x0 · e[0, u, w] and, as (x^n)[0, u, w] = h_(n−2)(u, w) (the
    // complete homogeneous polynomial of degree n − 2), e[0, u, w] = Σ_k h_k(u, w) / (k + 2)!.
    let (u, w) = (x1 - x0, x2 - x0);
    let mut h = 1.0; // h_0(u, w)
    let mut u_pow = 1.0; // u^k
    let mut sum = 0.5; // h_0 / 2!
    let mut fact = 2.0;
    for k in 1..40 {
        u_pow *= u;
        // h_k(u, w) = w · h_(k−1)(u, w) + u^k
        h = w * h + u_pow;
        fact *= (k + 2) as f64;
        let term = h / fact;
        sum += term;
        if term.abs() < 1e-18 * sum.abs() {
            break;
        }
    }
    x0.exp() * sum
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// `∫_T e^φ` by subdividing the triangle into `n²` small triangles, each integrated by the
    /// 7-point degree-5 rule (Radon): independent of the divided differences.
    pub(crate) fn subdivided(t: [DVec2; 3], phi: &dyn Fn(DVec2) -> f64, n: usize) -> f64 {
        let (a, b, c) = (t[0], t[1], t[2]);
        let at = |i: f64, j: f64| a + (b - a) * (i / n as f64) + (c - a) * (j / n as f64);
        let s15 = 15f64.sqrt();
        let (w0, w1, w2) = (9.0 / 40.0, (155.0 - s15) / 1200.0, (155.0 + s15) / 1200.0);
        let (a1, b1) = ((6.0 - s15) / 21.0, (9.0 + 2.0 * s15) / 21.0);
        let (a2, b2) = ((6.0 + s15) / 21.0, (9.0 - 2.0 * s15) / 21.0);
        let rule = |p: DVec2, q: DVec2, r: DVec2| {
            let area = 0.5 * (q - p).perp_dot(r - p);
            let bary = |l0: f64, l1: f64, l2: f64| phi(p * l0 + q * l1 + r * l2).exp();
            area * (w0 * bary(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0)
                + w1 * (bary(a1, a1, b1) + bary(a1, b1, a1) + bary(b1, a1, a1))
                + w2 * (bary(a2, a2, b2) + bary(a2, b2, a2) + bary(b2, a2, a2)))
        };
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n - i {
                let (fi, fj) = (i as f64, j as f64);
                sum += rule(at(fi, fj), at(fi + 1.0, fj), at(fi, fj + 1.0));
                if i + j + 1 < n {
                    sum += rule(at(fi + 1.0, fj), at(fi + 1.0, fj + 1.0), at(fi, fj + 1.0));
                }
            }
        }
        sum
    }

    #[test]
    fn the_closed_form_matches_a_fine_subdivision() {
        // Footprints as the tracer makes them: small polygons, path lengths up to a few W,
        // absorption from faint to dark (exponents 0 to about −30).
        let polygons: Vec<Vec<DVec2>> = vec![
            vec![
                DVec2::new(0.0, 0.0),
                DVec2::new(0.3, 0.05),
                DVec2::new(0.1, 0.4),
            ],
            vec![
                DVec2::new(-0.2, -0.1),
                DVec2::new(0.25, -0.15),
                DVec2::new(0.35, 0.2),
                DVec2::new(0.05, 0.38),
                DVec2::new(-0.3, 0.12),
            ],
        ];
        for poly in &polygons {
            for (g, c) in [
                (DVec2::ZERO, -0.7),
                (DVec2::new(-1.3, 0.4), -0.2),
                (DVec2::new(1e-7, -2e-7), -3.0),
                (DVec2::new(-25.0, 18.0), -12.0),
                (DVec2::new(3.0, 0.0), 0.5),
            ] {
                let phi = |p: DVec2| g.dot(p) + c;
                let brute: f64 = poly[1..]
                    .windows(2)
                    .map(|w| subdivided([poly[0], w[0], w[1]], &phi, 48))
                    .sum();
                let exact = exp_integral(poly, g, c);
                assert!(
                    (exact - brute).abs() <= 1e-10 * brute.abs().max(1e-300),
                    "g {g} c {c}: {exact} against {brute}"
                );
            }
        }
    }

    #[test]
    fn divided_differences_agree_with_their_closed_forms() {
        // Distinct, well separated values: the textbook formula is exact enough there.
        let (a, b, c) = (-3.0f64, -1.0, 0.5);
        let direct = a.exp() / ((a - b) * (a - c))
            + b.exp() / ((b - a) * (b - c))
            + c.exp() / ((c - a) * (c - b));
        assert!((exp_dd2(a, b, c) - direct).abs() < 1e-14 * direct);
        // Order does not matter; equal values give e^x / 2.
        assert_eq!(exp_dd2(a, b, c), exp_dd2(c, a, b));
        assert!((exp_dd2(0.3, 0.3, 0.3) - 0.3f64.exp() / 2.0).abs() < 1e-16);
        // Two equal, one apart: e[x, x, y] = (e^y − e^x − (y − x) e^x) / (y − x)².
        for (x, y) in [(0.0f64, 0.4f64), (-2.0, 1.5), (-8.0, -7.9999)] {
            let d = y - x;
            let closed = x.exp() * (d.exp_m1() - d) / (d * d);
            let got = exp_dd2(x, x, y);
            assert!(
                (got - closed).abs() < 1e-12 * closed,
                "{x} {y}: {got} {closed}"
            );
        }
        // Either side of the switch between series and differences (spread 1), against the
        // textbook formula (well conditioned there): 2 (e^c − 2 e^0.5 + 1)-like values.
        for c in [1.0 - 1e-9, 1.0 + 1e-9] {
            let (a, b) = (0.0f64, 0.5f64);
            let direct = a.exp() / ((a - b) * (a - c))
                + b.exp() / ((b - a) * (b - c))
                + c.exp() / ((c - a) * (c - b));
            let got = exp_dd2(a, b, c);
            assert!((got - direct).abs() < 1e-14, "{c}: {got} {direct}");
        }
    }

    #[test]
    fn a_slab_keeps_exp_of_minus_alpha_d_and_the_mean_is_a_mean() {
        // Constant path length d: the footprint keeps e^(−α d) of its light everywhere.
        let tri = [DVec2::ZERO, DVec2::new(0.2, 0.0), DVec2::new(0.0, 0.2)];
        let (alpha, d) = (1.7, 0.35);
        assert!((exp_mean(&tri, DVec2::ZERO, -alpha * d) - (-alpha * d).exp()).abs() < 1e-15);
        // A clockwise polygon integrates to the negative; the mean is the same.
        let cw = [tri[0], tri[2], tri[1]];
        let g = DVec2::new(-2.0, 0.5);
        assert!((exp_integral(&cw, g, 0.1) + exp_integral(&tri, g, 0.1)).abs() < 1e-16);
        assert!((exp_mean(&cw, g, 0.1) - exp_mean(&tri, g, 0.1)).abs() < 1e-15);
        // The mean lies between the exponent's extremes over the polygon.
        let m = exp_mean(&tri, g, 0.1);
        let vals: Vec<f64> = tri.iter().map(|p| (g.dot(*p) + 0.1).exp()).collect();
        let (lo, hi) = vals
            .iter()
            .fold((f64::MAX, f64::MIN), |(l, h), v| (l.min(*v), h.max(*v)));
        assert!(lo < m && m < hi);
    }
}
