//! Pictures of a plan: the rough seen from the top (x, y), the front (x, z) and the side
//! (y, z), orthographic and at one scale, its silhouette grey with its edges, each planned cut
//! drawn inside as a tinted silhouette with its edges in the cut's series colour. A rough of
//! more than [`EDGES_DRAWN`] facets (a scan) shows only its ridges, the edges where its
//! surface turns by more than [`RIDGE_DEG`]: its thousands of small facets would grey the
//! picture over and make its SVG megabytes long.

use super::{font, DrawResult, Figure, SERIES};
use crate::geometry::{DVec2, DVec3, Polyhedron};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Three views of a rough with cuts inside.
pub struct ThreeViews<'a> {
    /// The rough (mm).
    pub rough: &'a Polyhedron,
    /// The placed cuts (mm), each with a label for the caption.
    pub cuts: Vec<(&'a Polyhedron, String)>,
    /// Caption above the views.
    pub title: String,
}

const PANEL: u32 = 360;

/// A rough with more facets than this is drawn with its ridges only.
pub const EDGES_DRAWN: usize = 2000;

/// The smallest turn between two facets that makes a ridge, in degrees.
pub const RIDGE_DEG: f64 = 5.0;

/// A view: its caption and the projection onto the picture plane (right, up).
type View = (&'static str, fn(DVec3) -> DVec2);
const TOP: u32 = 56;

/// Convex hull of 2-D points, counter-clockwise (Andrew's monotone chain).
fn hull2(mut pts: Vec<DVec2>) -> Vec<DVec2> {
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    let turn = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut out: Vec<DVec2> = Vec::new();
    for pass in 0..2 {
        let start = out.len();
        let iter: Box<dyn Iterator<Item = &DVec2>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for p in iter {
            while out.len() >= start + 2 && turn(out[out.len() - 2], out[out.len() - 1], *p) <= 0.0
            {
                out.pop();
            }
            out.push(*p);
        }
        out.pop();
    }
    out
}

impl Figure for ThreeViews<'_> {
    fn size(&self) -> (u32, u32) {
        (3 * PANEL, PANEL + TOP)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let (lo, hi) = self.rough.bounding_box();
        let centre = 0.5 * (lo + hi);
        let extent = (hi - lo).max_element().max(1e-9);
        let scale = 0.86 * PANEL as f64 / extent;
        root.draw(&Text::new(self.title.clone(), (10, 6), font(17)))?;
        let views: [View; 3] = [
            ("top (x right, y up)", |p| DVec2::new(p.x, p.y)),
            ("front (x right, z up)", |p| DVec2::new(p.x, p.z)),
            ("side (y right, z up)", |p| DVec2::new(p.y, p.z)),
        ];
        // Labels in a row, each as wide as its text (about 7.5 px a character at 14 px).
        let mut x = 10;
        for (k, label) in self.cuts.iter().map(|c| &c.1).enumerate() {
            let colour = SERIES[k % SERIES.len()];
            root.draw(&Text::new(label.clone(), (x, 30), font(14).color(&colour)))?;
            x += 15 * label.chars().count() as i32 / 2 + 24;
        }
        for (v, (name, project)) in views.iter().enumerate() {
            let x0 = v as f64 * PANEL as f64 + PANEL as f64 / 2.0;
            let y0 = TOP as f64 + PANEL as f64 / 2.0;
            let c2 = project(centre);
            let px = |p: DVec3| -> (i32, i32) {
                let q = (project(p) - c2) * scale;
                ((x0 + q.x).round() as i32, (y0 - q.y).round() as i32)
            };
            root.draw(&Text::new(
                name.to_string(),
                (v as i32 * PANEL as i32 + 8, TOP as i32 + PANEL as i32 - 20),
                font(13),
            ))?;
            let shadow = |s: &Polyhedron| -> Vec<(i32, i32)> {
                let pts: Vec<DVec2> = s.vertices().iter().map(|p| project(*p)).collect();
                hull2(pts)
                    .into_iter()
                    .map(|q| {
                        let q = (q - c2) * scale;
                        ((x0 + q.x).round() as i32, (y0 - q.y).round() as i32)
                    })
                    .collect()
            };
            root.draw(&Polygon::new(shadow(self.rough), RGBColor(215, 215, 215)))?;
            let ridge = RIDGE_DEG.to_radians().cos();
            let facets = self.rough.facets();
            let every = facets.len() <= EDGES_DRAWN;
            for e in self.rough.edges().iter().filter(|e| {
                every || {
                    let [f, g] = e.facets.map(|k| facets[k].plane.normal);
                    f.dot(g) < ridge
                }
            }) {
                let (a, b) = (self.rough.vertices()[e.a], self.rough.vertices()[e.b]);
                root.draw(&PathElement::new(
                    vec![px(a), px(b)],
                    RGBColor(150, 150, 150),
                ))?;
            }
            for (k, (cut, _)) in self.cuts.iter().enumerate() {
                let colour = SERIES[k % SERIES.len()];
                root.draw(&Polygon::new(shadow(cut), colour.mix(0.18)))?;
                for e in cut.edges() {
                    let (a, b) = (cut.vertices()[e.a], cut.vertices()[e.b]);
                    root.draw(&PathElement::new(
                        vec![px(a), px(b)],
                        colour.stroke_width(1),
                    ))?;
                }
            }
        }
        Ok(())
    }
}
