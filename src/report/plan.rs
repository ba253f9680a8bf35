//! A rough plan's `report.html` (`facetlab plan`): the rough, a table of every plan, each
//! family's best plan seen in the rough (the three views the binary drew, handed in as PNG
//! bytes), and those best cuts' pictures, proportions and scores as in a cut report.

use super::{base64, escape, html, measure, ReportOptions};
use crate::error::Result;
use crate::metrics::ScoreConfig;
use crate::plan::run::LayoutShown;
use crate::plan::{Drawings, PlacedPlan, Plan, Rough};
use crate::plot::plan::{LayoutPicture, Overview, Placed, ThreeViews};
use std::fmt::Write;
use std::path::Path;

/// The pictures and page of a plan's run folder ([`crate::plan::write_folder`]): the three
/// views and the overview of [`crate::plot::plan`], the page of [`plan_page`].
pub struct PlanDrawings;

fn placed<'a>(p: &PlacedPlan<'a>) -> Placed<'a> {
    Placed {
        solid: p.solid,
        label: p.label.to_string(),
        frame: p.frame,
    }
}

impl Drawings for PlanDrawings {
    fn views(
        &self,
        rough: &Rough,
        stem: &str,
        plan: &PlacedPlan<'_>,
        png: &Path,
        svg: &Path,
    ) -> Result<()> {
        let views = ThreeViews {
            rough: &rough.solid,
            cut: placed(plan),
            title: format!("{} in {}", stem, rough.name),
        };
        crate::plot::save_to(&views, png, svg)
    }

    fn overview(
        &self,
        rough: &Rough,
        best: &[PlacedPlan<'_>],
        png: &Path,
        svg: &Path,
    ) -> Result<()> {
        let overview = Overview {
            rough: &rough.solid,
            cuts: best.iter().map(placed).collect(),
            title: format!("best plan of each family in {}", rough.name),
        };
        crate::plot::save_to(&overview, png, svg)
    }

    fn layout(&self, rough: &Rough, shown: &LayoutShown<'_>, png: &Path, svg: &Path) -> Result<()> {
        let picture = LayoutPicture {
            rough: &rough.solid,
            stones: shown
                .stones
                .iter()
                .map(|p| (p.solid, p.label.to_string()))
                .collect(),
            saw: shown.saw.clone(),
            inclusions: shown.inclusions.clone(),
            title: format!(
                "{} stone{} in {}",
                shown.stones.len(),
                if shown.stones.len() == 1 { "" } else { "s" },
                rough.name
            ),
        };
        crate::plot::save_to(&picture, png, svg)
    }

    fn page(
        &self,
        rough: &Rough,
        all: &[(String, Vec<Plan>)],
        views: &[Vec<u8>],
        score: &ScoreConfig,
    ) -> Result<String> {
        plan_page(rough, all, views, score)
    }
}

/// The page: `plans` per family (best first), `views` the PNG of each family's best plan in
/// the rough (same order), `score` the settings the cuts are scored with.
pub fn plan_page(
    rough: &Rough,
    plans: &[(String, Vec<Plan>)],
    views: &[Vec<u8>],
    score: &ScoreConfig,
) -> Result<String> {
    let mut o = ReportOptions {
        score: score.clone(),
        size: 200,
        title: format!("facetlab plan: {}", rough.name),
        ..Default::default()
    };
    let mut about = format!(
        "<p>Convex hull {:.3} mm³, {} planes, {:.3} mm across",
        rough.volume(),
        rough.solid.facets().len(),
        rough.size()
    );
    if let Some(v) = rough.mesh_volume {
        let _ = write!(
            about,
            "; the mesh itself {v:.3} mm³ (the hull adds {:.2} %)",
            100.0 * rough.hull_excess()
        );
    }
    about.push_str(".</p>");
    o.sections.push(("Rough".into(), about));
    let mut table = String::from(
        "<table><tr><th>plan</th><th>carats</th><th>yield</th><th>width W (mm)</th><th>grade</th><th>objective</th></tr>\n",
    );
    for (fam, list) in plans {
        for (k, p) in list.iter().enumerate() {
            let _ = writeln!(
                table,
                "<tr><td>{}-{}</td><td>{:.4}</td><td>{:.2} %</td><td>{:.3}</td><td>{}</td><td>{:.4}</td></tr>",
                escape(fam),
                k + 1,
                p.carats,
                100.0 * p.yield_fraction,
                p.scale,
                p.grade.map_or("—", |g| g.name()),
                p.objective
            );
        }
    }
    table.push_str("</table>");
    o.sections.push(("Plans".into(), table));
    let mut pictures = String::new();
    for ((fam, _), png) in plans.iter().zip(views) {
        let _ = writeln!(
            pictures,
            "<p><img alt=\"{0}-1 in the rough\" style=\"max-width:100%\" src=\"data:image/png;base64,{1}\"></p>",
            escape(fam),
            base64(png)
        );
    }
    o.sections
        .push(("Each family's best plan in the rough".into(), pictures));
    let mut cuts = Vec::new();
    for (fam, list) in plans {
        if let Some(p) = list.first() {
            cuts.push(measure(&format!("{fam}-1"), &p.cut, &o)?);
        }
    }
    html(&cuts, &o)
}
