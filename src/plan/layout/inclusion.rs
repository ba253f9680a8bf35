//! An inclusion kept out of every stone: the hull of a closed mesh, grown by its margin.

use super::super::mesh::read_triangles;
use crate::error::{Error, Result};
use crate::geometry::{hull, DVec3, FacetPlane, HullOptions, Plane, Polyhedron};
use std::path::Path;

/// The directions of the support planes that, with the hull's own faces, bound an
/// inclusion grown by its margin (the 26 of a cube's faces, edges and corners).
fn kdop() -> Vec<DVec3> {
    let mut out = Vec::new();
    for x in -1..=1 {
        for y in -1..=1 {
            for z in -1..=1 {
                if (x, y, z) != (0, 0, 0) {
                    out.push(DVec3::new(x as f64, y as f64, z as f64).normalize());
                }
            }
        }
    }
    out
}

/// An inclusion: the convex hull of a closed mesh (mm, the rough's coordinates) and the same
/// grown by the margin.
#[derive(Clone, Debug)]
pub struct Inclusion {
    /// Name (the file stem).
    pub name: String,
    /// The inclusion's convex hull (mm).
    pub hull: Polyhedron,
    /// The hull grown by the margin, enclosed in the half-spaces of the hull's faces and of
    /// 26 directions, each moved out by the margin (every point within the margin of the
    /// hull is inside it: a stone outside it keeps at least the margin away).
    pub grown: Polyhedron,
}

impl Inclusion {
    /// An inclusion from points (mm) grown by `margin` (mm); `source` names it in errors.
    pub fn from_points(name: &str, source: &str, pts: &[DVec3], margin: f64) -> Result<Inclusion> {
        let h = hull(pts, HullOptions::default()).map_err(|e| {
            Error::parse(
                source,
                format!("the inclusion's convex hull: {e} (a closed mesh with volume is needed)"),
            )
        })?;
        let named = |planes: &[Plane], tier: &str| -> Vec<FacetPlane> {
            planes
                .iter()
                .zip(1..)
                .map(|(p, i)| FacetPlane {
                    plane: *p,
                    name: format!("{tier}-{i}"),
                    tier: tier.into(),
                })
                .collect()
        };
        let solid = Polyhedron::from_planes(&named(&h.planes, "inclusion"))
            .map_err(|e| Error::parse(source, format!("the inclusion's convex hull: {e}")))?;
        let mut grown: Vec<Plane> = h
            .planes
            .iter()
            .map(|p| Plane {
                normal: p.normal,
                offset: p.offset + margin,
            })
            .collect();
        for u in kdop() {
            let top = solid
                .vertices()
                .iter()
                .map(|v| u.dot(*v))
                .fold(f64::NEG_INFINITY, f64::max);
            if !grown.iter().any(|p| p.normal.dot(u) > 1.0 - 1e-9) {
                grown.push(Plane {
                    normal: u,
                    offset: top + margin,
                });
            }
        }
        let grown = Polyhedron::from_planes_pruned(&named(&grown, "margin"))
            .map_err(|e| Error::parse(source, format!("the inclusion grown by its margin: {e}")))?;
        Ok(Inclusion {
            name: name.to_string(),
            hull: solid,
            grown,
        })
    }

    /// An inclusion from an `.obj` or `.stl` mesh (mm, the rough's coordinates), grown by
    /// `margin`: the mesh must be closed.
    pub fn from_mesh(path: &Path, margin: f64) -> Result<Inclusion> {
        let shown = path.display().to_string();
        let ext = path
            .extension()
            .map_or(String::new(), |e| e.to_string_lossy().to_ascii_lowercase());
        if ext != "obj" && ext != "stl" {
            return Err(Error::invalid(
                "inclusion mesh",
                format!(
                    "{shown}: an inclusion is an .obj or .stl mesh (mm, the rough's coordinates)"
                ),
            ));
        }
        let bytes = std::fs::read(path).map_err(|e| Error::io(&shown, e))?;
        let name = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("inclusion");
        Inclusion::from_bytes(&bytes, &ext, name, &shown, margin)
    }

    /// An inclusion from the bytes of an `.obj` or `.stl` mesh (`format` `obj` or `stl`; mm,
    /// the rough's coordinates) named `name`, grown by `margin`; `shown` names it in errors.
    /// The mesh must be closed.
    pub fn from_bytes(
        bytes: &[u8],
        format: &str,
        name: &str,
        shown: &str,
        margin: f64,
    ) -> Result<Inclusion> {
        let mesh = read_triangles(bytes, format, shown)?;
        mesh.check_closed(shown).map_err(|e| match e {
            Error::Parse { source, message } => Error::Parse {
                source,
                message: message.replace("a rough must", "an inclusion must"),
            },
            other => other,
        })?;
        if mesh.vertices.iter().any(|p| !p.is_finite()) {
            return Err(Error::parse(
                shown,
                "a vertex coordinate is not a finite number",
            ));
        }
        Inclusion::from_points(name, shown, &mesh.vertices, margin)
    }
}
