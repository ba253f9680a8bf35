//! The photograph's camera: where it looks from ([`View`]), its projection ([`Projection`])
//! and, for a perspective camera, the tiles of parallel beams it is traced in ([`Tile`]).
//!
//! Image coordinates are the plane through the stone's centre facing the camera, in girdle
//! diameters (units of the canonical solid), `x` to the right and `y` up: an orthographic
//! picture is that plane seen along the view, a perspective picture the pinhole projection
//! onto it from the camera (so a point on the plane stays where it is, nearer points grow).
//!
//! **Perspective in tiles.** Sight lines through a pinhole diverge; the beam tracer's beams
//! are parallel. The picture is cut into square tiles; each is traced as an orthographic
//! picture along the sight line through its centre ([`Tile::frame`]), limited to the part of
//! the stone that the tile shows ([`Tile::window`]), and that picture is sheared onto the
//! image plane along the same direction ([`Tile::to_image`]): exact on the tile's central
//! sight line, off by the sight lines' spread within a tile elsewhere (measured in the tests
//! against a brute-force tracer of diverging sight lines). Tiles tile the picture exactly:
//! their windows' images are the tiles' squares.

use crate::beam::Frame;
use crate::error::{Error, Result};
use crate::io::text::number;
use glam::{DMat2, DMat3, DVec2, DVec3, DVec4};

/// Where the camera looks at the stone from.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct View {
    /// Elevation of the camera above the horizon, degrees (90: straight above, face-up;
    /// 0: a side view; negative: from below).
    pub elevation_deg: f64,
    /// Azimuth of the camera, degrees counter-clockwise seen from above, 0 = in front (on
    /// the −y side), so that `90@0` is the face-up picture with x to the right and y up.
    pub azimuth_deg: f64,
}

impl View {
    /// Straight above (the face-up picture of `render`).
    pub const FACE_UP: View = View {
        elevation_deg: 90.0,
        azimuth_deg: 0.0,
    };

    /// The camera's azimuth in the world: degrees from +x toward +y.
    pub fn world_azimuth_deg(&self) -> f64 {
        self.azimuth_deg - 90.0
    }

    /// The view's axes in the world: the direction from the camera to the stone (`dir`),
    /// the image's right and up (`right × up = −dir`).
    pub fn axes(&self) -> (DVec3, DVec3, DVec3) {
        let (e, a) = (
            self.elevation_deg.to_radians(),
            self.world_azimuth_deg().to_radians(),
        );
        let c = DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin());
        let right = DVec3::new(-a.sin(), a.cos(), 0.0);
        let up = c.cross(right);
        (-c, right, up)
    }
}

/// `ELEV` or `ELEV@AZ`: a view from ELEV in [−90, 90] degrees above the horizon, from azimuth
/// AZ in [−360, 360] degrees (default 0, the front); the error names `field`.
///
/// ```
/// use facetlab::render::photo::parse_view;
/// let v = parse_view("view", "30@45").unwrap();
/// assert_eq!((v.elevation_deg, v.azimuth_deg), (30.0, 45.0));
/// assert!(parse_view("view", "95").is_err());
/// ```
pub fn parse_view(field: &str, s: &str) -> Result<View> {
    let bad = || {
        Error::invalid(
            field,
            format!("`{s}` is not allowed; give ELEV or ELEV@AZ: the camera's elevation in [-90, 90] degrees (90 = straight above, 0 = a side view) and azimuth in [-360, 360] degrees (30@45)"),
        )
    };
    let (e, a) = s.split_once('@').unwrap_or((s, "0"));
    let elevation_deg = number(field, e, -90.0, 90.0, "degrees").map_err(|_| bad())?;
    let azimuth_deg = number(field, a, -360.0, 360.0, "degrees").map_err(|_| bad())?;
    Ok(View {
        elevation_deg,
        azimuth_deg,
    })
}

/// How the camera projects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Parallel sight lines (a distant camera with a long lens): exact.
    Orthographic,
    /// A pinhole this far from the stone's centre, in girdle diameters (units of the
    /// canonical solid), traced in tiles of `tile` pixels.
    Perspective {
        /// Distance from the stone's centre.
        distance: f64,
        /// Tile side, pixels.
        tile: usize,
    },
}

/// The camera in the stone's frame: its axes (world), the pose (stone → world), the
/// picture's square and its projection.
#[derive(Clone, Debug)]
pub struct Camera {
    /// From the camera toward the stone (world, unit).
    pub dir: DVec3,
    /// Image right (world).
    pub right: DVec3,
    /// Image up (world).
    pub up: DVec3,
    /// Stone coordinates → world.
    pub rot: DMat3,
    /// Half the side of the picture's square, image units.
    pub half: f64,
    /// Pixels per side.
    pub size: usize,
    /// The projection.
    pub projection: Projection,
}

impl Camera {
    /// The orthographic frame in the stone's coordinates (for the beam tracer).
    pub fn frame(&self) -> Frame {
        let t = self.rot.transpose();
        Frame {
            dir: t * self.dir,
            u: t * self.right,
            v: t * self.up,
        }
    }

    /// The camera's position (world) for a perspective camera.
    fn eye(&self) -> Option<DVec3> {
        match self.projection {
            Projection::Perspective { distance, .. } => Some(-self.dir * distance),
            Projection::Orthographic => None,
        }
    }

    /// The point of the image plane at image coordinates `p` (world).
    #[inline]
    pub fn plane_point(&self, p: DVec2) -> DVec3 {
        self.right * p.x + self.up * p.y
    }

    /// The sight line through image point `p`: a point on it and its direction (world).
    #[inline]
    pub fn ray(&self, p: DVec2) -> (DVec3, DVec3) {
        let x = self.plane_point(p);
        match self.eye() {
            Some(c) => (c, (x - c).normalize()),
            None => (x, self.dir),
        }
    }

    /// The perspective tiles, in rows from the bottom (none for an orthographic camera).
    pub fn tiles(&self) -> Vec<Tile> {
        let Projection::Perspective { distance, tile } = self.projection else {
            return Vec::new();
        };
        let n = self.size.div_ceil(tile.max(1));
        let h = 2.0 * self.half / self.size as f64;
        let eye = -self.dir * distance;
        let t = self.rot.transpose();
        let mut out = Vec::with_capacity(n * n);
        for j in 0..n {
            for i in 0..n {
                let (i0, i1) = (i * tile, ((i + 1) * tile).min(self.size));
                let (j0, j1) = (j * tile, ((j + 1) * tile).min(self.size));
                let lo = DVec2::new(-self.half + i0 as f64 * h, -self.half + j0 as f64 * h);
                let hi = DVec2::new(-self.half + i1 as f64 * h, -self.half + j1 as f64 * h);
                let centre = self.plane_point(0.5 * (lo + hi));
                let d = (centre - eye).normalize();
                let u = (self.right - d * self.right.dot(d)).normalize();
                let v = u.cross(d);
                // Footprint (x · u, x · v) ↦ image: slide along d onto the image plane.
                let k = d.dot(self.dir);
                let img = |y: DVec3| {
                    let x = y - d * (y.dot(self.dir) / k);
                    DVec2::new(x.dot(self.right), x.dot(self.up))
                };
                let m = DMat2::from_cols(img(u), img(v));
                let inv = m.inverse();
                let corners = [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
                let q: Vec<DVec2> = corners.iter().map(|&c| inv * c).collect();
                // The window: the quad's edges, outward normals (it is counter-clockwise
                // when m keeps orientation).
                let orient = if m.determinant() > 0.0 { 1.0 } else { -1.0 };
                let (tu, tv) = (t * u, t * v);
                let window = (0..4)
                    .map(|k| {
                        let (a, b) = (q[k], q[(k + 1) % 4]);
                        let e = b - a;
                        let nrm = DVec2::new(e.y, -e.x) * orient;
                        (tu * nrm.x + tv * nrm.y).extend(nrm.dot(a))
                    })
                    .collect();
                out.push(Tile {
                    frame: Frame {
                        dir: t * d,
                        u: tu,
                        v: tv,
                    },
                    window,
                    to_image: [m.x_axis.x, m.y_axis.x, m.x_axis.y, m.y_axis.y],
                    quad: q,
                    dir_world: d,
                });
            }
        }
        out
    }
}

/// One tile of a perspective picture.
#[derive(Clone, Debug)]
pub struct Tile {
    /// The orthographic frame it is traced along (stone coordinates).
    pub frame: Frame,
    /// The part of the cross-section it shows: `n · x <= c` for every `(n, c)`.
    pub window: Vec<DVec4>,
    /// Footprint → image coordinates, `[a, b, c, d]`: `(a x + b y, c x + d y)`.
    pub to_image: [f64; 4],
    /// The window in footprint coordinates (its corners).
    pub quad: Vec<DVec2>,
    /// Its sight line's direction (world).
    pub dir_world: DVec3,
}

impl Tile {
    /// A footprint point in image coordinates.
    #[inline]
    pub fn image(&self, p: DVec2) -> DVec2 {
        let m = self.to_image;
        DVec2::new(m[0] * p.x + m[1] * p.y, m[2] * p.x + m[3] * p.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Straight above from the front is the face-up frame (x right, y up); the axes are
    /// orthonormal with right × up = −dir from any view.
    #[test]
    fn views_have_right_handed_axes() {
        let (d, r, u) = View::FACE_UP.axes();
        assert!((d - DVec3::NEG_Z).length() < 1e-15);
        assert!((r - DVec3::X).length() < 1e-15);
        assert!((u - DVec3::Y).length() < 1e-15);
        for (e, a) in [(30.0, 0.0), (0.0, 45.0), (-60.0, 200.0), (89.0, -30.0)] {
            let (d, r, u) = View {
                elevation_deg: e,
                azimuth_deg: a,
            }
            .axes();
            assert!((r.cross(u) + d).length() < 1e-12);
            assert!(r.dot(u).abs() < 1e-12 && (r.length() - 1.0).abs() < 1e-12);
            // Up points up (or is horizontal face-on).
            assert!(u.z >= -1e-12);
        }
    }

    /// The tiles' windows are the tiles' squares: each window corner maps onto its tile's
    /// corner, and the tiles' central sight lines pass through the eye.
    #[test]
    fn tiles_cover_the_picture() {
        let (dir, right, up) = View {
            elevation_deg: 30.0,
            azimuth_deg: 20.0,
        }
        .axes();
        let cam = Camera {
            dir,
            right,
            up,
            rot: DMat3::IDENTITY,
            half: 0.6,
            size: 100,
            projection: Projection::Perspective {
                distance: 20.0,
                tile: 32,
            },
        };
        let tiles = cam.tiles();
        assert_eq!(tiles.len(), 16);
        let mut area = 0.0;
        for t in &tiles {
            let img: Vec<DVec2> = t.quad.iter().map(|&q| t.image(q)).collect();
            area += crate::geometry::clip2d::area(&img);
            // Footprint coordinates of a point x are (x · u, x · v): the window holds the
            // quad's corners on its edges.
            for &q in &t.quad {
                let x = t.frame.u * q.x + t.frame.v * q.y;
                for h in &t.window {
                    assert!(h.truncate().dot(x) <= h.w + 1e-12);
                }
            }
            let eye = -dir * 20.0;
            let centre = 0.25 * img.iter().copied().sum::<DVec2>();
            let on = cam.plane_point(centre) - eye;
            assert!(on.normalize().cross(t.dir_world).length() < 1e-9);
        }
        assert!((area - 1.2 * 1.2).abs() < 1e-12, "{area}");
    }
}
