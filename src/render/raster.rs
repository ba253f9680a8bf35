//! A square image of the stone with exact area coverage: a convex polygon adds its weight
//! times the exact area it covers in each pixel, so an image changes continuously as the
//! polygons move.

use crate::geometry::clip2d::{self, clip_side};
use glam::DVec2;

/// `clip2d::area` of `clip2d::clip_strip_x_into(subject, x0, x1)`, with the very same
/// arithmetic in the same order (so the same number to the last bit), but without building
/// the clipped polygon: the first half-plane's output goes to `buf` (indexed, grown only when
/// too short), the second's straight into the shoelace sum.
///
/// `sx0`, `sx1` are the smallest and largest x of `subject`: where a half-plane holds all of
/// it (with room to spare for rounding) its clip would copy the polygon unchanged, and is
/// skipped.
#[inline]
fn slab_area(
    subject: &[DVec2],
    x0: f64,
    x1: f64,
    (sx0, sx1): (f64, f64),
    buf: &mut Vec<DVec2>,
) -> f64 {
    let n = subject.len();
    if n == 0 {
        return 0.0;
    }
    // Every point has x − x0 ≥ sx0 − x0 ≥ 0 (rounding is monotone): all kept.
    let left_all = sx0 - x0 >= 0.0;
    // x1 − x ≥ 0 for every point of the subject, and the first clip's new points lie within
    // rounding of x0 < x1 or of the subject's x-range: all kept (tolerance 1e-12).
    let right_all = x1 - sx1 >= 0.0;
    if left_all && right_all {
        return clip2d::area(subject);
    }
    // Each edge emits at most two points.
    if buf.len() < 2 * n {
        buf.resize(2 * n, DVec2::ZERO);
    }
    let tol = clip2d::TOL;
    let m = if left_all {
        0
    } else {
        clip_x0(subject, x0, buf)
    };
    let first = if left_all { subject } else { &buf[..m] };
    if first.is_empty() {
        return 0.0;
    }
    if right_all {
        return clip2d::area(first);
    }
    // x ≤ x1, side value x1 − p.x, each emitted vertex fed to the shoelace sum of
    // `clip2d::signed_area` (relative to the first vertex; pairs (1, 2), (2, 3), …).
    let m = first.len();
    let (mut count, mut o, mut prev, mut s) = (0usize, DVec2::ZERO, DVec2::ZERO, 0.0);
    let mut emit = |v: DVec2| {
        if count == 0 {
            o = v;
        } else if count >= 2 {
            s += clip2d::cross(prev - o, v - o);
        }
        prev = v;
        count += 1;
    };
    let mut p = first[m - 1];
    let mut sp = x1 - p.x;
    for &q in first {
        let sq = x1 - q.x;
        let (p_in, q_in) = (sp >= -tol, sq >= -tol);
        if p_in != q_in {
            let t = (sp / (sp - sq)).clamp(0.0, 1.0);
            emit(p + (q - p) * t);
        }
        if q_in {
            emit(q);
        }
        p = q;
        sp = sq;
    }
    // Fewer than three points: clip_strip_x_into gives an empty polygon, of area 0.
    if count < 3 {
        0.0
    } else {
        (0.5 * s).abs()
    }
}

/// `v.floor() as i64` (saturating; 0 for NaN) without a call to the `floor` routine (the
/// default x86-64 target has no rounding instruction).
#[inline]
pub(crate) fn floor_i64(v: f64) -> i64 {
    let t = v as i64;
    if (t as f64) > v {
        t.saturating_sub(1)
    } else {
        t
    }
}

/// `v.ceil() as i64` (saturating; 0 for NaN), as [`floor_i64`].
#[inline]
pub(crate) fn ceil_i64(v: f64) -> i64 {
    let t = v as i64;
    if (t as f64) < v {
        t.saturating_add(1)
    } else {
        t
    }
}

/// The range of x over which the horizontal segments at heights `y0` and `y1` both lie
/// inside the convex polygon `poly` (orientation `orient`, the sign of its signed area):
/// every pixel of the strip between them whose x-range lies in it is wholly covered. Empty
/// (lo > hi) when there is none.
fn interior_x(poly: &[DVec2], orient: f64, y0: f64, y1: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    let mut p = poly[poly.len() - 1];
    for &q in poly {
        let d = q - p;
        let k = orient * d.y;
        if k == 0.0 {
            // A horizontal edge bounds y only: it must hold both heights on its inner side.
            if orient * d.x * (y0 - p.y) < 0.0 || orient * d.x * (y1 - p.y) < 0.0 {
                return (f64::INFINITY, f64::NEG_INFINITY);
            }
        } else {
            // Inside: orient · (d.x (y − p.y) − d.y (x − p.x)) ≥ 0.
            let xa = p.x + d.x * (y0 - p.y) / d.y;
            let xb = p.x + d.x * (y1 - p.y) / d.y;
            if k > 0.0 {
                hi = hi.min(xa.min(xb));
            } else {
                lo = lo.max(xa.max(xb));
            }
        }
        p = q;
    }
    (lo, hi)
}

/// The x ≥ x0 clip of clip2d's clip_side (side value p.x − x0), written by index into
/// `buf` (at least twice as long as `subject`); returns the number of points.
#[inline]
fn clip_x0(subject: &[DVec2], x0: f64, buf: &mut [DVec2]) -> usize {
    let n = subject.len();
    let tol = clip2d::TOL;
    let mut m = 0;
    let mut p = subject[n - 1];
    let mut sp = p.x - x0;
    for &q in subject {
        let sq = q.x - x0;
        let (p_in, q_in) = (sp >= -tol, sq >= -tol);
        if p_in != q_in {
            let t = (sp / (sp - sq)).clamp(0.0, 1.0);
            buf[m] = p + (q - p) * t;
            m += 1;
        }
        if q_in {
            buf[m] = q;
            m += 1;
        }
        p = q;
        sp = sq;
    }
    m
}

/// `clip2d::clip_strip_y_into(poly, y0, y1)` (the same points to the last bit), skipping
/// either half-plane clip that would keep every point: `lo_y`, `hi_y` are the polygon's
/// smallest and largest y.
fn strip_y(
    poly: &[DVec2],
    (lo_y, hi_y): (f64, f64),
    (y0, y1): (f64, f64),
    out: &mut Vec<DVec2>,
    scratch: &mut Vec<DVec2>,
) {
    // As in slab_area: all points (and the first clip's new points, within rounding) kept.
    let bottom_all = lo_y - y0 >= 0.0;
    let top_all = y1 - hi_y >= 0.0;
    match (bottom_all, top_all) {
        (true, true) => {
            out.clear();
            out.extend_from_slice(poly);
        }
        (true, false) => clip_side(poly, |p| y1 - p.y, out),
        (false, true) => clip_side(poly, |p| p.y - y0, out),
        (false, false) => {
            clip_side(poly, |p| p.y - y0, scratch);
            clip_side(scratch, |p| y1 - p.y, out);
        }
    }
    if out.len() < 3 {
        out.clear();
    }
}

/// A symmetry of the pixel grid of a square image centred on the origin: one of the eight
/// maps `(x, y) ↦ (a x + b y, c x + d y)` with `[a, b, c, d]` a signed permutation matrix
/// (quarter turns and mirrors through the axes and diagonals). Such a map takes pixels onto
/// pixels, so the coverage of a polygon's image under it is the polygon's coverage with the
/// pixels moved ([`Raster::map_coverage`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GridMap([i8; 4]);

impl GridMap {
    /// The identity.
    pub const IDENTITY: GridMap = GridMap([1, 0, 0, 1]);

    /// The grid symmetry a 2×2 map `[a, b, c, d]` is, when every entry is within 1e-9 of 0
    /// or ±1 and they form a signed permutation: an orthogonal map computed in floating point
    /// (a quarter turn), or a stone's mirror found to ~1e-11 (a polygon's coverage then moves
    /// by ~1e-9 of a pixel at most, as little as the symmetry is exact).
    pub fn of(m: [f64; 4]) -> Option<GridMap> {
        let mut g = [0i8; 4];
        for (gi, &x) in g.iter_mut().zip(&m) {
            let r = x.round();
            if !((x - r).abs() <= 1e-9 && r.abs() <= 1.0) {
                return None;
            }
            *gi = r as i8;
        }
        let [a, b, c, d] = g;
        let ok = (a != 0 && d != 0 && b == 0 && c == 0) || (a == 0 && d == 0 && b != 0 && c != 0);
        ok.then_some(GridMap(g))
    }

    /// `self ∘ other⁻¹` (the inverse of a signed permutation is its transpose).
    pub fn after_inverse_of(self, other: GridMap) -> GridMap {
        let [a, b, c, d] = self.0;
        // other⁻¹ = otherᵀ = [p, r, q, s] for other = [p, q, r, s].
        let [p, q, r, s] = other.0;
        GridMap([a * p + b * q, a * r + b * s, c * p + d * q, c * r + d * s])
    }
}

/// The exact area a convex polygon covers in each pixel it touches (pixel index, area), for
/// images of one size: computed once by [`Raster::coverage_into`], added to any number of
/// images of that size with [`Raster::add_coverage`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Coverage {
    /// Row-major pixel index and covered area (≥ 0), each pixel at most once.
    pub cells: Vec<(usize, f64)>,
    strip: Vec<DVec2>,
    cell: Vec<DVec2>,
    scratch: Vec<DVec2>,
}

/// Exact area coverage of many convex polygons at once, by accumulation (the scan-converter
/// of font rasterisers, in double precision): each polygon edge adds, to the cells it
/// crosses, its signed height there split between the cell and the next one by where it
/// crosses; a running sum along each row then turns those into the area every polygon
/// covers in every pixel. The work per polygon is proportional to its perimeter in pixels,
/// not its area, and polygons add linearly (each with its values), so one pass of running
/// sums at the end serves them all. The result is the same as [`Raster::add_polygon`] for
/// each polygon, to rounding.
///
/// An accumulator holds the rows `rows.0 .. rows.1` of an `n × n` image over
/// `[−half, half]²` (row 0 at the bottom) with `channels` values per pixel, so an image can
/// be filled in bands of rows, one per thread.
#[derive(Clone, Debug)]
pub struct Accumulator {
    n: usize,
    half: f64,
    rows: (usize, usize),
    channels: usize,
    /// Per row of the band: n + 2 cells (the last ones take carries past the right edge),
    /// `channels` values each.
    acc: Vec<f64>,
    /// Runs of equal values along a row (their running sum is added to `acc`'s).
    acc2: Vec<f64>,
}

impl Accumulator {
    /// An empty accumulator for rows `rows.0 .. rows.1` of an `n × n` image.
    pub fn new(n: usize, half: f64, rows: (usize, usize), channels: usize) -> Accumulator {
        let n = n.max(1);
        let rows = (rows.0.min(n), rows.1.min(n).max(rows.0.min(n)));
        Accumulator {
            n,
            half,
            rows,
            channels,
            acc: vec![0.0; (rows.1 - rows.0) * (n + 2) * channels],
            acc2: vec![0.0; (rows.1 - rows.0) * (n + 2) * channels],
        }
    }

    /// Empty again, for rows `rows.0 .. rows.1` (of the same image and channels): the same
    /// as a new accumulator, reusing this one's memory (a fresh one is fresh pages, and a
    /// page's first touch costs more than clearing it).
    pub fn reset(&mut self, rows: (usize, usize)) {
        let n = self.n;
        self.rows = (rows.0.min(n), rows.1.min(n).max(rows.0.min(n)));
        let len = (self.rows.1 - self.rows.0) * (n + 2) * self.channels;
        for a in [&mut self.acc, &mut self.acc2] {
            a.clear();
            a.resize(len, 0.0);
        }
    }

    /// Add the convex polygon `poly` (image coordinates, either orientation) with `values`
    /// per unit area (one per channel; missing ones count as 0).
    pub fn add_polygon(&mut self, poly: &[DVec2], values: &[f64]) {
        if poly.len() < 3 || !(self.half > 0.0 && self.half.is_finite()) {
            return;
        }
        let s = clip2d::signed_area(poly);
        if s.is_nan() || s == 0.0 {
            return;
        }
        let c = self.channels.min(values.len());
        // Counter-clockwise polygons (positive area) accumulate positive coverage with the
        // sign convention of `add_line`.
        let sign = if s > 0.0 { -1.0 } else { 1.0 };
        let mut v = [0.0; 8];
        for (k, x) in values.iter().take(c.min(8)).enumerate() {
            v[k] = sign * x;
        }
        if v.iter().all(|&x| x == 0.0 || !x.is_finite()) {
            return;
        }
        let k = self.n as f64 / (2.0 * self.half);
        let half = self.half;
        let to_px = |p: DVec2| DVec2::new((p.x + half) * k, (p.y + half) * k);
        let mut a = to_px(poly[poly.len() - 1]);
        for &q in poly {
            let b = to_px(q);
            self.add_line(a, b, &v[..c.min(8)]);
            a = b;
        }
    }

    /// One edge from `a` to `b` in pixel units.
    #[inline]
    fn add_line(&mut self, a: DVec2, b: DVec2, v: &[f64]) {
        if !(a.is_finite() && b.is_finite()) || a.y == b.y {
            return;
        }
        let (dir, p, q) = if a.y < b.y { (1.0, a, b) } else { (-1.0, b, a) };
        let (r0, r1) = (self.rows.0 as f64, self.rows.1 as f64);
        let (y_lo, y_hi) = (p.y.max(r0), q.y.min(r1));
        if y_lo >= y_hi {
            return;
        }
        let n = self.n as f64;
        let dxdy = (q.x - p.x) / (q.y - p.y);
        let width = self.n + 2;
        let j_first = floor_i64(y_lo) as usize;
        let j_last = (ceil_i64(y_hi) as usize).min(self.rows.1);
        for j in j_first..j_last {
            let y0 = (j as f64).max(y_lo);
            let y1 = ((j + 1) as f64).min(y_hi);
            let dy = y1 - y0;
            if dy <= 0.0 {
                continue;
            }
            let x0 = p.x + (y0 - p.y) * dxdy;
            let x1 = p.x + (y1 - p.y) * dxdy;
            let row = (j - self.rows.0) * width;
            let (xl, xr) = if x0 <= x1 { (x0, x1) } else { (x1, x0) };
            let il = floor_i64(xl);
            if il == floor_i64(xr) || xr == (il + 1) as f64 {
                // Within one column: the cell takes dy times the share right of the
                // crossing, the next cell the rest. Left of the image the whole height goes
                // to column 0 (it covers all of it); right of it, nothing shows.
                if il >= self.n as i64 {
                    continue;
                }
                let (i, m) = if il < 0 {
                    (0, 0.0)
                } else {
                    (il as usize, 0.5 * (x0 + x1) - il as f64)
                };
                self.put(row + i, dir * dy, m, v);
                continue;
            }
            // Across several columns: split at every column line it crosses, the row's height
            // shared in proportion to width (per row, so that the pieces add up to dy even for
            // a nearly vertical edge whose x-range in the row is rounding).
            let dydx = dy / (xr - xl);
            if xl < 0.0 {
                self.put(row, dir * (xr.min(0.0) - xl) * dydx, 0.0, v);
            }
            let xa = xl.max(0.0);
            let end = xr.min(n);
            if xa >= end {
                continue;
            }
            // The first cell's piece, then whole cells (each the same height, crossed in its
            // middle), then the last cell's piece.
            let ia = floor_i64(xa) as usize;
            let xb = ((ia + 1) as f64).min(end);
            self.put(
                row + ia,
                dir * (xb - xa) * dydx,
                0.5 * (xa + xb) - ia as f64,
                v,
            );
            if xb >= end {
                continue;
            }
            let ie = (floor_i64(end) as usize).min(self.n);
            if ie >= ia + 2 {
                // Whole cells ia+1 ..= ie−1, each crossed in its middle with the same height
                // d: each keeps d/2 and passes d/2 on, so ia+1 and ie get d/2 and the cells
                // between get d, that run as a start and an end in the second-order buffer.
                let d = dir * dydx;
                self.put(row + ia + 1, 0.5 * d, 0.0, v);
                self.put(row + ie, 0.5 * d, 0.0, v);
                if ie >= ia + 3 {
                    self.run(row + ia + 2, row + ie, d, v);
                }
            }
            if end > ie as f64 {
                self.put(
                    row + ie,
                    dir * (end - ie as f64) * dydx,
                    0.5 * (ie as f64 + end) - ie as f64,
                    v,
                );
            }
        }
    }

    /// Add `d` to every cell from `from` to `to` (excluded) through the second-order buffer.
    #[inline(always)]
    fn run(&mut self, from: usize, to: usize, d: f64, v: &[f64]) {
        let ch = self.channels;
        for (k, &val) in v.iter().enumerate() {
            self.acc2[from * ch + k] += val * d;
            self.acc2[to * ch + k] -= val * d;
        }
    }

    /// Add height `d` crossing cell `cell` (index within the band) at `m` of its width: the
    /// cell takes `d (1 − m)`, the next one `d m`.
    #[inline(always)]
    fn put(&mut self, cell: usize, d: f64, m: f64, v: &[f64]) {
        if let [val] = v {
            let w = val * d;
            let r = w * m;
            self.acc[cell] += w - r;
            self.acc[cell + 1] += r;
            return;
        }
        let ch = self.channels;
        let (c0, c1) = (cell * ch, (cell + 1) * ch);
        for (k, &val) in v.iter().enumerate() {
            self.acc[c0 + k] += val * d * (1.0 - m);
            self.acc[c1 + k] += val * d * m;
        }
    }

    /// The accumulated rows as pixel averages: channel by channel, row-major from the band's
    /// first row, `n` values per row.
    pub fn finish(&self) -> Vec<Vec<f64>> {
        let len = (self.rows.1 - self.rows.0) * self.n;
        let mut out = vec![vec![0.0; len]; self.channels];
        let mut outs: Vec<&mut [f64]> = out.iter_mut().map(|o| o.as_mut_slice()).collect();
        self.finish_into(&mut outs);
        out
    }

    /// [`Accumulator::finish`] into `outs` (one slice per channel, at least the band's rows
    /// × `n` long, row `rows.0` first): the very same values, without new memory.
    pub fn finish_into(&self, outs: &mut [&mut [f64]]) {
        let width = self.n + 2;
        let ch = self.channels;
        for r in 0..self.rows.1 - self.rows.0 {
            for (k, o) in outs.iter_mut().enumerate().take(ch) {
                let row = &mut o[r * self.n..(r + 1) * self.n];
                let (mut run, mut run2) = (0.0, 0.0);
                for (i, px) in row.iter_mut().enumerate() {
                    let c = (r * width + i) * ch + k;
                    run2 += self.acc2[c];
                    run += self.acc[c] + run2;
                    *px = run;
                }
            }
        }
    }
}

/// An `n × n` image over the square `[−half, half]²` of image coordinates; each pixel holds
/// an average value (weight per unit area × covered area / pixel area).
#[derive(Clone, Debug, PartialEq)]
pub struct Raster {
    /// Pixels per side.
    pub n: usize,
    /// Half the side of the imaged square.
    pub half: f64,
    /// Row-major values, row 0 at the bottom (y = −half).
    pub data: Vec<f64>,
    cov: Coverage,
}

impl Raster {
    /// Largest difference between two pictures' pixels (tests compare ways of drawing).
    #[cfg(test)]
    pub(crate) fn max_difference(&self, other: &Raster) -> f64 {
        self.data
            .iter()
            .zip(&other.data)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    }

    /// A black image (at least one pixel; a non-positive or non-finite `half` gives an image
    /// that ignores everything).
    pub fn new(n: usize, half: f64) -> Raster {
        let n = n.max(1);
        Raster {
            n,
            half,
            data: vec![0.0; n * n],
            cov: Coverage::default(),
        }
    }

    /// Side of a pixel.
    pub fn pixel(&self) -> f64 {
        2.0 * self.half / self.n as f64
    }

    /// Add `value` (per unit area, i.e. the pixel average where fully covered) over the convex
    /// polygon `poly`, pixel by pixel by exact clipping.
    pub fn add_polygon(&mut self, poly: &[DVec2], value: f64) {
        if value == 0.0 || !value.is_finite() {
            return;
        }
        let mut cov = std::mem::take(&mut self.cov);
        self.coverage_into(poly, &mut cov);
        self.add_coverage(&cov, value);
        self.cov = cov;
    }

    /// Add `value` per unit area over a coverage computed by [`Raster::coverage_into`] for an
    /// image of this size: the same as [`Raster::add_polygon`] with the polygon.
    pub fn add_coverage(&mut self, cov: &Coverage, value: f64) {
        if cov.cells.is_empty() || value == 0.0 || !value.is_finite() {
            return;
        }
        let h = self.pixel();
        let scale = value / (h * h);
        for &(k, a) in &cov.cells {
            self.data[k] += a * scale;
        }
    }

    /// The coverage of a polygon's image under the grid symmetry `g` from the polygon's own
    /// coverage `cov` (for this image's size), into `out` (cleared first): the same pixels
    /// moved by `g`, with the same areas. Equal to [`Raster::coverage_into`] of the mapped
    /// polygon to rounding, without clipping anything.
    pub fn map_coverage(&self, cov: &Coverage, g: GridMap, out: &mut Coverage) {
        out.cells.clear();
        out.cells.reserve(cov.cells.len());
        let n = self.n as i64;
        let [a, b, c, d] = g.0.map(i64::from);
        // With pixel centres at X = 2i − (n − 1) half-pixels from the image centre, the map
        // takes pixel (i, j) to (a i + b j + oi, c i + d j + oj), one of a, b and one of c, d
        // being 0: so k = j n + i goes to (c n + a) i + (d n + b) j + oj n + oi.
        let (oi, oj) = ((n - 1) * (1 - a - b) / 2, (n - 1) * (1 - c - d) / 2);
        let (ki, kj, k0) = (c * n + a, d * n + b, oj * n + oi);
        for &(k, area) in &cov.cells {
            let (i, j) = ((k % self.n) as i64, (k / self.n) as i64);
            out.cells.push(((ki * i + kj * j + k0) as usize, area));
        }
    }

    /// The pixels the convex polygon `poly` covers in this image, with the exact covered
    /// areas, into `cov` (cleared first; empty when nothing is covered).
    pub fn coverage_into(&self, poly: &[DVec2], cov: &mut Coverage) {
        self.coverage_rows_into(poly, (0, self.n), cov);
    }

    /// [`Raster::coverage_into`] restricted to the pixel rows `rows.0 .. rows.1` (row 0 at
    /// the bottom): the cells of those rows only, the same numbers as the whole coverage has
    /// there. Images can so be filled in horizontal bands, one per thread.
    ///
    /// Pixels wholly inside the polygon get the pixel's area `h²` without clipping (the
    /// clip would give `h²` to rounding); only pixels the polygon's edges cross are clipped.
    pub fn coverage_rows_into(&self, poly: &[DVec2], rows: (usize, usize), cov: &mut Coverage) {
        cov.cells.clear();
        let rows = (rows.0.min(self.n), rows.1.min(self.n));
        if poly.len() < 3 || rows.0 >= rows.1 || !(self.half > 0.0 && self.half.is_finite()) {
            return;
        }
        let h = self.pixel();
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for p in poly {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        if !(lo.is_finite() && hi.is_finite()) {
            return;
        }
        let n = self.n as isize;
        let idx = |c: f64| floor_i64((c + self.half) / h) as isize;
        let (i0, i1) = (idx(lo.x).clamp(0, n - 1), idx(hi.x).clamp(0, n - 1));
        let (j0, j1) = (idx(lo.y).clamp(0, n - 1), idx(hi.y).clamp(0, n - 1));
        // One pixel holds the whole polygon only if its own rows (not the band's) are one.
        let single = i0 == i1 && j0 == j1;
        let (j0, j1) = (j0.max(rows.0 as isize), j1.min(rows.1 as isize - 1));
        if j0 > j1 {
            return;
        }
        if single {
            // Inside one pixel (the common case for small beams): no clipping needed unless it
            // sticks out of the imaged square.
            let inside =
                lo.x >= -self.half && hi.x <= self.half && lo.y >= -self.half && hi.y <= self.half;
            let a = if inside {
                clip2d::area(poly)
            } else {
                let x0 = -self.half + i0 as f64 * h;
                let y0 = -self.half + j0 as f64 * h;
                clip2d::rect_overlap_area(poly, DVec2::new(x0, y0), DVec2::new(x0 + h, y0 + h))
            };
            cov.cells.push((j0 as usize * self.n + i0 as usize, a));
            return;
        }
        // Orientation, for the interior test of whole pixels.
        let orient = clip2d::signed_area(poly).signum();
        let wide = i1 - i0 >= 3;
        for j in j0..=j1 {
            let y0 = -self.half + j as f64 * h;
            strip_y(
                poly,
                (lo.y, hi.y),
                (y0, y0 + h),
                &mut cov.strip,
                &mut cov.scratch,
            );
            if cov.strip.is_empty() {
                continue;
            }
            let (mut sx0, mut sx1) = (f64::INFINITY, f64::NEG_INFINITY);
            for p in &cov.strip {
                sx0 = sx0.min(p.x);
                sx1 = sx1.max(p.x);
            }
            let (full_lo, full_hi) = if wide && lo.y < y0 && hi.y > y0 + h {
                interior_x(poly, orient, y0, y0 + h)
            } else {
                (f64::INFINITY, f64::NEG_INFINITY)
            };
            let full = h * h;
            // A margin far above rounding, so that a pixel taken as whole is whole.
            let margin = 1e-9 * h;
            for i in i0..=i1 {
                let x0 = -self.half + i as f64 * h;
                let a = if x0 >= full_lo + margin && x0 + h <= full_hi - margin {
                    full
                } else {
                    slab_area(&cov.strip, x0, x0 + h, (sx0, sx1), &mut cov.cell)
                };
                if a > 0.0 {
                    cov.cells.push((j as usize * self.n + i as usize, a));
                }
            }
        }
    }

    /// Sum over pixels of value × pixel area (the integral of the image).
    pub fn integral(&self) -> f64 {
        let h = self.pixel();
        self.data.iter().sum::<f64>() * h * h
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coverage_is_exact() {
        let mut r = Raster::new(16, 1.0);
        let tri = [
            DVec2::new(-0.7, -0.3),
            DVec2::new(0.61, -0.52),
            DVec2::new(0.05, 0.83),
        ];
        r.add_polygon(&tri, 2.0);
        assert!((r.integral() - 2.0 * clip2d::area(&tri)).abs() < 1e-14);
        // A polygon partly outside keeps only its inside part.
        let mut r = Raster::new(8, 0.5);
        let sq = [
            DVec2::new(0.25, 0.25),
            DVec2::new(0.75, 0.25),
            DVec2::new(0.75, 0.75),
            DVec2::new(0.25, 0.75),
        ];
        r.add_polygon(&sq, 1.0);
        assert!((r.integral() - 0.0625).abs() < 1e-15);
        // A tiny polygon inside one pixel.
        let mut r = Raster::new(8, 0.5);
        let t = [
            DVec2::new(0.01, 0.01),
            DVec2::new(0.02, 0.01),
            DVec2::new(0.01, 0.02),
        ];
        r.add_polygon(&t, 1.0);
        assert!((r.integral() - 5e-5).abs() < 1e-18);
        assert_eq!(r.data.iter().filter(|&&v| v > 0.0).count(), 1);
    }

    /// A polygon's coverage moved by a grid symmetry is the coverage of the moved polygon (the
    /// same pixels, the same areas to rounding), for all eight symmetries, on even and odd
    /// image sizes; maps that are not grid symmetries are refused.
    #[test]
    fn grid_maps_move_coverage_exactly() {
        let mut rnd = crate::testkit::uniform(192837465u64);
        let quarter = glam::DMat2::from_angle(std::f64::consts::FRAC_PI_2);
        let q = [
            quarter.x_axis.x,
            quarter.y_axis.x,
            quarter.x_axis.y,
            quarter.y_axis.y,
        ];
        assert_eq!(GridMap::of(q), Some(GridMap([0, -1, 1, 0])));
        let c = std::f64::consts::FRAC_1_SQRT_2;
        assert_eq!(GridMap::of([c, -c, c, c]), None);
        assert_eq!(GridMap::of([1.0, 0.0, 0.0, 0.5]), None);
        assert_eq!(GridMap::of([1.0, 1.0, 0.0, 1.0]), None);
        let maps: Vec<[i8; 4]> = vec![
            [1, 0, 0, 1],
            [0, -1, 1, 0],
            [-1, 0, 0, -1],
            [0, 1, -1, 0],
            [1, 0, 0, -1],
            [-1, 0, 0, 1],
            [0, 1, 1, 0],
            [0, -1, -1, 0],
        ];
        for n in [15, 16] {
            let r = Raster::new(n, 0.5);
            let (mut cov, mut moved, mut direct) = (
                Coverage::default(),
                Coverage::default(),
                Coverage::default(),
            );
            for _ in 0..300 {
                let k = 3 + (rnd() * 5.0) as usize;
                let (cx, cy, rad, ph) = (rnd() - 0.5, rnd() - 0.5, rnd() * 0.2, rnd() * 6.0);
                let poly: Vec<DVec2> = (0..k)
                    .map(|i| {
                        let th = ph + i as f64 * std::f64::consts::TAU / k as f64;
                        DVec2::new(cx + rad * th.cos(), cy + rad * th.sin())
                    })
                    .collect();
                r.coverage_into(&poly, &mut cov);
                for m in &maps {
                    let g = GridMap::of(m.map(f64::from)).expect("a grid map");
                    let [a, b, c, d] = m.map(f64::from);
                    let image: Vec<DVec2> = poly
                        .iter()
                        .map(|p| DVec2::new(a * p.x + b * p.y, c * p.x + d * p.y))
                        .collect();
                    r.coverage_into(&image, &mut direct);
                    r.map_coverage(&cov, g, &mut moved);
                    let tiny = 1e-12 * r.pixel() * r.pixel();
                    let sorted = |c: &Coverage| {
                        let mut v: Vec<(usize, f64)> =
                            c.cells.iter().copied().filter(|x| x.1 > tiny).collect();
                        v.sort_by_key(|x| x.0);
                        v
                    };
                    let (got, want) = (sorted(&moved), sorted(&direct));
                    assert_eq!(got.len(), want.len(), "{n} {m:?} {poly:?}");
                    for (x, y) in got.iter().zip(&want) {
                        assert_eq!(x.0, y.0, "{n} {m:?} {poly:?}");
                        assert!((x.1 - y.1).abs() <= 1e-13 * r.pixel() * r.pixel());
                    }
                    // Composition: moving by g then by h g⁻¹ is moving by h.
                    let h = GridMap([0, 1, -1, 0]);
                    let mut twice = Coverage::default();
                    r.map_coverage(&moved, h.after_inverse_of(g), &mut twice);
                    let mut once = Coverage::default();
                    r.map_coverage(&cov, h, &mut once);
                    assert_eq!(sorted(&twice), sorted(&once));
                }
            }
        }
    }

    /// The coverage is the per-pixel clip with clip2d's strip clips: bit for bit where a pixel
    /// is clipped, to rounding where it is wholly covered.
    #[test]
    fn coverage_matches_the_plain_clip_bit_for_bit() {
        let mut rnd = crate::testkit::uniform(987654321u64);
        let r = Raster::new(16, 0.5);
        let h = r.pixel();
        let mut cov = Coverage::default();
        let (mut strip, mut cell, mut scratch) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..2000 {
            let n = 3 + (rnd() * 6.0) as usize;
            let (cx, cy, rad, ph) = (rnd() - 0.5, rnd() - 0.5, rnd() * 0.45, rnd() * 6.0);
            // Some vertices exactly on pixel lines.
            let snap = rnd() < 0.3;
            let poly: Vec<DVec2> = (0..n)
                .map(|i| {
                    let th = ph + i as f64 * std::f64::consts::TAU / n as f64;
                    let p = DVec2::new(cx + rad * th.cos(), cy + rad * th.sin());
                    if snap {
                        ((p + 0.5) / h).round() * h - 0.5
                    } else {
                        p
                    }
                })
                .collect();
            r.coverage_into(&poly, &mut cov);
            let mut want = Vec::new();
            for j in 0..16 {
                let y0 = -0.5 + j as f64 * h;
                clip2d::clip_strip_y_into(&poly, y0, y0 + h, &mut strip, &mut scratch);
                for i in 0..16 {
                    let x0 = -0.5 + i as f64 * h;
                    clip2d::clip_strip_x_into(&strip, x0, x0 + h, &mut cell, &mut scratch);
                    let a = clip2d::area(&cell);
                    if a > 0.0 {
                        want.push((j * 16 + i, a));
                    }
                }
            }
            let got: Vec<(usize, f64)> = cov.cells.iter().copied().filter(|c| c.1 > 0.0).collect();
            // Cells touched only along a pixel line get a zero-width sliver (area ~1e-17) from
            // the clip's tolerance, or nothing: not a difference.
            let tiny = 1e-12 * h * h;
            let got: Vec<(usize, f64)> = got.into_iter().filter(|c| c.1 > tiny).collect();
            want.retain(|c| c.1 > tiny);
            assert_eq!(got.len(), want.len(), "{poly:?}");
            for (g, w) in got.iter().zip(&want) {
                assert_eq!(g.0, w.0, "{poly:?}");
                if g.1 == h * h {
                    assert!((g.1 - w.1).abs() <= 1e-13 * h * h, "{poly:?}");
                } else {
                    assert_eq!(g.1, w.1, "{poly:?}");
                }
            }
        }
    }

    /// The accumulator gives every polygon's exact coverage (as the clip does), in bands of
    /// rows too.
    #[test]
    fn accumulator_matches_the_clip() {
        let mut rnd = crate::testkit::uniform(12345u64);
        let n = 24;
        let mut want = [Raster::new(n, 0.5), Raster::new(n, 0.5)];
        let mut whole = Accumulator::new(n, 0.5, (0, n), 2);
        let mut bands: Vec<Accumulator> = (0..n)
            .step_by(7)
            .map(|j| Accumulator::new(n, 0.5, (j, (j + 7).min(n)), 2))
            .collect();
        for _ in 0..300 {
            let k = 3 + (rnd() * 6.0) as usize;
            let (cx, cy, rad, ph) = (rnd() - 0.5, rnd() - 0.5, rnd() * 0.4, rnd() * 6.0);
            let ccw = rnd() < 0.5;
            let mut poly: Vec<DVec2> = (0..k)
                .map(|i| {
                    let th = ph + i as f64 * std::f64::consts::TAU / k as f64;
                    DVec2::new(cx + rad * th.cos(), cy + rad * th.sin())
                })
                .collect();
            if !ccw {
                poly.reverse();
            }
            let vals = [rnd(), rnd() - 0.5];
            for (r, v) in want.iter_mut().zip(vals) {
                r.add_polygon(&poly, v);
            }
            whole.add_polygon(&poly, &vals);
            for b in &mut bands {
                b.add_polygon(&poly, &vals);
            }
        }
        let got = whole.finish();
        let mut banded = [Vec::new(), Vec::new()];
        for b in &bands {
            for (c, rows) in b.finish().into_iter().enumerate() {
                banded[c].extend(rows);
            }
        }
        for c in 0..2 {
            for p in 0..n * n {
                assert!(
                    (got[c][p] - want[c].data[p]).abs() < 1e-11,
                    "{c} {p} {} {}",
                    got[c][p],
                    want[c].data[p]
                );
                assert!((banded[c][p] - want[c].data[p]).abs() < 1e-11, "{c} {p}");
            }
        }
    }

    #[test]
    fn integer_floor_and_ceil() {
        for v in [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            2.5,
            -2.5,
            1e300,
            -1e300,
            9.3e18,
            -9.3e18,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e-300,
            -1e-300,
            4503599627370497.0,
        ] {
            assert_eq!(floor_i64(v), v.floor() as i64, "{v}");
            assert_eq!(ceil_i64(v), v.ceil() as i64, "{v}");
        }
    }

    #[test]
    fn moving_polygon_changes_image_continuously() {
        let mut prev: Option<Raster> = None;
        for k in 0..50 {
            let dx = k as f64 * 1e-3;
            let p = [
                DVec2::new(-0.3 + dx, -0.2),
                DVec2::new(0.2 + dx, -0.25),
                DVec2::new(0.1 + dx, 0.3),
            ];
            let mut r = Raster::new(12, 0.5);
            r.add_polygon(&p, 1.0);
            if let Some(q) = &prev {
                let diff: f64 = r.data.iter().zip(&q.data).map(|(a, b)| (a - b).abs()).sum();
                assert!(diff * r.pixel().powi(2) < 2.0 * 1e-3 * 0.6, "{diff}");
            }
            prev = Some(r);
        }
    }
}
