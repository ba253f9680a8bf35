//! From mesh vertices to named facet planes: convex hull, convexity check, normalisation to
//! the girdle frame (see the parent module's documentation) and tier names.

use super::{hull_error, sig2, Points};
use crate::cut::units::{girdle_frame, is_girdle};
use crate::error::{Error, Result};
use crate::geometry::{
    convex_hull_with_tolerance, facet_angle_deg, facet_azimuth_deg, DVec3, FacetPlane, Plane,
    Polyhedron, MERGE_TOL,
};

/// Largest allowed depth of a mesh vertex inside its convex hull, as a fraction of the size.
pub const CONVEX_TOL: f64 = 1e-3;

/// Largest merge tolerance used for coarse coordinates (fraction of the size).
const MAX_MERGE_TOL: f64 = 1e-4;

/// The most facets a mesh read as a cut may have: a scanned rough's hull has tens of
/// thousands, and no cut is traced or measured usefully with them.
pub const MAX_FACETS: usize = 5000;

/// Hull, convexity check, normalisation and naming.
pub(super) fn planes_from_points(
    points: &Points,
    source: &str,
) -> Result<(Vec<FacetPlane>, Option<String>)> {
    let pts = &points.pts;
    if pts.len() < 4 {
        return Err(Error::parse(
            source,
            format!(
                "a stone needs at least 4 distinct vertices, the mesh has {}",
                pts.len()
            ),
        ));
    }
    let (mut lo, mut hi) = (pts[0], pts[0]);
    for p in pts {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let size = (hi - lo).max_element();
    let largest = lo.abs().max(hi.abs()).max_element();
    if !size.is_finite() || largest > 1e150 {
        return Err(Error::parse(
            source,
            format!("vertex coordinates up to {largest:e} are too large; allowed up to 1e150"),
        ));
    }
    if !(size.is_finite() && size > 0.0) {
        return Err(Error::parse(
            source,
            "all vertices coincide; a stone needs a solid",
        ));
    }
    let tol = (8.0 * points.rel_noise * largest / size).clamp(MERGE_TOL, MAX_MERGE_TOL);
    let hull = convex_hull_with_tolerance(pts, tol).map_err(|e| hull_error(e, source))?;
    if hull.len() > MAX_FACETS {
        return Err(Error::parse(
            source,
            format!(
                "the mesh's convex hull has {} facets; a cut has at most {MAX_FACETS} (a scanned rough? plan cuts inside it with `facetlab plan`)",
                hull.len()
            ),
        ));
    }

    // Convexity: the deepest vertex inside the hull, of those deeper than allowed (a vertex
    // within the allowance of some plane passes at once; the planes are tried from the one
    // that passed the vertex before, as neighbours in a file tend to share a facet).
    let allowed = CONVEX_TOL * size;
    let mut deepest = (0.0, 0usize);
    let mut last = 0;
    for (i, p) in pts.iter().enumerate() {
        let near = (last..hull.len())
            .chain(0..last)
            .find(|&k| -hull[k].distance(*p) <= allowed);
        if let Some(k) = near {
            last = k;
            continue;
        }
        let depth = hull
            .iter()
            .map(|h| -h.distance(*p))
            .fold(f64::INFINITY, f64::min);
        if depth > deepest.0 {
            deepest = (depth, i);
        }
    }
    if deepest.0 > allowed {
        let (depth, i) = deepest;
        return Err(Error::parse(
            source,
            format!(
                "mesh is not convex: a vertex ({}) lies {} ({}% of the size) inside its convex hull; allowed {}%",
                points.locs[i].describe(),
                sig2(depth),
                sig2(100.0 * depth / size),
                100.0 * CONVEX_TOL
            ),
        ));
    }

    // Into a unit frame first (Polyhedron works in a bounded box), then to the girdle frame.
    let centre = 0.5 * (lo + hi);
    let unit: Vec<Plane> = hull
        .iter()
        .map(|h| Plane {
            normal: h.normal,
            offset: (h.offset - h.normal.dot(centre)) / size,
        })
        .collect();
    let solid = Polyhedron::from_planes(&named(&unit)).map_err(|e| hull_error(e, source))?;
    let (origin, width) = girdle_frame(&solid);
    if width <= 1e-9 {
        return Err(Error::parse(
            source,
            "the mesh has no horizontal extent; the stone must stand upright, z up",
        ));
    }
    let mut planes: Vec<Plane> = unit
        .iter()
        .map(|h| Plane {
            normal: h.normal,
            offset: (h.offset - h.normal.dot(origin)) / width,
        })
        .collect();
    planes.sort_by(|a, b| {
        let key = |p: &Plane| (side(p.normal).1, (facet_angle_deg(p.normal) * 1e3).round());
        let (ka, kb) = (key(a), key(b));
        ka.0.cmp(&kb.0)
            .then(ka.1.total_cmp(&kb.1))
            .then(facet_azimuth_deg(a.normal).total_cmp(&facet_azimuth_deg(b.normal)))
    });
    let mut out = named(&planes);
    for f in &mut out {
        f.tier = side(f.plane.normal).0.to_string();
    }
    split_tiers_by_angle(&mut out);
    if points.single_precision {
        Ok(weld(out, tol))
    } else {
        Ok((out, None))
    }
}

/// Welding tolerance as a multiple of the merge tolerance: corners split by rounding sit where
/// nearly parallel planes meet, so their spread is many times the coordinates' rounding error.
const WELD: f64 = 16.0;
/// Largest welding tolerance (fraction of the size).
const MAX_WELD: f64 = 1e-5;

/// Weld clusters of vertices closer than `WELD` times the merge tolerance `tol` (at most
/// `MAX_WELD`) of the size (coordinate rounding splits a
/// point where many facets meet, such as a pointed culet, into a cluster of vertices with
/// tiny edges between them): each cluster becomes its mean point; a facet touching one cluster
/// is moved parallel to itself through that point, one touching several is fitted again through
/// its welded corners (Newell's normal); facets left with fewer than three corners are dropped. Returns the planes and, if anything was welded, a one-line note.
fn weld(mut planes: Vec<FacetPlane>, tol: f64) -> (Vec<FacetPlane>, Option<String>) {
    let Ok(s) = Polyhedron::from_planes(&planes) else {
        return (planes, None);
    };
    let (lo, hi) = s.bounding_box();
    let eps = (WELD * tol).min(MAX_WELD) * (hi - lo).max_element();
    // Moving a plane can split a corner elsewhere (again by far less than `eps`): repeat.
    let (mut merged, mut dropped, mut spread) = (0, 0, 0.0f64);
    for _ in 0..WELD_ROUNDS {
        let Some((next, m, d, sp)) = weld_once(&planes, eps) else {
            break;
        };
        planes = next;
        merged += m;
        dropped += d;
        spread = spread.max(sp);
    }
    if merged == 0 {
        return (planes, None);
    }
    let note = format!(
        "welded {merged} vertices into their neighbours within {} girdle diameters (moved up to {}); {dropped} facets dropped",
        sig2(eps),
        sig2(spread)
    );
    (planes, Some(note))
}

/// Rounds of [`weld`] at most.
const WELD_ROUNDS: usize = 8;

/// One round of [`weld`]: the new planes, vertices merged, facets dropped and the largest
/// move, or `None` when nothing is within `eps`.
fn weld_once(planes: &[FacetPlane], eps: f64) -> Option<(Vec<FacetPlane>, usize, usize, f64)> {
    let s = Polyhedron::from_planes(planes).ok()?;
    let mut root: Vec<usize> = (0..s.vertices().len()).collect();
    fn find(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    let mut merged = 0;
    let mut size = vec![1usize; s.vertices().len()];
    for e in s.edges() {
        if s.vertices()[e.a].distance(s.vertices()[e.b]) < eps {
            let (a, b) = (find(&mut root, e.a), find(&mut root, e.b));
            if a != b {
                root[a.max(b)] = a.min(b);
                size[a.min(b)] += size[a.max(b)];
                merged += 1;
            }
        }
    }
    if merged == 0 {
        return None;
    }
    let n = s.vertices().len();
    let mut sum = vec![(DVec3::ZERO, 0.0); n];
    for i in 0..n {
        let r = find(&mut root, i);
        sum[r].0 += s.vertices()[i];
        sum[r].1 += 1.0;
    }
    let mut spread: f64 = 0.0;
    for i in 0..n {
        let r = find(&mut root, i);
        spread = spread.max(s.vertices()[i].distance(sum[r].0 / sum[r].1));
    }
    let (mut out, mut dropped) = (Vec::with_capacity(planes.len()), 0);
    for (f, p) in s.facets().iter().zip(planes.iter().cloned()) {
        let mut ids: Vec<usize> = f.vertices.iter().map(|&v| find(&mut root, v)).collect();
        ids.dedup();
        while ids.len() > 1 && ids.first() == ids.last() {
            ids.pop();
        }
        if ids.len() < 3 {
            dropped += 1;
            continue;
        }
        let pts: Vec<DVec3> = ids.iter().map(|&r| sum[r].0 / sum[r].1).collect();
        let welded: Vec<DVec3> = ids
            .iter()
            .filter(|&&r| size[r] > 1)
            .map(|&r| sum[r].0 / sum[r].1)
            .collect();
        if welded.is_empty() {
            out.push(p);
            continue;
        }
        if let [c] = welded[..] {
            // Through the one welded point exactly: the planes meeting there meet in it.
            let offset = p.plane.normal.dot(c);
            let normal = p.plane.normal;
            out.push(FacetPlane {
                plane: Plane { normal, offset },
                ..p
            });
            continue;
        }
        let mut normal = DVec3::ZERO;
        for (k, a) in pts.iter().enumerate() {
            let b = pts[(k + 1) % pts.len()];
            normal += DVec3::new(
                (a.y - b.y) * (a.z + b.z),
                (a.z - b.z) * (a.x + b.x),
                (a.x - b.x) * (a.y + b.y),
            );
        }
        let normal = normal.normalize_or(p.plane.normal);
        let offset = welded.iter().map(|q| normal.dot(*q)).sum::<f64>() / welded.len() as f64;
        out.push(FacetPlane {
            plane: Plane { normal, offset },
            ..p
        });
    }
    Some((out, merged, dropped, spread))
}

/// Crown and pavilion facets grouped into tiers by angle: angles within 0.05° of their
/// neighbour in sorted order form one tier, named by side and mean angle (`crown-34.50`), so
/// that `info` reports a mesh's bezels and mains as a cutter would.
fn split_tiers_by_angle(facets: &mut [FacetPlane]) {
    for sidename in ["crown", "pavilion"] {
        let mut idx: Vec<(usize, f64)> = facets
            .iter()
            .enumerate()
            .filter(|(_, f)| f.tier == sidename)
            .map(|(i, f)| (i, facet_angle_deg(f.plane.normal)))
            .collect();
        idx.sort_by(|a, b| a.1.total_cmp(&b.1));
        let mut start = 0;
        while start < idx.len() {
            let mut end = start + 1;
            while end < idx.len() && idx[end].1 - idx[end - 1].1 <= 0.05 {
                end += 1;
            }
            let mean = idx[start..end].iter().map(|x| x.1).sum::<f64>() / (end - start) as f64;
            for &(i, _) in &idx[start..end] {
                facets[i].tier = format!("{sidename}-{mean:.2}");
            }
            start = end;
        }
    }
}

fn named(planes: &[Plane]) -> Vec<FacetPlane> {
    planes
        .iter()
        .enumerate()
        .map(|(i, p)| FacetPlane {
            plane: *p,
            name: format!("f-{}", i + 1),
            tier: String::new(),
        })
        .collect()
}

/// The side (tier) of a facet from its outward normal, with its rank in the facet order.
fn side(n: DVec3) -> (&'static str, u8) {
    let flat = facet_angle_deg(n) < 0.01;
    if is_girdle(n) {
        ("girdle", 2)
    } else if n.z > 0.0 {
        if flat {
            ("table", 0)
        } else {
            ("crown", 1)
        }
    } else if flat {
        ("culet", 4)
    } else {
        ("pavilion", 3)
    }
}
