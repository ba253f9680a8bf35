//! Pictures of the stone: recorded photon paths and the facets coloured by normal category,
//! both seen by an orthographic [`Camera`].

use super::{font, save, DrawResult, Figure, TAB10};
use crate::error::Result;
use crate::geometry::{DVec3, Polyhedron};
use crate::optics::color::{cmf, srgb_encode, xyz_to_linear_srgb};
use crate::photon::{face_category, PhotonPath, CATEGORY_LABELS};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// An orthographic camera looking at the girdle centre from azimuth (from +x toward +y) and
/// elevation (above the girdle plane), degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Azimuth, degrees.
    pub azimuth_deg: f64,
    /// Elevation, degrees.
    pub elevation_deg: f64,
}

impl Camera {
    /// Unit vectors (right, up, toward the camera).
    fn basis(&self) -> (DVec3, DVec3, DVec3) {
        let (a, e) = (
            self.azimuth_deg.to_radians(),
            self.elevation_deg.to_radians(),
        );
        let c = DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin());
        let right = DVec3::new(-a.sin(), a.cos(), 0.0);
        let up = c.cross(right);
        (right, up, c)
    }
    /// Screen coordinates (right, up) of `p`.
    pub fn project(&self, p: DVec3) -> (f64, f64) {
        let (r, u, _) = self.basis();
        (p.dot(r), p.dot(u))
    }
}

/// How path segments are coloured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathColor {
    /// By the number of surface interactions before the segment.
    Bounces,
    /// By the photon's wavelength (its sRGB colour).
    Wavelength,
}

/// Options of [`photon_paths`].
#[derive(Clone, Debug)]
pub struct PathStyle {
    /// The camera.
    pub camera: Camera,
    /// Colouring.
    pub color: PathColor,
    /// Draw the segment from the light to the stone.
    pub first_segment: bool,
    /// Opacity of each path, (0, 1].
    pub alpha: f64,
    /// Draw at most this many paths.
    pub max_paths: usize,
    /// Title.
    pub title: String,
}

/// Colours of the four face categories (< 45°, 45–90°, 90–135°, > 135° from up).
pub const CATEGORY_COLORS: [RGBColor; 4] = [TAB10[0], TAB10[2], TAB10[1], TAB10[3]];

/// Colours by interaction count: 0 = light → stone (grey), then after 1, 2, … interactions; the
/// third is a darker orange than Tableau's, which is too faint at low alpha on white.
const BOUNCE: [RGBColor; 8] = [
    RGBColor(150, 150, 150),
    TAB10[0],
    TAB10[2],
    RGBColor(230, 160, 0),
    TAB10[3],
    TAB10[4],
    TAB10[5],
    BLACK,
];

// ---------------------------------------------------------------------------------------------
// Pictures of the stone

/// Clip segment a→b to the rectangle; `None` if outside (Liang–Barsky).
fn clip(
    a: (f64, f64),
    b: (f64, f64),
    lo: (f64, f64),
    hi: (f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - lo.0),
        (dx, hi.0 - a.0),
        (-dy, a.1 - lo.1),
        (dy, hi.1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then_some({
        (
            (a.0 + t0 * dx, a.1 + t0 * dy),
            (a.0 + t1 * dx, a.1 + t1 * dy),
        )
    })
}

/// Square view window (lo, hi) around the stone's projection, `pad` times its size.
fn window(solid: &Polyhedron, cam: Camera, pad: f64) -> ((f64, f64), (f64, f64)) {
    let pts: Vec<(f64, f64)> = solid.vertices().iter().map(|v| cam.project(*v)).collect();
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for (x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let h = 0.5 * (x1 - x0).max(y1 - y0) * pad;
    ((cx - h, cy - h), (cx + h, cy + h))
}

/// Draw the stone's edges: front edges dark, back edges light.
fn draw_edges<DB: DrawingBackend, CT: plotters::coord::CoordTranslate<From = (f64, f64)>>(
    area: &DrawingArea<DB, CT>,
    solid: &Polyhedron,
    cam: Camera,
    front: RGBAColor,
    back: RGBAColor,
) -> DrawResult<DB> {
    let (_, _, toward) = cam.basis();
    for edge in solid.edges() {
        let visible = edge
            .facets
            .iter()
            .any(|&f| solid.facets()[f].plane.normal.dot(toward) > 1e-12);
        let a = cam.project(solid.vertices()[edge.a]);
        let b = cam.project(solid.vertices()[edge.b]);
        let style = if visible {
            front.stroke_width(1)
        } else {
            back.stroke_width(1)
        };
        area.draw(&PathElement::new(vec![a, b], style))?;
    }
    Ok(())
}

/// sRGB colour of a wavelength (saturated, brightness normalised). Wavelengths beyond
/// 400–670 nm take the colour of the nearer end: out there the colour-matching fit's tails,
/// not the hue, would decide the normalised colour.
pub fn wavelength_rgb(nm: f64) -> RGBColor {
    let l = xyz_to_linear_srgb(cmf(nm.clamp(400.0, 670.0)));
    let l = DVec3::new(l.x.max(0.0), l.y.max(0.0), l.z.max(0.0));
    let m = l.max_element().max(1e-9);
    let c = l / m;
    let f = |v: f64| (srgb_encode(v) * 255.0).round() as u8;
    RGBColor(f(c.x), f(c.y), f(c.z))
}

struct Paths<'a> {
    solid: &'a Polyhedron,
    paths: &'a [PhotonPath],
    style: &'a PathStyle,
}

impl Figure for Paths<'_> {
    fn size(&self) -> (u32, u32) {
        (900, 900)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let st = self.style;
        let cam = st.camera;
        let (lo, hi) = window(self.solid, cam, 2.6);
        let titled = root.margin(8, 0, 0, 0).titled(&st.title, font(22))?;
        let (main, foot) = titled.split_vertically(titled.dim_in_pixel().1 - 60);
        let mut chart = ChartBuilder::on(&main)
            .margin(10)
            .build_cartesian_2d(lo.0..hi.0, lo.1..hi.1)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .disable_axes()
            .draw()?;
        let area = chart.plotting_area();
        draw_edges(area, self.solid, cam, BLACK.mix(0.9), BLACK.mix(0.3))?;
        let n = st.max_paths.min(self.paths.len());
        let alpha = st.alpha.clamp(0.01, 1.0);
        for p in &self.paths[..n] {
            let pts: Vec<(f64, f64)> = p.points.iter().map(|q| cam.project(*q)).collect();
            for (k, w) in pts.windows(2).enumerate() {
                if k == 0 && !st.first_segment {
                    continue;
                }
                let c = match st.color {
                    PathColor::Bounces => BOUNCE[k.min(BOUNCE.len() - 1)],
                    PathColor::Wavelength => wavelength_rgb(p.wavelength),
                };
                if let Some((a, b)) = clip(w[0], w[1], lo, hi) {
                    let width = if n == 1 { 2 } else { 1 };
                    area.draw(&PathElement::new(
                        vec![a, b],
                        c.mix(alpha).stroke_width(width),
                    ))?;
                }
            }
            if n == 1 {
                for q in &pts[1..pts.len() - 1] {
                    area.draw(&Circle::new(*q, 3, BLACK.filled()))?;
                }
            }
        }
        // Legend / caption strip.
        let line = format!(
            "{} photon path{} · camera azimuth {}°, elevation {}° (orthographic) · window {:.2} D wide",
            n,
            if n == 1 { "" } else { "s" },
            cam.azimuth_deg,
            cam.elevation_deg,
            hi.0 - lo.0
        );
        foot.draw(&Text::new(line, (12, 4), font(15)))?;
        match st.color {
            PathColor::Bounces => {
                let labels = ["light → stone", "after 1", "2", "3", "4", "5", "6", "7+"];
                let mut x = 12;
                for (k, l) in labels.iter().enumerate() {
                    if k == 0 && !st.first_segment {
                        continue;
                    }
                    foot.draw(&Rectangle::new([(x, 30), (x + 22, 42)], BOUNCE[k].filled()))?;
                    foot.draw(&Text::new(l.to_string(), (x + 27, 28), font(15)))?;
                    x += 37 + 9 * l.chars().count() as i32;
                }
                foot.draw(&Text::new(
                    "interactions before the segment".to_string(),
                    (x + 8, 28),
                    font(15),
                ))?;
            }
            PathColor::Wavelength => {
                let x0 = 12;
                for (i, nm) in (380..=780).step_by(4).enumerate() {
                    let x = x0 + 3 * i as i32;
                    foot.draw(&Rectangle::new(
                        [(x, 30), (x + 3, 44)],
                        wavelength_rgb(nm as f64).filled(),
                    ))?;
                }
                foot.draw(&Text::new(
                    "380 – 780 nm (colour of each photon's wavelength)".to_string(),
                    (x0 + 3 * 101 + 12, 28),
                    font(15),
                ))?;
            }
        }
        Ok(())
    }
}

/// Photon paths seen from `style.camera` over the stone's edges (back edges faint), coloured
/// by bounce count or wavelength, each with opacity `style.alpha`; the segment from the light
/// is drawn only with `style.first_segment`. The window is 2.6× the stone's projected size;
/// longer segments are clipped at its border.
pub fn photon_paths(
    solid: &Polyhedron,
    paths: &[PhotonPath],
    style: &PathStyle,
    stem: &Path,
) -> Result<()> {
    save(
        &Paths {
            solid,
            paths,
            style,
        },
        stem,
    )
}

struct Facets<'a> {
    solid: &'a Polyhedron,
    cam: Camera,
    title: &'a str,
}

impl Facets<'_> {
    fn panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        cam: Camera,
        caption: &str,
    ) -> DrawResult<DB> {
        let (lo, hi) = window(self.solid, cam, 1.1);
        let mut chart = ChartBuilder::on(area)
            .caption(caption, font(18))
            .margin(10)
            .build_cartesian_2d(lo.0..hi.0, lo.1..hi.1)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .disable_axes()
            .draw()?;
        let plot = chart.plotting_area();
        let (_, _, toward) = cam.basis();
        for (i, f) in self.solid.facets().iter().enumerate() {
            let facing = f.plane.normal.dot(toward);
            if facing <= 1e-9 {
                continue;
            }
            let c = CATEGORY_COLORS[face_category(f.plane.normal) as usize];
            // Shade by facing so neighbouring facets of one category stay distinguishable.
            let s = 0.55 + 0.45 * facing;
            let shaded = RGBColor(
                (c.0 as f64 * s) as u8,
                (c.1 as f64 * s) as u8,
                (c.2 as f64 * s) as u8,
            );
            let poly: Vec<(f64, f64)> = self
                .solid
                .facet_polygon(i)
                .iter()
                .map(|v| cam.project(*v))
                .collect();
            plot.draw(&Polygon::new(poly, shaded.filled()))?;
        }
        draw_edges(plot, self.solid, cam, BLACK.mix(1.0), TRANSPARENT)?;
        Ok(())
    }
}

impl Figure for Facets<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, 680)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let titled = root.margin(8, 0, 0, 0).titled(self.title, font(24))?;
        let (main, foot) = titled.split_vertically(titled.dim_in_pixel().1 - 40);
        let panels = main.split_evenly((1, 2));
        let below = Camera {
            azimuth_deg: self.cam.azimuth_deg,
            elevation_deg: -self.cam.elevation_deg,
        };
        self.panel(
            &panels[0],
            self.cam,
            &format!(
                "from above: azimuth {}°, elevation {}°",
                self.cam.azimuth_deg, self.cam.elevation_deg
            ),
        )?;
        self.panel(
            &panels[1],
            below,
            &format!(
                "from below: azimuth {}°, elevation {}°",
                below.azimuth_deg, below.elevation_deg
            ),
        )?;
        let mut x = 20;
        foot.draw(&Text::new(
            "facet normal from up:".to_string(),
            (x, 8),
            font(17),
        ))?;
        x += 185;
        for (k, l) in CATEGORY_LABELS.iter().enumerate() {
            foot.draw(&Rectangle::new(
                [(x, 8), (x + 24, 26)],
                CATEGORY_COLORS[k].filled(),
            ))?;
            foot.draw(&Text::new(l.to_string(), (x + 30, 8), font(17)))?;
            x += 130;
        }
        Ok(())
    }
}

/// The stone seen from `camera` and from the mirrored camera below, facets filled with the
/// colour of their normal category (< 45°, 45–90°, 90–135°, > 135° from up), shaded by how
/// squarely they face the camera.
pub fn facet_categories(
    solid: &Polyhedron,
    camera: Camera,
    title: &str,
    stem: &Path,
) -> Result<()> {
    save(
        &Facets {
            solid,
            cam: camera,
            title,
        },
        stem,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camera_projects_up_to_screen_up() {
        let cam = Camera {
            azimuth_deg: 0.0,
            elevation_deg: 0.0,
        };
        assert_eq!(cam.project(DVec3::Z), (0.0, 1.0));
        assert_eq!(cam.project(DVec3::Y), (1.0, 0.0));
        assert!(
            clip((-2.0, 0.0), (2.0, 0.0), (-1.0, -1.0), (1.0, 1.0))
                == Some(((-1.0, 0.0), (1.0, 0.0)))
        );
        assert!(clip((-2.0, 5.0), (2.0, 5.0), (-1.0, -1.0), (1.0, 1.0)).is_none());
    }
}
