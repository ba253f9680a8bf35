//! Contour lines of a gridded function by marching squares, and "nice" contour levels.

/// A contour segment, two points in data coordinates.
pub type Segment = ((f64, f64), (f64, f64));

/// The segments where the grid function crosses `level`. `z[j][i]` is the value at
/// `(xs[i], ys[j])`; cells with a NaN corner are skipped. Saddle cells are resolved by the
/// mean of the four corners.
pub fn segments(xs: &[f64], ys: &[f64], z: &[Vec<f64>], level: f64) -> Vec<Segment> {
    let mut out = Vec::new();
    if xs.len() < 2 || ys.len() < 2 {
        return out;
    }
    for j in 0..ys.len() - 1 {
        for i in 0..xs.len() - 1 {
            // Corners counter-clockwise from the bottom left.
            let c = [
                (xs[i], ys[j], z[j][i]),
                (xs[i + 1], ys[j], z[j][i + 1]),
                (xs[i + 1], ys[j + 1], z[j + 1][i + 1]),
                (xs[i], ys[j + 1], z[j + 1][i]),
            ];
            if c.iter().any(|p| !p.2.is_finite()) {
                continue;
            }
            let above: Vec<bool> = c.iter().map(|p| p.2 >= level).collect();
            // Edge k joins corner k and k+1.
            let cross = |k: usize| {
                // Interpolate from the edge's lower corner, so neighbouring cells compute the
                // very same point on their shared edge.
                let (mut a, mut b) = (c[k], c[(k + 1) % 4]);
                if (b.0, b.1) < (a.0, a.1) {
                    std::mem::swap(&mut a, &mut b);
                }
                let t = if b.2 == a.2 {
                    0.5
                } else {
                    (level - a.2) / (b.2 - a.2)
                };
                (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
            };
            let edges: Vec<usize> = (0..4).filter(|&k| above[k] != above[(k + 1) % 4]).collect();
            match edges.len() {
                2 => out.push((cross(edges[0]), cross(edges[1]))),
                4 => {
                    let centre = c.iter().map(|p| p.2).sum::<f64>() / 4.0;
                    // Join the crossings around the corners that differ from the centre.
                    if (centre >= level) == above[0] {
                        out.push((cross(0), cross(1)));
                        out.push((cross(2), cross(3)));
                    } else {
                        out.push((cross(3), cross(0)));
                        out.push((cross(1), cross(2)));
                    }
                }
                _ => {}
            }
        }
    }
    out
}

/// About `n` round contour levels strictly inside `(lo, hi)` (steps of 1, 2 or 5 × 10^k).
pub fn nice_levels(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if !(lo.is_finite() && hi.is_finite()) || hi <= lo || n == 0 {
        return Vec::new();
    }
    let raw = (hi - lo) / n as f64;
    let mag = 10f64.powf(raw.log10().floor());
    // The round step closest to the wanted one (on a log scale).
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .min_by(|a, b| (a / raw).ln().abs().total_cmp(&(b / raw).ln().abs()))
        .unwrap_or(mag);
    let decimals = (-step.log10().floor()).max(0.0) as i32 + 1;
    let snap = 10f64.powi(decimals);
    let first = (lo / step).floor() as i64;
    let mut out = Vec::new();
    for k in first.. {
        // Snap to the decimals of the step so labels print cleanly.
        let v = (k as f64 * step * snap).round() / snap;
        if v >= hi {
            break;
        }
        if v > lo {
            out.push(v);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_contours_of_a_cone() {
        let xs: Vec<f64> = (0..41).map(|i| -1.0 + i as f64 * 0.05).collect();
        let ys = xs.clone();
        let z: Vec<Vec<f64>> = ys
            .iter()
            .map(|y| xs.iter().map(|x| (x * x + y * y).sqrt()).collect())
            .collect();
        let segs = segments(&xs, &ys, &z, 0.52);
        assert!(segs.len() > 30);
        for (a, b) in &segs {
            for p in [a, b] {
                let r = (p.0 * p.0 + p.1 * p.1).sqrt();
                assert!((r - 0.52).abs() < 0.01, "{r}");
            }
        }
        // A closed curve: every endpoint is shared by exactly two segments.
        let key = |p: &(f64, f64)| ((p.0 * 1e9).round() as i64, (p.1 * 1e9).round() as i64);
        let mut count = std::collections::HashMap::new();
        for (a, b) in &segs {
            *count.entry(key(a)).or_insert(0) += 1;
            *count.entry(key(b)).or_insert(0) += 1;
        }
        assert!(count.values().all(|&c| c == 2));
        // NaN cells are skipped, levels outside the range give nothing.
        let mut zn = z.clone();
        zn[20][30] = f64::NAN;
        assert!(segments(&xs, &ys, &zn, 0.52).len() < segs.len());
        assert!(segments(&xs, &ys, &z, 5.0).is_empty());
    }

    #[test]
    fn nice_levels_are_round() {
        let l = nice_levels(0.0, 1.0, 5);
        assert_eq!(l, vec![0.2, 0.4, 0.6, 0.8]);
        let l = nice_levels(0.512, 0.687, 8);
        assert_eq!(l[0], 0.52, "{l:?}");
        assert_eq!(l.len(), 9, "{l:?}");
        assert!(l.iter().all(|v| *v > 0.512 && *v < 0.687));
        assert!(nice_levels(1.0, 1.0, 5).is_empty());
    }
}
