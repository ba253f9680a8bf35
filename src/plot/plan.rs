//! Pictures of a plan, each cut seen in its own frame with its table up (the rough turned with
//! it): [`ThreeViews`] shows one plan from the top, the front and the side; [`Overview`] the
//! best plan of each family from the front, one panel each, captioned under it. Orthographic;
//! the rough is its grey silhouette, the cut its facets that face the viewer, each shaded by
//! its slope to a light above the viewer's left shoulder (a convex solid's front facets never
//! overlap, so no sorting is needed) in the cut's series colour.

use super::{font, DrawResult, Figure, SERIES};
use crate::geometry::{DVec2, DVec3, Polyhedron};
use glam::DQuat;
use plotters::coord::Shift;
use plotters::prelude::*;

/// A planned cut placed in the rough (mm, the rough's coordinates), with its label and the
/// turn from the rough's frame to its own (its table along +z: the inverse of the plan's
/// rotation).
pub struct Placed<'a> {
    /// The placed cut.
    pub solid: &'a Polyhedron,
    /// Its caption (`round-brilliant-1: 0.529 ct, yield 52.4 %`).
    pub label: String,
    /// Rough's frame → the cut's frame.
    pub frame: DQuat,
}

/// One plan's three views, in the cut's frame.
pub struct ThreeViews<'a> {
    /// The rough (mm).
    pub rough: &'a Polyhedron,
    /// The plan.
    pub cut: Placed<'a>,
    /// Caption above the views.
    pub title: String,
}

/// The best plan of each family, one front view each, in the cut's own frame.
pub struct Overview<'a> {
    /// The rough (mm).
    pub rough: &'a Polyhedron,
    /// The plans, one panel each, in order.
    pub cuts: Vec<Placed<'a>>,
    /// Caption above the panels.
    pub title: String,
}

/// A view: its caption, the camera's right and up axes, and the direction toward the viewer
/// (all in the cut's frame).
struct View {
    name: &'static str,
    right: DVec3,
    up: DVec3,
    toward: DVec3,
}

const TOP_VIEW: View = View {
    name: "top: table up, seen from above",
    right: DVec3::X,
    up: DVec3::Y,
    toward: DVec3::Z,
};
const FRONT_VIEW: View = View {
    name: "front: table up",
    right: DVec3::X,
    up: DVec3::Z,
    toward: DVec3::NEG_Y,
};
const SIDE_VIEW: View = View {
    name: "side: table up",
    right: DVec3::Y,
    up: DVec3::Z,
    toward: DVec3::X,
};

/// The brightness of a facet with outward normal `n` (cut frame) seen in `view`: ambient 0.45
/// and the rest by its slope to a light above the viewer's left shoulder.
fn shade(n: DVec3, view: &View) -> f64 {
    let light = (view.toward * 0.8 + view.up * 0.5 - view.right * 0.3).normalize();
    0.45 + 0.55 * n.dot(light).max(0.0)
}

/// Draw `view` of `rough` and `cut` (its frame turning the rough's points, about `centre`)
/// into the square of side `side` at `(x0, y0)`.
fn draw_view<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    (x0, y0, side): (f64, f64, f64),
    view: &View,
    rough: &Polyhedron,
    cut: &Placed,
    colour: RGBColor,
) -> DrawResult<DB> {
    let centre = {
        let (lo, hi) = rough.bounding_box();
        0.5 * (lo + hi)
    };
    let to_view = |p: DVec3| cut.frame * (p - centre);
    let flat = |q: DVec3| DVec2::new(q.dot(view.right), q.dot(view.up));
    // One scale for every view of the rough: its largest extent fills 86 % of the square.
    let extent = rough
        .vertices()
        .iter()
        .map(|p| (to_view(*p)).length())
        .fold(0.0, f64::max)
        .max(1e-9);
    let scale = 0.43 * side / extent;
    let (cx, cy) = (x0 + side / 2.0, y0 + side / 2.0);
    let px = |q: DVec2| -> (i32, i32) {
        (
            (cx + q.x * scale).round() as i32,
            (cy - q.y * scale).round() as i32,
        )
    };
    let outline: Vec<(i32, i32)> = crate::geometry::clip2d::convex_hull(
        rough.vertices().iter().map(|p| flat(to_view(*p))).collect(),
    )
    .into_iter()
    .map(px)
    .collect();
    root.draw(&Polygon::new(outline.clone(), RGBColor(222, 222, 222)))?;
    let mut closed = outline;
    if let Some(&first) = closed.first() {
        closed.push(first);
    }
    root.draw(&PathElement::new(closed, RGBColor(150, 150, 150)))?;
    for (i, f) in cut.solid.facets().iter().enumerate() {
        let n = cut.frame * f.plane.normal;
        if n.dot(view.toward) <= 1e-9 {
            continue;
        }
        let pts: Vec<(i32, i32)> = cut
            .solid
            .facet_polygon(i)
            .iter()
            .map(|p| px(flat(to_view(*p))))
            .collect();
        let s = shade(n, view);
        let fill = RGBColor(
            (f64::from(colour.0) * s).round().min(255.0) as u8,
            (f64::from(colour.1) * s).round().min(255.0) as u8,
            (f64::from(colour.2) * s).round().min(255.0) as u8,
        );
        root.draw(&Polygon::new(pts.clone(), fill))?;
        let mut ring = pts;
        if let Some(&first) = ring.first() {
            ring.push(first);
        }
        root.draw(&PathElement::new(ring, BLACK.mix(0.45)))?;
    }
    Ok(())
}

/// `text` cut to fit `width` pixels at `size` (an ellipsis ends a shortened one).
fn fitted(text: &str, size: u32, width: f64) -> String {
    let fits = |t: &str| f64::from(super::text::width(t, f64::from(size))) <= width;
    if fits(text) {
        return text.to_string();
    }
    let mut t: Vec<char> = text.chars().collect();
    while !t.is_empty() && !fits(&format!("{}…", t.iter().collect::<String>())) {
        t.pop();
    }
    format!("{}…", t.iter().collect::<String>())
}

const PANEL: u32 = 360;
const TOP: u32 = 56;

impl Figure for ThreeViews<'_> {
    fn size(&self) -> (u32, u32) {
        (3 * PANEL, PANEL + TOP)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let width = f64::from(3 * PANEL) - 20.0;
        root.draw(&Text::new(
            fitted(&self.title, 17, width),
            (10, 8),
            font(17),
        ))?;
        root.draw(&Text::new(
            fitted(&self.cut.label, 14, width),
            (10, 32),
            font(14).color(&SERIES[0]),
        ))?;
        for (v, view) in [TOP_VIEW, FRONT_VIEW, SIDE_VIEW].iter().enumerate() {
            let x0 = f64::from(v as u32 * PANEL);
            draw_view(
                root,
                (x0, f64::from(TOP), f64::from(PANEL)),
                view,
                self.rough,
                &self.cut,
                SERIES[0],
            )?;
            root.draw(&Text::new(
                view.name,
                (x0 as i32 + 8, (TOP + PANEL) as i32 - 18),
                font(13),
            ))?;
        }
        Ok(())
    }
}

/// Overview panels: side, the caption band under each, columns.
const CELL: u32 = 270;
const CAPTION: u32 = 44;
const COLUMNS: usize = 4;

/// The overview's subtitle.
const OVERVIEW_NOTE: &str = "each cut from the front, table up (the rough turned with it)";

impl Overview<'_> {
    fn grid(&self) -> (usize, usize) {
        let n = self.cuts.len().max(1);
        let cols = n.min(COLUMNS);
        (cols, n.div_ceil(cols))
    }

    /// The picture's width: the panels', or the title's and subtitle's when wider (one
    /// family's panel is narrower than its title), up to four panels (a longer title is cut).
    fn width(&self) -> u32 {
        let (cols, _) = self.grid();
        let text = |t: &str, size: u32| super::text::width(t, f64::from(size)).ceil() as u32 + 20;
        (cols as u32 * CELL)
            .max(text(&self.title, 17))
            .max(text(OVERVIEW_NOTE, 13))
            .min(COLUMNS as u32 * CELL)
    }
}

impl Figure for Overview<'_> {
    fn size(&self) -> (u32, u32) {
        let (_, rows) = self.grid();
        (self.width(), TOP + rows as u32 * (CELL + CAPTION))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let (cols, _) = self.grid();
        let width = self.width();
        root.draw(&Text::new(
            fitted(&self.title, 17, f64::from(width) - 20.0),
            (10, 8),
            font(17),
        ))?;
        // The panels centred under the title.
        let left = (width - cols as u32 * CELL) / 2;
        root.draw(&Text::new(
            fitted(OVERVIEW_NOTE, 13, f64::from(width) - 20.0),
            (10, 32),
            font(13).color(&RGBColor(90, 90, 90)),
        ))?;
        for (k, cut) in self.cuts.iter().enumerate() {
            let (c, r) = (k % cols, k / cols);
            let (x0, y0) = (left + c as u32 * CELL, TOP + r as u32 * (CELL + CAPTION));
            let colour = SERIES[k % SERIES.len()];
            draw_view(
                root,
                (f64::from(x0), f64::from(y0), f64::from(CELL)),
                &FRONT_VIEW,
                self.rough,
                cut,
                colour,
            )?;
            // The caption: the family's label on its own lines, inside the panel.
            let (name, rest) = cut.label.split_once(": ").unwrap_or((&cut.label, ""));
            let inner = f64::from(CELL) - 16.0;
            root.draw(&Text::new(
                fitted(name, 14, inner),
                (x0 as i32 + 8, (y0 + CELL) as i32 - 2),
                font(14).color(&colour),
            ))?;
            root.draw(&Text::new(
                fitted(rest, 13, inner),
                (x0 as i32 + 8, (y0 + CELL) as i32 + 18),
                font(13),
            ))?;
        }
        Ok(())
    }
}

/// A layout of several stones in one rough ([`crate::plan::Layout`]): the rough seen from
/// three sides in its own coordinates (down z, down −y, down x), see-through (its
/// silhouette light, its back edges drawn too), the saw planes as their sections through
/// the rough in blue, the inclusions in red and each stone's facets facing the viewer shaded
/// in its series colour (farther stones drawn first).
pub struct LayoutPicture<'a> {
    /// The rough (mm).
    pub rough: &'a Polyhedron,
    /// The stones, placed, with their captions.
    pub stones: Vec<(&'a Polyhedron, String)>,
    /// The saw planes, `(normal, offset, the piece it cuts)`, in cutting order.
    pub saw: Vec<(DVec3, f64, &'a Polyhedron)>,
    /// The inclusions' hulls (mm).
    pub inclusions: Vec<&'a Polyhedron>,
    /// Caption above the views.
    pub title: String,
}

/// The stones' colours: the series without its red (the inclusions' colour).
const STONE_COLOURS: [RGBColor; 7] = [
    SERIES[0], SERIES[2], SERIES[3], SERIES[4], SERIES[5], SERIES[6], SERIES[7],
];

const LAYOUT_VIEWS: [View; 3] = [
    View {
        name: "from above (down z)",
        right: DVec3::X,
        up: DVec3::Y,
        toward: DVec3::Z,
    },
    View {
        name: "from the front (along +y)",
        right: DVec3::X,
        up: DVec3::Z,
        toward: DVec3::NEG_Y,
    },
    View {
        name: "from the side (along −x)",
        right: DVec3::Y,
        up: DVec3::Z,
        toward: DVec3::X,
    },
];

/// The section of a convex solid by the plane `n·x = d`: its corners (unordered).
fn section(solid: &Polyhedron, n: DVec3, d: f64) -> Vec<DVec3> {
    let v = solid.vertices();
    solid
        .edges()
        .iter()
        .filter_map(|e| {
            let (p, q) = (v[e.a], v[e.b]);
            let (dp, dq) = (n.dot(p) - d, n.dot(q) - d);
            ((dp <= 0.0) != (dq <= 0.0)).then(|| p + (dp / (dp - dq)) * (q - p))
        })
        .collect()
}

impl LayoutPicture<'_> {
    fn lines(&self) -> u32 {
        self.stones.len().div_ceil(3) as u32
    }

    fn draw_panel<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        (x0, y0, side): (f64, f64, f64),
        view: &View,
    ) -> DrawResult<DB> {
        let (lo, hi) = self.rough.bounding_box();
        let centre = 0.5 * (lo + hi);
        let flat = |p: DVec3| DVec2::new((p - centre).dot(view.right), (p - centre).dot(view.up));
        let extent = self
            .rough
            .vertices()
            .iter()
            .map(|p| flat(*p).length())
            .fold(0.0, f64::max)
            .max(1e-9);
        let scale = 0.46 * side / extent;
        let (cx, cy) = (x0 + side / 2.0, y0 + side / 2.0);
        let px = |q: DVec2| -> (i32, i32) {
            (
                (cx + q.x * scale).round() as i32,
                (cy - q.y * scale).round() as i32,
            )
        };
        let hull_of = |pts: &[DVec3]| -> Vec<(i32, i32)> {
            crate::geometry::clip2d::convex_hull(pts.iter().map(|p| flat(*p)).collect())
                .into_iter()
                .map(px)
                .collect()
        };
        let ring = |mut pts: Vec<(i32, i32)>| {
            if let Some(&f) = pts.first() {
                pts.push(f);
            }
            pts
        };
        // The rough, see-through: its silhouette and every edge.
        let outline = hull_of(self.rough.vertices());
        root.draw(&Polygon::new(outline.clone(), RGBColor(232, 238, 245)))?;
        let v = self.rough.vertices();
        for e in self.rough.edges() {
            root.draw(&PathElement::new(
                vec![px(flat(v[e.a])), px(flat(v[e.b]))],
                RGBColor(170, 180, 195).mix(0.6),
            ))?;
        }
        root.draw(&PathElement::new(ring(outline), RGBColor(120, 130, 150)))?;
        // The stones, farther first.
        let mut order: Vec<usize> = (0..self.stones.len()).collect();
        let depth = |k: usize| self.stones[k].0.centroid().dot(view.toward);
        order.sort_by(|a, b| depth(*a).total_cmp(&depth(*b)));
        for k in order {
            let (solid, _) = &self.stones[k];
            let colour = STONE_COLOURS[k % STONE_COLOURS.len()];
            for (i, f) in solid.facets().iter().enumerate() {
                let n = f.plane.normal;
                if n.dot(view.toward) <= 1e-9 {
                    continue;
                }
                let pts: Vec<(i32, i32)> = solid
                    .facet_polygon(i)
                    .iter()
                    .map(|p| px(flat(*p)))
                    .collect();
                let s = shade(n, view);
                let fill = RGBColor(
                    (f64::from(colour.0) * s).round().min(255.0) as u8,
                    (f64::from(colour.1) * s).round().min(255.0) as u8,
                    (f64::from(colour.2) * s).round().min(255.0) as u8,
                );
                root.draw(&Polygon::new(pts.clone(), fill))?;
                root.draw(&PathElement::new(ring(pts), BLACK.mix(0.4)))?;
            }
        }
        // The saw planes' sections and the inclusions on top, so that they always show.
        for (n, d, piece) in &self.saw {
            let cut = section(piece, *n, *d);
            if cut.len() >= 3 {
                let pts = hull_of(&cut);
                root.draw(&Polygon::new(pts.clone(), RGBColor(40, 90, 220).mix(0.12)))?;
                root.draw(&PathElement::new(
                    ring(pts),
                    ShapeStyle::from(&RGBColor(40, 90, 220)).stroke_width(2),
                ))?;
            }
        }
        for inc in &self.inclusions {
            let pts = hull_of(inc.vertices());
            root.draw(&Polygon::new(pts.clone(), RGBColor(220, 30, 30)))?;
            root.draw(&PathElement::new(ring(pts), RGBColor(120, 0, 0)))?;
        }
        Ok(())
    }
}

impl Figure for LayoutPicture<'_> {
    fn size(&self) -> (u32, u32) {
        (3 * PANEL, TOP + PANEL + 20 * self.lines() + 10)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let width = f64::from(3 * PANEL) - 20.0;
        root.draw(&Text::new(
            fitted(&self.title, 17, width),
            (10, 8),
            font(17),
        ))?;
        root.draw(&Text::new(
            fitted(
                "the rough see-through, saw planes blue, inclusions red, each stone in its colour",
                13,
                width,
            ),
            (10, 32),
            font(13).color(&RGBColor(90, 90, 90)),
        ))?;
        for (v, view) in LAYOUT_VIEWS.iter().enumerate() {
            let x0 = f64::from(v as u32 * PANEL);
            self.draw_panel(root, (x0, f64::from(TOP), f64::from(PANEL)), view)?;
            root.draw(&Text::new(
                view.name,
                (x0 as i32 + 8, (TOP + PANEL) as i32 - 18),
                font(13),
            ))?;
        }
        for (k, (_, label)) in self.stones.iter().enumerate() {
            let (c, r) = (k % 3, k / 3);
            root.draw(&Text::new(
                fitted(label, 13, f64::from(PANEL) - 16.0),
                (
                    (c as u32 * PANEL) as i32 + 8,
                    (TOP + PANEL + 4 + 20 * r as u32) as i32,
                ),
                font(13).color(&STONE_COLOURS[k % STONE_COLOURS.len()]),
            ))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cut::Cut;

    /// A round brilliant placed table-down and turned inside a box rough, drawn table up: in
    /// the front view its table (the cut's top) is at the top of the panel, shaded lighter
    /// than its pavilion; the overview's captions all fit their panels.
    #[test]
    fn plans_are_drawn_table_up_shaded_with_every_label() {
        let cut = Cut::from_family("r", "round-brilliant", &Default::default()).unwrap();
        let turn = DQuat::from_rotation_x(std::f64::consts::PI) * DQuat::from_rotation_z(0.3);
        // The cut turned by `turn` and scaled by `k`, from its facet planes.
        let moved = |k: f64| {
            let planes: Vec<_> = cut
                .solid
                .facet_planes()
                .into_iter()
                .map(|mut f| {
                    f.plane.normal = turn * f.plane.normal;
                    f.plane.offset *= k;
                    f
                })
                .collect();
            Polyhedron::from_planes(&planes).unwrap()
        };
        let (placed, rough) = (moved(4.0), moved(6.0));
        let p = Placed {
            solid: &placed,
            label: "round-brilliant-1: 0.5 ct, yield 30 %".into(),
            frame: turn.inverse(),
        };
        // The table's outward normal in the cut's frame is +z.
        let table = placed.facets().iter().find(|f| f.tier == "table").unwrap();
        assert!((p.frame * table.plane.normal - DVec3::Z).length() < 1e-9);
        let (w, h) = (CELL, CELL);
        let mut buf = vec![255u8; (w * h * 3) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
            draw_view(
                &root,
                (0.0, 0.0, f64::from(CELL)),
                &FRONT_VIEW,
                &rough,
                &p,
                SERIES[0],
            )
            .unwrap();
            root.present().unwrap();
        }
        // Rows holding the cut's colour (not grey, not white): the table row (top of the cut)
        // is above the culet (its bottom), and the crown's pixels are lighter than the
        // pavilion's (lit from above).
        let coloured = |x: u32, y: u32| {
            let i = ((y * w + x) * 3) as usize;
            let (r, g, b) = (buf[i] as i32, buf[i + 1] as i32, buf[i + 2] as i32);
            ((r - g).abs() + (g - b).abs() > 40).then_some(r + g + b)
        };
        let rows: Vec<(u32, i32)> = (0..h)
            .filter_map(|y| {
                let v: Vec<i32> = (0..w).filter_map(|x| coloured(x, y)).collect();
                (!v.is_empty()).then(|| (y, v.iter().sum::<i32>() / v.len() as i32))
            })
            .collect();
        let (top, bottom) = (rows[0].0, rows[rows.len() - 1].0);
        // The crown is the upper third of the cut's height; the pavilion the rest.
        let split = top + (bottom - top) / 3;
        let mean = |f: &dyn Fn(u32) -> bool| {
            let v: Vec<i32> = rows.iter().filter(|r| f(r.0)).map(|r| r.1).collect();
            v.iter().sum::<i32>() as f64 / v.len() as f64
        };
        let (crown, pavilion) = (mean(&|y| y < split), mean(&|y| y > split + 4));
        assert!(crown > pavilion, "crown {crown} pavilion {pavilion}");
        // The pavilion is the longer part: the widest row is nearer the top (the girdle).
        let widest = (0..h)
            .max_by_key(|&y| (0..w).filter(|&x| coloured(x, y).is_some()).count())
            .unwrap();
        assert!(
            widest < split + (bottom - top) / 6,
            "girdle row {widest} of {top}..{bottom}"
        );
        // Seven families' captions in an overview: each fits its panel.
        let labels: Vec<String> = (0..7)
            .map(|k| format!("family-with-a-long-name-{k}-1: 0.571 ct, yield 56.6 %, W 5.078 mm"))
            .collect();
        let o = Overview {
            rough: &rough,
            cuts: labels
                .iter()
                .map(|l| Placed {
                    solid: &placed,
                    label: l.clone(),
                    frame: turn.inverse(),
                })
                .collect(),
            title: "t".into(),
        };
        assert_eq!(o.size(), (4 * CELL, TOP + 2 * (CELL + CAPTION)));
        for l in &labels {
            let (name, rest) = l.split_once(": ").unwrap();
            for (t, size) in [(name, 14), (rest, 13)] {
                let shown = fitted(t, size, f64::from(CELL) - 16.0);
                assert!(
                    f64::from(crate::plot::text::width(&shown, f64::from(size)))
                        <= f64::from(CELL) - 16.0
                );
            }
        }
    }
}
