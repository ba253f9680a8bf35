//! The stone in the layout the tracer's inner loops want: the facet planes as structure-of-
//! arrays (normals' x, y, z and offsets), padded to a multiple of [`LANES`] with planes that no
//! ray can leave through, so the exit search is a fixed-width, branch-free loop.

use super::tally::face_category;
use crate::error::{Error, Result};
use crate::geometry::{DVec3, Polyhedron};

/// Width of the padded facet arrays.
pub const LANES: usize = 8;

/// A convex stone prepared for photon tracing.
#[derive(Clone, Debug)]
pub struct TraceSolid {
    /// Facet count (without padding).
    pub facets: usize,
    /// Normal x components, padded with zeros.
    pub nx: Vec<f64>,
    /// Normal y components, padded with zeros.
    pub ny: Vec<f64>,
    /// Normal z components, padded with zeros.
    pub nz: Vec<f64>,
    /// Plane offsets, padded with ones.
    pub off: Vec<f64>,
    /// f32 copies for the fast exit search.
    pub(crate) f: [Vec<f32>; 4],
    /// Outward unit normals.
    pub normals: Vec<DVec3>,
    /// Face category (0: < 45°, 1: 45–90°, 2: 90–135°, 3: > 135° from up) of each facet.
    pub category: Vec<u8>,
    /// Facet names.
    pub names: Vec<String>,
    /// Facet tiers.
    pub tiers: Vec<String>,
    /// Vertices (for lights that cover the stone's shadow).
    pub vertices: Vec<DVec3>,
    /// Centre of the bounding sphere.
    pub centre: DVec3,
    /// Radius of the bounding sphere (slightly enlarged).
    pub radius: f64,
}

impl TraceSolid {
    /// Prepare `p` for tracing.
    pub fn new(p: &Polyhedron) -> Result<TraceSolid> {
        let n = p.facets.len();
        if n < 4 || p.vertices.is_empty() {
            return Err(Error::Geometry(
                "the solid has too few facets to trace".into(),
            ));
        }
        let padded = n.div_ceil(LANES) * LANES;
        let mut nx = vec![0.0; padded];
        let mut ny = vec![0.0; padded];
        let mut nz = vec![0.0; padded];
        let mut off = vec![1.0; padded];
        for (i, f) in p.facets.iter().enumerate() {
            let m = f.plane.normal;
            if !(m.is_finite() && f.plane.offset.is_finite()) {
                return Err(Error::Geometry(format!(
                    "facet {} has a non-finite plane",
                    f.name
                )));
            }
            nx[i] = m.x;
            ny[i] = m.y;
            nz[i] = m.z;
            off[i] = f.plane.offset;
        }
        let (lo, hi) = p.bounding_box();
        let centre = 0.5 * (lo + hi);
        let radius = p
            .vertices
            .iter()
            .map(|v| v.distance(centre))
            .fold(0.0, f64::max)
            * (1.0 + 1e-9)
            + 1e-12;
        // The f32 search works relative to the bounding-sphere centre (smaller numbers).
        let f = [
            nx.iter().map(|&v| v as f32).collect(),
            ny.iter().map(|&v| v as f32).collect(),
            nz.iter().map(|&v| v as f32).collect(),
            (0..padded)
                .map(|i| {
                    if i < n {
                        (off[i] - DVec3::new(nx[i], ny[i], nz[i]).dot(centre)) as f32
                    } else {
                        1.0
                    }
                })
                .collect(),
        ];
        Ok(TraceSolid {
            facets: n,
            nx,
            ny,
            nz,
            off,
            f,
            normals: p.facets.iter().map(|f| f.plane.normal).collect(),
            category: p
                .facets
                .iter()
                .map(|f| face_category(f.plane.normal))
                .collect(),
            names: p.facets.iter().map(|f| f.name.clone()).collect(),
            tiers: p.facets.iter().map(|f| f.tier.clone()).collect(),
            vertices: p.vertices.clone(),
            centre,
            radius,
        })
    }

    /// Where a ray from `p` (inside or on the solid) in unit direction `d` leaves it: the
    /// smallest `t = (offset − n·p)/(n·d)` over facets with `n·d > 0`, and that facet.
    #[inline]
    pub fn exit(&self, p: DVec3, d: DVec3) -> (f64, usize) {
        let mut best = [f64::INFINITY; LANES];
        let mut idx = [0usize; LANES];
        let chunks = self.nx.len() / LANES;
        for c in 0..chunks {
            let b = c * LANES;
            for l in 0..LANES {
                let i = b + l;
                let nd = self.nx[i] * d.x + self.ny[i] * d.y + self.nz[i] * d.z;
                let np = self.nx[i] * p.x + self.ny[i] * p.y + self.nz[i] * p.z;
                let t = if nd > 0.0 {
                    (self.off[i] - np) / nd
                } else {
                    f64::INFINITY
                };
                if t < best[l] {
                    best[l] = t;
                    idx[l] = i;
                }
            }
        }
        let mut bt = best[0];
        let mut bi = idx[0];
        for l in 1..LANES {
            if best[l] < bt || (best[l] == bt && idx[l] < bi) {
                bt = best[l];
                bi = idx[l];
            }
        }
        (bt, bi)
    }

    /// Where a ray from `o` (outside) in unit direction `d` enters the solid: `(t, facet)`,
    /// or `None` if it misses. Tests the bounding sphere first.
    #[inline]
    pub fn entry(&self, o: DVec3, d: DVec3) -> Option<(f64, usize)> {
        let oc = self.centre - o;
        let b = oc.dot(d);
        let r2 = self.radius * self.radius;
        let c2 = oc.length_squared();
        if c2 - b * b > r2 || (b < 0.0 && c2 > r2) {
            return None;
        }
        let mut t_in = f64::NEG_INFINITY;
        let mut f_in = usize::MAX;
        let mut t_out = f64::INFINITY;
        for i in 0..self.facets {
            let nd = self.nx[i] * d.x + self.ny[i] * d.y + self.nz[i] * d.z;
            let num = self.off[i] - (self.nx[i] * o.x + self.ny[i] * o.y + self.nz[i] * o.z);
            if nd < 0.0 {
                let t = num / nd;
                if t > t_in {
                    t_in = t;
                    f_in = i;
                }
            } else if nd > 0.0 {
                t_out = t_out.min(num / nd);
            } else if num < 0.0 {
                return None;
            }
        }
        if f_in == usize::MAX || t_in > t_out || t_in < 0.0 {
            return None;
        }
        Some((t_in, f_in))
    }
}
