//! The diagram's views of the stone: the facets facing the viewer, tinted by tier, with the
//! outline drawn heavier and one label per tier.

use super::svg::{esc, label, points_attr, View, INK};
use crate::geometry::{DVec2, DVec3, Polyhedron};
use std::fmt::Write as _;

/// Light tints for tiers, in order of appearance (the girdle gets grey).
const TINTS: &[&str] = &[
    "#fbe3a6", "#cfe6fa", "#d6f2cf", "#f8d2df", "#e2dafa", "#fbdcc0", "#cdeeed", "#eeeec4",
    "#e6d3c4", "#dfe6f2",
];

pub(super) fn tint(tiers: &[String], tier: &str) -> &'static str {
    if tier == "girdle" {
        return "#e4e4e4";
    }
    let i = tiers
        .iter()
        .filter(|t| t.as_str() != "girdle")
        .position(|t| t == tier)
        .unwrap_or(0);
    TINTS[i % TINTS.len()]
}

/// Draw the facets selected by `facing` projected by `proj` and their outline in a view, and
/// with `labels` one label per tier.
pub(super) fn facet_view(
    out: &mut String,
    solid: &Polyhedron,
    tiers: &[String],
    view: View,
    facing: impl Fn(DVec3) -> bool,
    proj: impl Fn(DVec3) -> DVec2,
    labels: bool,
) {
    let mut shown: Vec<usize> = Vec::new();
    for (i, f) in solid.facets().iter().enumerate() {
        if !facing(f.plane.normal) {
            continue;
        }
        shown.push(i);
        let pts: Vec<DVec2> = solid
            .facet_polygon(i)
            .into_iter()
            .map(|p| view.px(proj(p)))
            .collect();
        let _ = writeln!(
            out,
            r#"<polygon points="{}" fill="{}" stroke="{INK}" stroke-width="0.7" stroke-linejoin="round"><title>{} ({})</title></polygon>"#,
            points_attr(&pts),
            tint(tiers, &f.tier),
            esc(&f.name),
            esc(&f.tier)
        );
    }
    let outline = crate::geometry::clip2d::convex_hull(
        solid.vertices().iter().map(|p| view.px(proj(*p))).collect(),
    );
    let _ = writeln!(
        out,
        r#"<polygon points="{}" fill="none" stroke="{INK}" stroke-width="1.8" stroke-linejoin="round"/>"#,
        points_attr(&outline)
    );
    if !labels {
        return;
    }
    // One label per tier, spread around the view: the facet nearest a target direction.
    let mut k = 0;
    for tier in tiers {
        let members: Vec<usize> = shown
            .iter()
            .copied()
            .filter(|&i| &solid.facets()[i].tier == tier)
            .collect();
        if members.is_empty() {
            continue;
        }
        let centre = |i: usize| view.px(proj(solid.facets()[i].centroid));
        let at = if members.len() == 1 {
            centre(members[0])
        } else {
            let target = (100.0 + 67.0 * k as f64).to_radians();
            let dir = DVec2::new(target.cos(), -target.sin());
            k += 1;
            let best = members
                .iter()
                .copied()
                .max_by(|&a, &b| {
                    let score = |i: usize| {
                        let d = centre(i) - view.centre;
                        d.normalize_or_zero().dot(dir)
                    };
                    score(a).total_cmp(&score(b))
                })
                .unwrap_or(members[0]);
            centre(best)
        };
        label(out, at + DVec2::new(0.0, 3.5), 10.5, "middle", tier);
    }
}
