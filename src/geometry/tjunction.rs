//! Mending T-junctions of a clipped solid's faces before they are assembled into a
//! [`super::Polyhedron`] (`polyhedron.rs`): every half-edge then has its twin.

use glam::DVec3;

/// Insert into each facet polygon the vertices that lie inside one of its edges. Clipping can
/// leave a vertex (where several planes nearly meet) on one face's edge but not in the
/// polygon of the face across that edge; after this every half-edge has its twin. The
/// candidates of an edge are the used vertices whose x lies within its x range (widened by
/// `weld`), found by binary search in the vertices sorted by x.
pub(super) fn split_t_junctions(polys: &mut [Option<Vec<usize>>], vertices: &[DVec3], weld: f64) {
    let mut used = vec![false; vertices.len()];
    for idx in polys.iter().flatten() {
        for &i in idx {
            used[i] = true;
        }
    }
    let mut by_x: Vec<usize> = (0..vertices.len()).filter(|&v| used[v]).collect();
    by_x.sort_by(|&a, &b| vertices[a].x.total_cmp(&vertices[b].x).then(a.cmp(&b)));
    let xs: Vec<f64> = by_x.iter().map(|&v| vertices[v].x).collect();
    for idx in polys.iter_mut().flatten() {
        let mut out: Vec<usize> = Vec::with_capacity(idx.len());
        let n = idx.len();
        for e in 0..n {
            let (a, b) = (idx[e], idx[(e + 1) % n]);
            out.push(a);
            let (pa, pb) = (vertices[a], vertices[b]);
            let ab = pb - pa;
            let len2 = ab.length_squared();
            if len2 <= 0.0 {
                continue;
            }
            let lo = xs.partition_point(|&x| x < pa.x.min(pb.x) - weld);
            let hi = xs.partition_point(|&x| x <= pa.x.max(pb.x) + weld);
            let mut inner: Vec<(f64, usize)> = Vec::new();
            for &v in &by_x[lo..hi] {
                if idx.contains(&v) {
                    continue;
                }
                let p = vertices[v];
                let t = (p - pa).dot(ab) / len2;
                if t <= 0.0 || t >= 1.0 {
                    continue;
                }
                if (pa + ab * t).distance(p) <= weld {
                    inner.push((t, v));
                }
            }
            inner.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            out.extend(inner.into_iter().map(|(_, v)| v));
        }
        *idx = out;
    }
}
