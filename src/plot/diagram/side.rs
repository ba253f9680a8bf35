//! The side view's annotations: the girdle plane, dimension lines for the crown height,
//! pavilion depth, total depth and table width, and the crown and pavilion angles.

use super::svg::{dimension, label, line, pct, View, DIM};
use crate::geometry::{DVec2, DVec3, Polyhedron};
use std::fmt::Write as _;

pub(super) fn side_annotations(
    out: &mut String,
    solid: &Polyhedron,
    props: &crate::cut::Proportions,
    side: View,
    lo: DVec3,
    hi: DVec3,
) {
    let z_bot = lo.z;
    let g_bot = z_bot + props.pavilion_depth;
    let g_top = g_bot + props.girdle;
    let z_table = g_top + props.crown_height;
    let px = |x: f64, z: f64| side.px(DVec2::new(x, z));
    let thin = r##"stroke="#8aa4c8" stroke-width="0.6" stroke-dasharray="3,3""##;
    // Girdle plane across the stone.
    let gz = 0.5 * (g_top + g_bot);
    line(out, px(lo.x - 0.06, gz), px(hi.x + 0.06, gz), thin);
    // Right: crown height and pavilion depth. Left: total depth.
    let xr = px(hi.x, 0.0).x + 28.0;
    let xl = px(lo.x, 0.0).x - 110.0;
    for z in [z_table, g_top, g_bot, z_bot] {
        line(
            out,
            DVec2::new(px(hi.x, 0.0).x + 4.0, px(0.0, z).y),
            DVec2::new(xr + 6.0, px(0.0, z).y),
            thin,
        );
    }
    for z in [hi.z, lo.z] {
        line(
            out,
            DVec2::new(xl - 6.0, px(0.0, z).y),
            DVec2::new(px(lo.x, 0.0).x - 4.0, px(0.0, z).y),
            thin,
        );
    }
    // A vertical dimension at x = xr between heights a and b, labelled to its right.
    let side_dimension = |out: &mut String, a: f64, b: f64, text: String| {
        dimension(
            out,
            DVec2::new(xr, px(0.0, a).y),
            DVec2::new(xr, px(0.0, b).y),
        );
        let y = px(0.0, 0.5 * (a + b)).y + 4.0;
        label(out, DVec2::new(xr + 8.0, y), 12.0, "start", &text);
    };
    if props.crown_height > 1e-9 {
        side_dimension(
            out,
            g_top,
            z_table,
            format!("crown height {}", pct(props.crown_height)),
        );
    }
    if props.pavilion_depth > 1e-9 {
        side_dimension(
            out,
            g_bot,
            z_bot,
            format!("pavilion depth {}", pct(props.pavilion_depth)),
        );
    }
    dimension(
        out,
        DVec2::new(xl, px(0.0, hi.z).y),
        DVec2::new(xl, px(0.0, lo.z).y),
    );
    let y = px(0.0, 0.5 * (hi.z + lo.z)).y;
    label(
        out,
        DVec2::new(xl - 8.0, y - 3.0),
        12.0,
        "end",
        "total depth",
    );
    label(
        out,
        DVec2::new(xl - 8.0, y + 13.0),
        12.0,
        "end",
        &pct(props.total_depth),
    );
    // Table width above the stone, from the table facet's extent in x.
    if let Some(ti) = solid
        .facets()
        .iter()
        .enumerate()
        .filter(|(_, f)| f.plane.normal.z > 1.0 - 1e-9)
        .max_by(|a, b| a.1.plane.offset.total_cmp(&b.1.plane.offset))
        .map(|(i, _)| i)
    {
        let xs: Vec<f64> = solid.facet_polygon(ti).iter().map(|p| p.x).collect();
        let (x0, x1) = (
            xs.iter().copied().fold(f64::INFINITY, f64::min),
            xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        );
        let y = px(0.0, hi.z).y - 18.0;
        for x in [x0, x1] {
            line(
                out,
                DVec2::new(px(x, 0.0).x, y - 5.0),
                DVec2::new(px(x, 0.0).x, px(0.0, hi.z).y - 3.0),
                thin,
            );
        }
        dimension(
            out,
            DVec2::new(px(x0, 0.0).x, y),
            DVec2::new(px(x1, 0.0).x, y),
        );
        label(
            out,
            DVec2::new(px(0.5 * (x0 + x1), 0.0).x, y - 5.0),
            12.0,
            "middle",
            &format!("table {}", pct(props.table)),
        );
    }
    // Crown and pavilion angles at the left girdle corner.
    let corner_top = px(lo.x, g_top);
    let corner_bot = px(lo.x, g_bot);
    let arc = |out: &mut String, c: DVec2, deg: f64, up: bool, name: &str| {
        if !(deg > 0.5 && deg < 89.5) {
            return;
        }
        let r = 40.0;
        let a = deg.to_radians();
        let sign = if up { -1.0 } else { 1.0 };
        let end = c + DVec2::new(r * a.cos(), sign * r * a.sin());
        let sweep = if up { 0 } else { 1 };
        line(
            out,
            c,
            c + DVec2::new(r + 8.0, 0.0),
            &format!(r#"stroke="{DIM}" stroke-width="1""#),
        );
        let _ = writeln!(
            out,
            r#"<path d="M{:.2},{:.2} A{r},{r} 0 0 {sweep} {:.2},{:.2}" fill="none" stroke="{DIM}" stroke-width="1.3"/>"#,
            c.x + r,
            c.y,
            end.x,
            end.y
        );
        // The value outside the stone, left of the corner, above or below the girdle.
        let at = c + DVec2::new(-8.0, if up { -8.0 } else { 17.0 });
        let _ = writeln!(
            out,
            r##"<text x="{:.1}" y="{:.1}" font-size="11.5" text-anchor="end" fill="{DIM}" stroke="#fff" stroke-width="3" stroke-linejoin="round" paint-order="stroke">{name} {deg:.2}°</text>"##,
            at.x, at.y
        );
    };
    arc(out, corner_top, props.crown_angle, true, "crown");
    arc(out, corner_bot, props.pavilion_angle, false, "pavilion");
}
