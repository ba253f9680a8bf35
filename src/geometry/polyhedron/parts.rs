//! A solid restored from its parts, exactly as it was: [`Polyhedron::from_parts`] (for a cut
//! sent between processes bit for bit, `crate::io::exact`).

use super::{build_edges, Facet, Polyhedron};
use crate::error::{Error, Result};
use crate::geometry::DVec3;

/// How far a facet's vertex may lie from its plane, relative to the solid's size: the
/// rounding of a solid [`Polyhedron::from_planes`] built (and transformed) stays far below.
const ON_PLANE: f64 = 1e-6;

impl Polyhedron {
    /// The solid whose [`Polyhedron::vertices`] and [`Polyhedron::facets`] these are, every
    /// number kept as given (its edges rebuilt from the facets' polygons, as
    /// [`Polyhedron::from_planes`] builds them). Checked so that no tracer meets a broken
    /// solid: at least 4 facets, finite numbers, unit normals, polygons of 3 or more vertices
    /// that exist and lie on their facet's plane, every edge shared by two facets.
    ///
    /// ```
    /// use facetlab::geometry::{DVec3, FacetPlane, Polyhedron};
    /// let normals = [DVec3::X, DVec3::NEG_X, DVec3::Y, DVec3::NEG_Y, DVec3::Z, DVec3::NEG_Z];
    /// let planes: Vec<FacetPlane> = normals
    ///     .iter()
    ///     .enumerate()
    ///     .map(|(i, n)| FacetPlane::new(*n, 0.5, format!("f{i}"), "side"))
    ///     .collect();
    /// let cube = Polyhedron::from_planes(&planes).unwrap().scaled(3.0);
    /// let back = Polyhedron::from_parts(cube.vertices().to_vec(), cube.facets().to_vec()).unwrap();
    /// assert_eq!(back, cube);
    /// let mut bent = cube.vertices().to_vec();
    /// bent[0].z += 0.1;
    /// assert!(Polyhedron::from_parts(bent, cube.facets().to_vec()).is_err());
    /// ```
    pub fn from_parts(vertices: Vec<DVec3>, facets: Vec<Facet>) -> Result<Polyhedron> {
        let bad = |m: String| Err(Error::Geometry(m));
        if facets.len() < 4 {
            return bad(format!(
                "a solid needs at least 4 facets, got {}",
                facets.len()
            ));
        }
        if let Some(i) = vertices.iter().position(|v| !v.is_finite()) {
            return bad(format!("vertex {} is not finite", i + 1));
        }
        let size = vertices
            .iter()
            .map(|v| v.abs().max_element())
            .fold(1.0, f64::max);
        for f in &facets {
            let n = f.plane.normal;
            let unit = n.is_finite() && (n.length() - 1.0).abs() <= 1e-6;
            if !unit || !f.plane.offset.is_finite() || !f.area.is_finite() || f.area <= 0.0 {
                return bad(format!("facet {} has no valid plane or area", f.name));
            }
            if !f.centroid.is_finite() || f.vertices.len() < 3 {
                return bad(format!("facet {} has no valid polygon", f.name));
            }
            for &v in &f.vertices {
                let Some(p) = vertices.get(v) else {
                    return bad(format!(
                        "facet {} names a vertex that does not exist",
                        f.name
                    ));
                };
                if (n.dot(*p) - f.plane.offset).abs() > ON_PLANE * size {
                    return bad(format!("facet {} has a vertex off its plane", f.name));
                }
            }
        }
        let edges = build_edges(&facets)?;
        Ok(Polyhedron {
            vertices,
            facets,
            edges,
        })
    }
}
