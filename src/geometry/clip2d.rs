//! 2-D convex polygons: signed area, orientation, centroid, containment, and clipping of a
//! convex polygon by a convex polygon (Sutherland–Hodgman) or by an axis-aligned rectangle.
//!
//! Polygons are slices of [`DVec2`] vertices, closed implicitly (the last vertex joins the
//! first). A polygon with positive [`signed_area`] is counter-clockwise (CCW). The clipping
//! functions accept either orientation for both the subject and the clip polygon, keep the
//! subject's orientation in the result, and treat points within [`TOL`] of a clip edge as on
//! it, so that polygons sharing an edge tile exactly (to rounding): the pieces of a subject
//! clipped by every tile of a partition add up to the subject's area.
//!
//! The `_into` variants write into caller-owned buffers and do not allocate once the buffers
//! have grown to size, which is what the beam tracer's hot path uses.

use glam::DVec2;

/// Distance tolerance in the plane (girdle diameters): points closer than this to a clip edge
/// count as on it; consecutive vertices closer than this are merged.
pub const TOL: f64 = 1e-12;

/// 2-D cross product `a × b`.
#[inline]
pub fn cross(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Signed area (shoelace): positive for counter-clockwise polygons. 0 for fewer than 3 points.
#[inline]
pub fn signed_area(poly: &[DVec2]) -> f64 {
    let n = poly.len();
    if n < 3 {
        return 0.0;
    }
    // Relative to the first vertex: better conditioned far from the origin.
    let o = poly[0];
    let mut s = 0.0;
    for i in 1..n - 1 {
        s += cross(poly[i] - o, poly[i + 1] - o);
    }
    0.5 * s
}

/// Unsigned area.
#[inline]
pub fn area(poly: &[DVec2]) -> f64 {
    signed_area(poly).abs()
}

/// Whether the polygon is counter-clockwise (positive signed area).
pub fn is_ccw(poly: &[DVec2]) -> bool {
    signed_area(poly) > 0.0
}

/// Area centroid; the vertex mean for degenerate (zero-area) polygons; `None` when empty.
pub fn centroid(poly: &[DVec2]) -> Option<DVec2> {
    if poly.is_empty() {
        return None;
    }
    let o = poly[0];
    let (mut acc, mut total) = (DVec2::ZERO, 0.0);
    for i in 1..poly.len().saturating_sub(1) {
        let (b, c) = (poly[i] - o, poly[i + 1] - o);
        let a = cross(b, c);
        acc += a * (b + c) / 3.0;
        total += a;
    }
    if total != 0.0 {
        Some(o + acc / total)
    } else {
        Some(poly.iter().copied().sum::<DVec2>() / poly.len() as f64)
    }
}

/// Whether `p` lies inside or on the convex polygon `poly` (either orientation), within
/// distance `tol` of its edges. Degenerate polygons (zero area) contain nothing.
pub fn contains(poly: &[DVec2], p: DVec2, tol: f64) -> bool {
    let sa = signed_area(poly);
    if sa == 0.0 {
        return false;
    }
    let sign = sa.signum();
    let n = poly.len();
    (0..n).all(|i| {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let e = b - a;
        sign * cross(e, p - a) >= -tol * e.length()
    })
}

/// Whether a polygon is convex (all turns the same way, collinear vertices allowed) and has
/// positive area.
pub fn is_convex(poly: &[DVec2]) -> bool {
    let n = poly.len();
    let sa = signed_area(poly);
    if n < 3 || sa == 0.0 {
        return false;
    }
    (0..n).all(|i| {
        let (a, b, c) = (poly[i], poly[(i + 1) % n], poly[(i + 2) % n]);
        let t = cross(b - a, c - b);
        t * sa >= -TOL * (b - a).length() * (c - b).length().max(1.0)
    })
}

/// Drop the vertices of a nearly convex polygon that turn against its orientation (a hair's
/// notch left by rounding), until every turn agrees: clipping against a short edge that turns
/// the wrong way would cut along its line far beyond the notch.
pub fn make_convex(poly: &mut Vec<DVec2>) {
    let sign = signed_area(poly).signum();
    while poly.len() > 3 {
        let m = poly.len();
        let bad = (0..m).find(|&k| {
            let (a, b, c) = (poly[(k + m - 1) % m], poly[k], poly[(k + 1) % m]);
            sign * cross(b - a, c - b) < 0.0
        });
        match bad {
            Some(k) => {
                poly.remove(k);
            }
            None => break,
        }
    }
}

/// Clip `subject` by the half-plane to the left of the directed line `a → b` (times `sign`:
/// `+1` keeps the left side, `−1` the right side), appending the result to `out` (cleared
/// first).
#[inline]
fn clip_edge(subject: &[DVec2], a: DVec2, b: DVec2, sign: f64, out: &mut Vec<DVec2>) {
    let e = b - a;
    clip_by(subject, |p| sign * cross(e, p - a), TOL * e.length(), out);
}

/// Drop consecutive vertices closer than [`TOL`] (also across the wrap); clear the polygon if
/// fewer than 3 vertices remain.
fn clean(poly: &mut Vec<DVec2>) {
    if poly.is_empty() {
        return;
    }
    let mut w = 1;
    for r in 1..poly.len() {
        if poly[r].distance_squared(poly[w - 1]) > TOL * TOL {
            poly[w] = poly[r];
            w += 1;
        }
    }
    poly.truncate(w);
    while poly.len() > 1 && poly[0].distance_squared(poly[poly.len() - 1]) <= TOL * TOL {
        poly.pop();
    }
    if poly.len() < 3 {
        poly.clear();
    }
}

/// Intersection of `subject` (any polygon, either orientation) with the convex polygon `clip`
/// (either orientation), written to `out`; `scratch` is working space. `out` is empty when the
/// intersection has no area (or `clip` is degenerate). The result keeps the subject's
/// orientation. Neither buffer allocates once grown.
pub fn clip_convex_into(
    subject: &[DVec2],
    clip: &[DVec2],
    out: &mut Vec<DVec2>,
    scratch: &mut Vec<DVec2>,
) {
    out.clear();
    let sa = signed_area(clip);
    if sa == 0.0 || subject.len() < 3 {
        return;
    }
    let sign = sa.signum();
    out.extend_from_slice(subject);
    let m = clip.len();
    for i in 0..m {
        let (a, b) = (clip[i], clip[(i + 1) % m]);
        if a.distance_squared(b) == 0.0 {
            continue;
        }
        // Every vertex inside this edge (by clip_edge's own test): the step would hand the
        // polygon back unchanged, so skip it.
        let e = b - a;
        let tol = TOL * e.length();
        if out.iter().all(|&p| sign * cross(e, p - a) >= -tol) {
            continue;
        }
        clip_edge(out, a, b, sign, scratch);
        std::mem::swap(out, scratch);
        if out.len() < 3 {
            out.clear();
            return;
        }
    }
    clean(out);
}

/// Convex hull of 2-D points, counter-clockwise (Andrew's monotone chain), points within
/// 1e-12 of each other taken as one; fewer than three points come back as they are.
pub fn convex_hull(mut pts: Vec<DVec2>) -> Vec<DVec2> {
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup_by(|a, b| a.distance(*b) < 1e-12);
    if pts.len() < 3 {
        return pts;
    }
    let turn = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut lower: Vec<DVec2> = Vec::new();
    for &p in &pts {
        while lower.len() >= 2 && turn(lower[lower.len() - 2], lower[lower.len() - 1], p) <= 0.0 {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<DVec2> = Vec::new();
    for &p in pts.iter().rev() {
        while upper.len() >= 2 && turn(upper[upper.len() - 2], upper[upper.len() - 1], p) <= 0.0 {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// Intersection of `subject` with the convex polygon `clip`, allocating. See
/// [`clip_convex_into`].
pub fn clip_convex(subject: &[DVec2], clip: &[DVec2]) -> Vec<DVec2> {
    let (mut out, mut scratch) = (Vec::with_capacity(subject.len() + clip.len()), Vec::new());
    clip_convex_into(subject, clip, &mut out, &mut scratch);
    out
}

/// Clip `subject` to the vertical strip `x0 ≤ x ≤ x1` (either orientation), into `out`.
pub fn clip_strip_x_into(
    subject: &[DVec2],
    x0: f64,
    x1: f64,
    out: &mut Vec<DVec2>,
    scratch: &mut Vec<DVec2>,
) {
    // The half-planes x ≥ x0 and x ≤ x1 (clip_edge with the lines x = x0 upward, sign −1, and
    // x = x1 upward, sign +1, whose side values reduce to these coordinate differences).
    clip_side(subject, |p| p.x - x0, scratch);
    clip_side(scratch, |p| x1 - p.x, out);
    if out.len() < 3 {
        out.clear();
    }
}

/// [`clip_edge`] for an axis-aligned line, where the side value `side(p)` is a plain
/// coordinate difference (the same number `clip_edge`'s cross product gives for a unit edge
/// vector along an axis): keeps the points with `side(p) ≥ −TOL`, writing to `out` (cleared
/// first).
#[inline(always)]
pub(crate) fn clip_side(subject: &[DVec2], side: impl Fn(DVec2) -> f64, out: &mut Vec<DVec2>) {
    clip_by(subject, side, TOL, out);
}

/// The one Sutherland–Hodgman step behind [`clip_edge`] and [`clip_side`]: keeps the points
/// with `side(p) ≥ −tol`, with the crossing points of the boundary between, writing to `out`
/// (cleared first).
#[inline(always)]
fn clip_by(subject: &[DVec2], side: impl Fn(DVec2) -> f64, tol: f64, out: &mut Vec<DVec2>) {
    out.clear();
    let n = subject.len();
    if n == 0 {
        return;
    }
    let mut p = subject[n - 1];
    let mut sp = side(p);
    for &q in subject {
        let sq = side(q);
        let (p_in, q_in) = (sp >= -tol, sq >= -tol);
        if p_in != q_in {
            let t = (sp / (sp - sq)).clamp(0.0, 1.0);
            out.push(p + (q - p) * t);
        }
        if q_in {
            out.push(q);
        }
        p = q;
        sp = sq;
    }
}

/// Clip `subject` to the horizontal strip `y0 ≤ y ≤ y1` (either orientation), into `out`.
pub fn clip_strip_y_into(
    subject: &[DVec2],
    y0: f64,
    y1: f64,
    out: &mut Vec<DVec2>,
    scratch: &mut Vec<DVec2>,
) {
    // The half-planes y ≥ y0 and y ≤ y1 (clip_edge with the lines y = y0 rightward, sign +1,
    // and y = y1 rightward, sign −1).
    clip_side(subject, |p| p.y - y0, scratch);
    clip_side(scratch, |p| y1 - p.y, out);
    if out.len() < 3 {
        out.clear();
    }
}

/// Area of the intersection of `subject` with the axis-aligned rectangle `[lo, hi]`.
pub fn rect_overlap_area(subject: &[DVec2], lo: DVec2, hi: DVec2) -> f64 {
    let (mut a, mut b, mut s) = (Vec::new(), Vec::new(), Vec::new());
    clip_strip_x_into(subject, lo.x, hi.x, &mut a, &mut s);
    clip_strip_y_into(&a, lo.y, hi.y, &mut b, &mut s);
    area(&b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn make_convex_drops_a_notch_and_keeps_convex_polygons() {
        // A square whose corner (1, 1) is split into two vertices 1e-7 apart that turn the
        // wrong way: clipping against that short edge cut the square along its line.
        let mut notched = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0 - 1e-7, 1.0 - 2e-7),
            DVec2::new(0.0, 1.0),
        ];
        let subject = [
            DVec2::new(0.2, 0.2),
            DVec2::new(0.8, 0.2),
            DVec2::new(0.8, 0.8),
            DVec2::new(0.2, 0.8),
        ];
        let broken = area(&clip_convex(&subject, &notched));
        assert!(broken < 0.3, "{broken}");
        make_convex(&mut notched);
        assert_eq!(notched.len(), 4);
        assert!((area(&clip_convex(&subject, &notched)) - 0.36).abs() < 1e-12);
        let mut square = subject.to_vec();
        make_convex(&mut square);
        assert_eq!(square, subject.to_vec());
    }

    /// The strip clips (side values as coordinate differences) give exactly what the general
    /// edge clip gives for the same axis-aligned lines.
    #[test]
    fn strips_match_the_general_edge_clip() {
        let mut rnd = crate::testkit::uniform(12345u64);
        let (mut out, mut scratch, mut a, mut b) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut cut = 0;
        for _ in 0..500 {
            let n = 3 + (rnd() * 6.0) as usize;
            let (cx, cy, r, ph) = (rnd() - 0.5, rnd() - 0.5, 0.05 + rnd() * 0.5, rnd() * 6.0);
            let poly: Vec<DVec2> = (0..n)
                .map(|i| {
                    let th = ph + i as f64 * std::f64::consts::TAU / n as f64;
                    DVec2::new(cx + r * th.cos(), cy + r * th.sin())
                })
                .collect();
            let (lo, hi) = (rnd() - 0.6, rnd() * 0.3);
            let (lo, hi) = (lo, lo + hi);
            clip_strip_x_into(&poly, lo, hi, &mut out, &mut scratch);
            clip_edge(
                &poly,
                DVec2::new(lo, 0.0),
                DVec2::new(lo, 1.0),
                -1.0,
                &mut a,
            );
            clip_edge(&a, DVec2::new(hi, 0.0), DVec2::new(hi, 1.0), 1.0, &mut b);
            if b.len() < 3 {
                b.clear();
            }
            assert_eq!(out, b);
            cut += (!out.is_empty() && out.len() != poly.len()) as usize;
            clip_strip_y_into(&poly, lo, hi, &mut out, &mut scratch);
            clip_edge(&poly, DVec2::new(0.0, lo), DVec2::new(1.0, lo), 1.0, &mut a);
            clip_edge(&a, DVec2::new(0.0, hi), DVec2::new(1.0, hi), -1.0, &mut b);
            if b.len() < 3 {
                b.clear();
            }
            assert_eq!(out, b);
        }
        assert!(cut > 100, "too few polygons were cut: {cut}");
    }

    fn sq(x0: f64, y0: f64, s: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(x0, y0),
            DVec2::new(x0 + s, y0),
            DVec2::new(x0 + s, y0 + s),
            DVec2::new(x0, y0 + s),
        ]
    }

    fn ngon(n: usize, r: f64, c: DVec2, phase: f64) -> Vec<DVec2> {
        (0..n)
            .map(|k| {
                let a = phase + k as f64 * std::f64::consts::TAU / n as f64;
                c + r * DVec2::new(a.cos(), a.sin())
            })
            .collect()
    }

    #[test]
    fn area_orientation_centroid() {
        let s = sq(1.0, 2.0, 2.0);
        assert_eq!(signed_area(&s), 4.0);
        let mut r = s.clone();
        r.reverse();
        assert_eq!(signed_area(&r), -4.0);
        assert!(is_ccw(&s) && !is_ccw(&r));
        assert!((centroid(&s).unwrap() - DVec2::new(2.0, 3.0)).length() < 1e-15);
        assert_eq!(signed_area(&s[..2]), 0.0);
        assert!(centroid(&[]).is_none());
        let h = ngon(6, 1.0, DVec2::ZERO, 0.1);
        assert!((area(&h) - 1.5 * 3f64.sqrt()).abs() < 1e-14);
        assert!(is_convex(&h) && is_convex(&r));
        let dart = vec![
            DVec2::ZERO,
            DVec2::new(2.0, 0.0),
            DVec2::new(1.0, 0.2),
            DVec2::new(1.0, 2.0),
        ];
        assert!(!is_convex(&dart));
    }

    #[test]
    fn containment_with_tolerance() {
        let s = sq(0.0, 0.0, 1.0);
        assert!(contains(&s, DVec2::new(0.5, 0.5), 0.0));
        assert!(contains(&s, DVec2::new(1.0, 0.5), 0.0));
        assert!(!contains(&s, DVec2::new(1.0 + 1e-9, 0.5), 1e-12));
        assert!(contains(&s, DVec2::new(1.0 + 1e-13, 0.5), 1e-12));
        let mut r = s.clone();
        r.reverse();
        assert!(contains(&r, DVec2::new(0.25, 0.75), 0.0));
        assert!(!contains(
            &[DVec2::ZERO, DVec2::X, DVec2::new(2.0, 0.0)],
            DVec2::ZERO,
            1.0
        ));
    }

    #[test]
    fn overlapping_squares() {
        let a = sq(0.0, 0.0, 2.0);
        let b = sq(1.0, 1.0, 2.0);
        let c = clip_convex(&a, &b);
        assert!((area(&c) - 1.0).abs() < 1e-15);
        assert!(is_ccw(&c));
        // Clip polygon clockwise: same result; subject clockwise: result clockwise.
        let mut bc = b.clone();
        bc.reverse();
        assert!((area(&clip_convex(&a, &bc)) - 1.0).abs() < 1e-15);
        let mut ac = a.clone();
        ac.reverse();
        let c2 = clip_convex(&ac, &b);
        assert!((signed_area(&c2) + 1.0).abs() < 1e-15);
    }

    #[test]
    fn containment_and_disjoint_and_touching() {
        let big = sq(-5.0, -5.0, 10.0);
        let small = ngon(7, 1.0, DVec2::new(0.3, -0.2), 0.4);
        assert!((area(&clip_convex(&small, &big)) - area(&small)).abs() < 1e-14);
        assert!((area(&clip_convex(&big, &small)) - area(&small)).abs() < 1e-13);
        assert!(clip_convex(&sq(0.0, 0.0, 1.0), &sq(3.0, 0.0, 1.0)).is_empty());
        // Sharing only an edge or a corner: no area.
        assert!(area(&clip_convex(&sq(0.0, 0.0, 1.0), &sq(1.0, 0.0, 1.0))) < 1e-15);
        assert!(area(&clip_convex(&sq(0.0, 0.0, 1.0), &sq(1.0, 1.0, 1.0))) < 1e-15);
        // Identical polygons.
        let h = ngon(5, 0.7, DVec2::new(1.0, 1.0), 0.0);
        assert!((area(&clip_convex(&h, &h)) - area(&h)).abs() < 1e-14);
    }

    #[test]
    fn degenerate_inputs() {
        let s = sq(0.0, 0.0, 1.0);
        let line = vec![DVec2::ZERO, DVec2::new(1.0, 1.0), DVec2::new(2.0, 2.0)];
        assert!(clip_convex(&s, &line).is_empty());
        assert!(clip_convex(&line, &s).len() < 3 || area(&clip_convex(&line, &s)) == 0.0);
        assert!(clip_convex(&[], &s).is_empty());
        assert!(clip_convex(&s, &[]).is_empty());
        // A clip polygon with a repeated vertex still works.
        let rep = vec![
            DVec2::ZERO,
            DVec2::new(0.5, 0.0),
            DVec2::new(0.5, 0.0),
            DVec2::new(0.5, 0.5),
            DVec2::new(0.0, 0.5),
        ];
        assert!((area(&clip_convex(&s, &rep)) - 0.25).abs() < 1e-15);
    }

    #[test]
    fn pieces_of_a_partition_tile_the_subject() {
        // A fan partition of a convex 9-gon into triangles around an interior point, and a
        // subject polygon overlapping it: the pieces' areas add up to the overlap.
        let outer = ngon(9, 1.0, DVec2::ZERO, 0.05);
        let p = DVec2::new(0.13, -0.21);
        let subject = ngon(6, 0.8, DVec2::new(0.2, 0.1), 0.3);
        let mut total = 0.0;
        for i in 0..9 {
            let tri = [p, outer[i], outer[(i + 1) % 9]];
            total += area(&clip_convex(&subject, &tri));
        }
        let whole = area(&clip_convex(&subject, &outer));
        assert!(
            (total - whole).abs() < 1e-14 * whole.max(1.0),
            "{total} vs {whole}"
        );
        // A grid of squares partitioning the plane around the subject.
        let mut total = 0.0;
        for i in -4..4 {
            for j in -4..4 {
                total += rect_overlap_area(
                    &subject,
                    DVec2::new(i as f64 * 0.25, j as f64 * 0.25),
                    DVec2::new((i + 1) as f64 * 0.25, (j + 1) as f64 * 0.25),
                );
            }
        }
        assert!((total - area(&subject)).abs() < 1e-14, "{total}");
    }

    #[test]
    fn near_tangent_and_tiny() {
        // A clip edge that passes within TOL/10 of a subject vertex: no spurious sliver.
        let s = sq(0.0, 0.0, 1.0);
        let c = vec![
            DVec2::new(1.0 + 1e-13, -1.0),
            DVec2::new(3.0, -1.0),
            DVec2::new(3.0, 3.0),
            DVec2::new(1.0 + 1e-13, 3.0),
        ];
        assert!(area(&clip_convex(&s, &c)) < 1e-12);
        // Tiny polygons keep their exact area.
        let t = sq(0.1, 0.1, 1e-6);
        assert!((area(&clip_convex(&t, &s)) - 1e-12).abs() < 1e-21);
    }
}
