//! The rough: a convex solid in millimetres, as half-spaces, from a scanned mesh (its convex
//! hull) or a bundled crystal form.

use super::ball::Ball;
use super::mesh::{read_triangles, TriMesh};
use crate::error::{setting, shown, Error, Result};
use crate::geometry::{hull, DVec3, FacetPlane, HullOptions, Plane, Polyhedron};
use glam::{DMat3, DQuat};
use std::path::Path;

/// The bundled crystal forms, for `facetlab plan FORM --size-mm L` (`sphere` is an exact
/// ball, a check with a closed form rather than a crystal).
pub const CRYSTALS: [&str; 5] = ["octahedron", "dodecahedron", "cube", "macle", "sphere"];

/// Tangent planes of the polyhedron that stands for a ball in pictures and meshes.
const BALL_PLANES: usize = 192;

/// A mesh whose largest extent is outside this range (mm) is taken not to be in millimetres
/// unless `--size-mm` is given.
pub const PLAUSIBLE_MM: [f64; 2] = [0.3, 300.0];

/// The largest rough, mm: its largest extent (a crystal form's, a mesh's `--size-mm`) and every
/// coordinate's distance from the origin stay within it (the solids are built inside a box of
/// ±1000). Every face checks a rough's size by [`rough_size_mm`].
pub const ROUGH_MAX_MM: f64 = 500.0;

/// A rough's largest extent `size_mm`, in (0, [`ROUGH_MAX_MM`]] mm; the one-line error names
/// `field`.
pub fn rough_size_mm(field: &str, size_mm: f64) -> Result<f64> {
    if size_mm.is_finite() && size_mm > 0.0 && size_mm <= ROUGH_MAX_MM {
        Ok(size_mm)
    } else {
        Err(Error::invalid(
            field,
            format!(
                "{} is not allowed; give the rough's largest extent in (0, {ROUGH_MAX_MM}] mm",
                shown(size_mm)
            ),
        ))
    }
}

/// [`rough_size_mm`] of a text (a face's number as typed, quoted in the error when it is none).
pub fn parse_rough_size_mm(field: &str, text: &str) -> Result<f64> {
    match text.trim().parse::<f64>() {
        Ok(x) => rough_size_mm(field, x),
        Err(_) => Err(Error::invalid(
            field,
            format!(
                "`{text}` is not allowed; give the rough's largest extent in (0, {ROUGH_MAX_MM}] mm"
            ),
        )),
    }
}

/// The most vertices a rough's hull keeps. A scan's hull has nearly every vertex of its mesh
/// (200,000 for a mesh of 400,000 triangles); beyond this many the hull is grown greedily,
/// always by the point farthest outside it, and stops here, inside the full hull: every plan
/// then fits the scan, and [`Rough::left_out`] says how much of it the hull leaves out (about
/// 2 µm of an 8 mm scan). Planning, pictures and files cost in proportion to the hull's planes
/// (`cargo bench --bench plan`).
pub const HULL_VERTICES: usize = 8000;

/// A convex rough in millimetres.
#[derive(Clone, Debug)]
pub struct Rough {
    /// Name (the file stem or the crystal form).
    pub name: String,
    /// The convex solid (the hull of a mesh), in mm.
    pub solid: Polyhedron,
    /// The volume the mesh itself encloses (mm³), for a mesh; `None` for a crystal form.
    pub mesh_volume: Option<f64>,
    /// For the `sphere` form: the exact ball. The planner then places cuts by their smallest
    /// enclosing ball (`super::ball`), and `solid` is only its circumscribed polyhedron, for
    /// pictures and meshes.
    pub ball: Option<Ball>,
    /// How far the farthest point of the mesh stands outside `solid` (mm): 0 unless its hull
    /// had more than [`HULL_VERTICES`] vertices.
    pub left_out: f64,
    /// The vertices of the mesh's hull as planned (at most [`HULL_VERTICES`]; 0 for a
    /// crystal form).
    pub hull_vertices: usize,
}

impl Rough {
    /// The rough's half-spaces `normal · x <= offset` (mm) (for a ball: its drawing's).
    pub fn planes(&self) -> Vec<Plane> {
        self.solid.facets().iter().map(|f| f.plane).collect()
    }

    /// The hull's volume in mm³ (what yields are measured against).
    pub fn volume(&self) -> f64 {
        match self.ball {
            Some(b) => b.volume(),
            None => self.solid.volume(),
        }
    }

    /// How much volume the convex hull adds to a mesh that is not convex, as a fraction of the
    /// mesh's own volume (0 for a convex mesh or a crystal form).
    pub fn hull_excess(&self) -> f64 {
        match self.mesh_volume {
            Some(v) if v > 0.0 => (self.volume() - v).max(0.0) / v,
            _ => 0.0,
        }
    }

    /// The largest side of the rough's bounding box (mm).
    pub fn size(&self) -> f64 {
        if let Some(b) = self.ball {
            return 2.0 * b.radius;
        }
        let (lo, hi) = self.solid.bounding_box();
        (hi - lo).max_element()
    }

    /// A rough from a convex solid's vertices (mm).
    pub fn from_points(name: &str, pts: &[DVec3], mesh_volume: Option<f64>) -> Result<Rough> {
        let far = pts
            .iter()
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
        if far > ROUGH_MAX_MM {
            return Err(Error::invalid(
                name,
                format!("the rough reaches {far:.1} mm from the origin; allowed up to {ROUGH_MAX_MM} mm (move it nearer the origin)"),
            ));
        }
        // Rounding can leave the planes of nearly coplanar facets meeting in a knot of
        // points that do not weld into one vertex; a coarser merge then joins those facets.
        let mut failure = None;
        for merge_tol in [1e-6, 1e-5, 1e-4] {
            let hull = hull(
                pts,
                HullOptions {
                    merge_tol,
                    max_vertices: Some(HULL_VERTICES),
                },
            )
            .map_err(|e| match e {
                Error::Geometry(m) => Error::parse(name, format!("the rough's convex hull: {m}")),
                other => other,
            })?;
            match rough_solid(&hull.planes, "r") {
                Ok(solid) => {
                    return Ok(Rough {
                        name: name.to_string(),
                        solid,
                        mesh_volume,
                        ball: None,
                        left_out: hull.left_out,
                        hull_vertices: hull.vertices,
                    })
                }
                Err(e) => {
                    failure.get_or_insert(e);
                }
            }
        }
        Err(failure.map_or_else(|| Error::parse(name, "no hull"), |e| e.context(name)))
    }

    /// An exact ball of diameter `size_mm` centred on the origin (`solid` its circumscribed
    /// polyhedron of `BALL_PLANES` tangent planes at Fibonacci points, for drawing).
    pub fn ball(size_mm: f64) -> Result<Rough> {
        let radius = 0.5 * size_mm;
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        let planes: Vec<Plane> = (0..BALL_PLANES)
            .filter_map(|k| {
                let z = 1.0 - (2 * k + 1) as f64 / BALL_PLANES as f64;
                let rho = (1.0 - z * z).sqrt();
                let a = golden * k as f64;
                Plane::new(DVec3::new(rho * a.cos(), rho * a.sin(), z), radius)
            })
            .collect();
        Ok(Rough {
            name: "sphere".into(),
            solid: rough_solid(&planes, "sphere")?,
            mesh_volume: None,
            ball: Some(Ball {
                centre: DVec3::ZERO,
                radius,
            }),
            left_out: 0.0,
            hull_vertices: 0,
        })
    }

    /// A rough from an `.obj` or `.stl` mesh in millimetres. With `size_mm`, the mesh is
    /// scaled so that its largest extent is `size_mm` and its bounding box is centred on the
    /// origin (for a mesh in other units); without it, a mesh that says it is not in mm, or whose largest
    /// extent is outside [`PLAUSIBLE_MM`], is refused.
    pub fn from_mesh(path: &Path, size_mm: Option<f64>) -> Result<Rough> {
        let shown = path.display().to_string();
        let ext = path
            .extension()
            .map_or(String::new(), |e| e.to_string_lossy().to_ascii_lowercase());
        let bytes = std::fs::read(path).map_err(|e| Error::io(&shown, e))?;
        let mesh = read_triangles(&bytes, &ext, &shown)?;
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("rough");
        Rough::from_trimesh(name, &shown, mesh, size_mm)
    }

    /// [`Rough::from_mesh`] on triangles already read (`source` names them in messages).
    pub fn from_trimesh(
        name: &str,
        source: &str,
        mut mesh: TriMesh,
        size_mm: Option<f64>,
    ) -> Result<Rough> {
        mesh.check_closed(source)?;
        if let Some(i) = mesh.vertices.iter().position(|p| !p.is_finite()) {
            return Err(Error::parse(
                source,
                format!(
                    "vertex {} has a coordinate that is not a finite number",
                    i + 1
                ),
            ));
        }
        let (lo, hi) = bounds(&mesh.vertices);
        let mut extent = (hi - lo).max_element();
        match size_mm {
            Some(l) => {
                if !(l.is_finite() && l > 0.0 && extent > 0.0) {
                    return Err(Error::invalid(
                        "rough size",
                        format!("{} is not a size; give the rough's largest extent in mm, > 0", shown(l)),
                    ));
                }
                // A mesh in other units: its position means nothing in mm either, so it is
                // centred on the origin as it is scaled.
                let c = 0.5 * (lo + hi);
                for p in &mut mesh.vertices {
                    *p = (*p - c) * (l / extent);
                }
                extent = l;
            }
            None if mesh.units_not_mm => {
                return Err(Error::invalid(
                    source,
                    format!("the file says its units are not millimetres; give {} L (the rough's largest extent in mm)", setting("rough size")),
                ))
            }
            None if !(PLAUSIBLE_MM[0]..=PLAUSIBLE_MM[1]).contains(&extent) => {
                return Err(Error::invalid(
                    source,
                    format!(
                        "the mesh is {extent:.4} units across, not a plausible size in millimetres ({} to {} mm); give {} L (its largest extent in mm)",
                        PLAUSIBLE_MM[0], PLAUSIBLE_MM[1], setting("rough size")
                    ),
                ))
            }
            None => {}
        }
        let volume = mesh.enclosed_volume();
        if volume.is_nan() || volume <= 1e-9 * extent.powi(3) {
            return Err(Error::parse(
                source,
                "the mesh encloses no volume (it is flat or degenerate); a rough must be a solid",
            ));
        }
        Rough::from_points(name, &mesh.vertices, Some(volume))
    }

    /// A bundled crystal form (one of [`CRYSTALS`]) whose largest extent is `size_mm`, centred
    /// on the origin: the octahedron (diamond's usual habit, vertices on the axes), the
    /// rhombic dodecahedron, the cube, and a macle (a spinel-law twin: an octahedron flattened
    /// to a third of its height along a three-fold axis, that axis turned to z).
    pub fn crystal(form: &str, size_mm: f64) -> Result<Rough> {
        rough_size_mm("rough size", size_mm)?;
        if form == "sphere" {
            return Rough::ball(size_mm);
        }
        let mut normals: Vec<(DVec3, f64)> = Vec::new();
        let signs = [-1.0, 1.0];
        match form {
            "octahedron" | "macle" => {
                for x in signs {
                    for y in signs {
                        for z in signs {
                            normals.push((DVec3::new(x, y, z), 1.0));
                        }
                    }
                }
            }
            "dodecahedron" => {
                for a in signs {
                    for b in signs {
                        normals.push((DVec3::new(a, b, 0.0), 1.0));
                        normals.push((DVec3::new(a, 0.0, b), 1.0));
                        normals.push((DVec3::new(0.0, a, b), 1.0));
                    }
                }
            }
            "cube" => {
                for a in signs {
                    normals.push((DVec3::new(a, 0.0, 0.0), 1.0));
                    normals.push((DVec3::new(0.0, a, 0.0), 1.0));
                    normals.push((DVec3::new(0.0, 0.0, a), 1.0));
                }
            }
            _ => {
                return Err(Error::invalid(
                    "ROUGH",
                    format!(
                        "`{form}` is neither an .obj/.stl file nor a crystal form; known forms: {}",
                        CRYSTALS.join(", ")
                    ),
                ))
            }
        }
        // Every plane at unit distance along its normal's direction (offsets are along the
        // unnormalised normal, so divide by its length).
        let mut planes: Vec<Plane> = normals
            .iter()
            .filter_map(|(n, d)| Plane::new(*n, d * n.length()))
            .collect();
        if form == "macle" {
            // Flatten along (1,1,1): the two faces across that axis move in to a third of
            // their distance; then turn that axis to z.
            let axis = DVec3::ONE.normalize();
            let turn = DQuat::from_rotation_arc(axis, DVec3::Z);
            for p in &mut planes {
                if p.normal.dot(axis).abs() > 0.99 {
                    p.offset /= 3.0;
                }
                p.normal = turn * p.normal;
            }
        }
        let unit = rough_solid(&planes, form)?;
        let (lo, hi) = unit.bounding_box();
        let solid = unit.scaled(size_mm / (hi - lo).max_element());
        Ok(Rough {
            name: form.to_string(),
            solid,
            mesh_volume: None,
            ball: None,
            left_out: 0.0,
            hull_vertices: 0,
        })
    }

    /// The rough's symmetries: every orthogonal map `G` (turns and mirrors) with
    /// `x ↦ c + G·(x − c)` carrying the rough onto itself, `c` its centroid, the identity
    /// first; empty for a ball (every orthogonal map about its centre is one). Found by
    /// sending a facet and a second, not parallel one to every pair of facets of the same
    /// distance from `c`, area and angle, and keeping the maps that carry every facet onto a
    /// facet (to 1e-6 of the rough's size).
    pub fn symmetries(&self) -> Vec<DMat3> {
        if self.ball.is_some() {
            return Vec::new();
        }
        let c = self.solid.centroid();
        let size = self.size();
        let tol = 1e-6;
        let sig: Vec<(DVec3, f64, f64)> = self
            .solid
            .facets()
            .iter()
            .map(|f| {
                let n = f.plane.normal;
                (
                    n,
                    (f.plane.offset - n.dot(c)) / size,
                    f.area / (size * size),
                )
            })
            .collect();
        let alike = |a: &(DVec3, f64, f64), b: &(DVec3, f64, f64)| {
            (a.1 - b.1).abs() < tol && (a.2 - b.2).abs() < tol
        };
        let mut out = vec![DMat3::IDENTITY];
        let Some(f1) = (1..sig.len()).find(|&j| sig[j].0.cross(sig[0].0).length() > 0.1) else {
            return out;
        };
        let (n0, n1) = (sig[0].0, sig[f1].0);
        let from = DMat3::from_cols(n0, n1, n0.cross(n1));
        let Some(from_inv) = (from.determinant().abs() > 1e-9).then(|| from.inverse()) else {
            return out;
        };
        for m0 in sig.iter().filter(|m| alike(m, &sig[0])) {
            for m1 in sig.iter().filter(|m| alike(m, &sig[f1])) {
                if (m0.0.dot(m1.0) - n0.dot(n1)).abs() > tol {
                    continue;
                }
                for hand in [1.0, -1.0] {
                    let to = DMat3::from_cols(m0.0, m1.0, hand * m0.0.cross(m1.0));
                    let g = to * from_inv;
                    if (g - DMat3::IDENTITY)
                        .abs()
                        .to_cols_array()
                        .iter()
                        .all(|x| *x < tol)
                    {
                        continue;
                    }
                    let onto = sig.iter().all(|a| {
                        let n = g * a.0;
                        sig.iter().any(|b| alike(a, b) && (n - b.0).length() < tol)
                    });
                    if onto
                        && !out
                            .iter()
                            .any(|h| (*h - g).abs().to_cols_array().iter().all(|x| *x < tol))
                    {
                        out.push(g);
                    }
                }
            }
        }
        out
    }

    /// The rough turned by `rotation` about the origin and then moved by `shift`.
    pub fn moved(&self, rotation: DQuat, shift: DVec3) -> Result<Rough> {
        if let Some(b) = self.ball {
            let planes: Vec<Plane> = self
                .planes()
                .iter()
                .map(|p| {
                    let normal = rotation * p.normal;
                    Plane {
                        normal,
                        offset: p.offset + normal.dot(shift),
                    }
                })
                .collect();
            let mut r = self.clone();
            r.solid = rough_solid(&planes, "sphere")?;
            r.ball = Some(Ball {
                centre: rotation * b.centre + shift,
                radius: b.radius,
            });
            return Ok(r);
        }
        let pts: Vec<DVec3> = self
            .solid
            .vertices()
            .iter()
            .map(|v| rotation * *v + shift)
            .collect();
        Rough::from_points(&self.name, &pts, self.mesh_volume)
    }
}

/// The solid of a rough's planes, facets named `PREFIX-1`, `PREFIX-2`, … of tier `rough`.
fn rough_solid(planes: &[Plane], prefix: &str) -> Result<Polyhedron> {
    let named: Vec<FacetPlane> = planes
        .iter()
        .zip(1..)
        .map(|(p, i)| FacetPlane {
            plane: *p,
            name: format!("{prefix}-{i}"),
            tier: "rough".into(),
        })
        .collect();
    Polyhedron::from_planes(&named)
}

fn bounds(pts: &[DVec3]) -> (DVec3, DVec3) {
    pts.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    )
}

/// Load a rough: a crystal form name (needs `size_mm`) or a mesh path.
pub fn load_rough(arg: &str, size_mm: Option<f64>) -> Result<Rough> {
    if CRYSTALS.contains(&arg) {
        let Some(l) = size_mm else {
            return Err(Error::invalid(
                "rough size",
                format!(
                    "the crystal form `{arg}` needs {} L (its largest extent in mm)",
                    setting("rough size")
                ),
            ));
        };
        return Rough::crystal(arg, l);
    }
    let path = Path::new(arg);
    if path.extension().is_none() && !path.exists() {
        return Rough::crystal(arg, size_mm.unwrap_or(1.0));
    }
    Rough::from_mesh(path, size_mm)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rough_size_is_in_its_one_range_and_the_crystal_forms_keep_it() {
        assert_eq!(rough_size_mm("size", ROUGH_MAX_MM).unwrap(), ROUGH_MAX_MM);
        assert_eq!(parse_rough_size_mm("size", " 1e-4 ").unwrap(), 1e-4);
        for x in [
            0.0,
            -1.0,
            ROUGH_MAX_MM * (1.0 + 1e-12),
            f64::NAN,
            f64::INFINITY,
        ] {
            let e = rough_size_mm("size", x).unwrap_err().to_string();
            assert_eq!(
                e,
                format!(
                    "size: {} is not allowed; give the rough's largest extent in (0, 500] mm",
                    shown(x)
                )
            );
        }
        let e = parse_rough_size_mm("size", "big").unwrap_err().to_string();
        assert_eq!(
            e,
            "size: `big` is not allowed; give the rough's largest extent in (0, 500] mm"
        );
        // A crystal form at the largest size is built, and measures it; one beyond is refused
        // by the same check.
        let r = Rough::crystal("cube", ROUGH_MAX_MM).unwrap();
        assert!((r.size() - ROUGH_MAX_MM).abs() < 1e-9 * ROUGH_MAX_MM);
        let e = Rough::crystal("cube", 600.0).unwrap_err().to_string();
        assert!(e.starts_with("rough size: 600 is not allowed"), "{e}");
    }
}
