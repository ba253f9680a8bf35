//! The info document, as `facetlab info --json` prints it ([`InfoJson`], keys in docs/commands.md):
//! a cut's proportions, tiers, ratios, size and weight for a width and a material, its
//! geometric checks and grade estimate, and on request its cutting instructions and meets
//! ([`meets_json`]); and the same as the text `facetlab info` prints ([`info_text`],
//! [`meets_text`]).

use crate::cut::Cut;
use crate::error::{setting, Result};
use crate::optics::Material;
use serde::Serialize;
use std::collections::BTreeMap;

/// JSON of `info` (keys documented in docs/commands.md).
#[derive(Debug, Serialize)]
pub struct InfoJson {
    /// Cut name.
    pub name: String,
    /// Family, if generated from one.
    pub family: Option<String>,
    /// Family parameters.
    pub params: BTreeMap<String, f64>,
    /// Number of facets, girdle facets included.
    pub facet_count: usize,
    /// Number of vertices.
    pub vertex_count: usize,
    /// Volume in widths W cubed (girdle diameters for a round).
    pub volume: f64,
    /// Measured proportions.
    pub proportions: crate::cut::Proportions,
    /// Tiers: name, mean angle, count, side.
    pub tiers: Vec<crate::cut::TierSummary>,
    /// Girdle width W used for the weight, mm (a round's diameter).
    pub diameter_mm: f64,
    /// The stone's length, width and depth in mm for that width.
    pub size_mm: SizeMm,
    /// GemCad's ratios over the width: `l_w`, `t_w`, `p_w`, `c_w`, `h_w`, `vol_w3`.
    pub ratios: crate::cut::Ratios,
    /// Material used for the weight.
    pub material: String,
    /// Weight in carats for that diameter and material.
    pub carats: f64,
    /// Geometric checks: closed surface (V − E + F = 2).
    pub checks: Checks,
    /// Proportion grade estimate (round brilliants of the `round-brilliant` family only):
    /// `estimate` (`excellent` … `poor`), `limiting` (the parameters that set it),
    /// `parameters` (each with its value, grade and that grade's range), `note`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grade: Option<crate::cut::grade::GradeEstimate>,
    /// Cutting instructions (with `--instructions`): `gear`, `gear_offset`, `ri`, and
    /// `steps[]` with `step`, `side`, `tier`, `angle`, `indices`, `note`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub instructions: Option<crate::io::asc::CuttingInstructions>,
    /// The design's meets (with `--meets`): `tiers`, `facets`, `point` [x, y, z] in W, `off`
    /// (how far the farthest of its planes passes from the point, in W).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub meets: Option<Vec<MeetJson>>,
    /// What a GemCad design file says about itself: `ri`, `title`, `footnotes`, `gear`,
    /// `gear_offset`, `symmetry`, `mirror`, `instructions` (by facet name), `scale` (file
    /// units per girdle width); absent for generated cuts.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub design: Option<crate::cut::GemcadRecord>,
}

/// A stone's size in millimetres.
#[derive(Debug, Serialize)]
pub struct SizeMm {
    /// Length (the outline's larger extent along x and y).
    pub length: f64,
    /// Width (its smaller extent).
    pub width: f64,
    /// Depth (top to bottom).
    pub depth: f64,
}

/// Geometric checks reported by `info`.
#[derive(Debug, Serialize)]
pub struct Checks {
    /// V − E + F.
    pub euler_characteristic: i64,
    /// Every edge separates exactly two facets and V − E + F = 2.
    pub closed: bool,
    /// Smallest facet area over the mean facet area.
    pub smallest_facet_ratio: f64,
}

/// The `info` document of `cut` for a girdle width W of `diameter_mm` millimetres in
/// `material` (the weight), without instructions or meets (set them with
/// [`crate::io::asc::cutting_instructions`] and [`meets_json`]).
pub fn info_json(cut: &Cut, diameter_mm: f64, material: &Material) -> InfoJson {
    let s = &cut.solid;
    let volume = s.volume();
    let ratios = cut.ratios();
    // Lengths are per width W (the unit convention); W is `diameter_mm` millimetres.
    let w = crate::cut::units::outline_size(s.vertices()).1.max(1e-300);
    let mm3 = volume / (w * w * w) * diameter_mm.powi(3);
    let carats = mm3 * 1e-3 * material.density / 0.2;
    let euler = s.vertices().len() as i64 - s.edges().len() as i64 + s.facets().len() as i64;
    let mean = s.surface_area() / s.facets().len() as f64;
    let smallest = s
        .facets()
        .iter()
        .map(|f| f.area)
        .fold(f64::INFINITY, f64::min);
    InfoJson {
        name: cut.name.clone(),
        family: cut.family.clone(),
        params: cut.params.clone(),
        facet_count: s.facets().len(),
        vertex_count: s.vertices().len(),
        volume,
        proportions: cut.proportions(),
        tiers: cut.tiers(),
        diameter_mm,
        size_mm: SizeMm {
            length: ratios.l_w * diameter_mm,
            width: diameter_mm,
            depth: ratios.h_w * diameter_mm,
        },
        ratios,
        material: material.name.clone(),
        carats,
        checks: Checks {
            euler_characteristic: euler,
            closed: euler == 2,
            smallest_facet_ratio: smallest / mean,
        },
        grade: crate::cut::grade::estimate(cut),
        design: cut.record.clone(),
        instructions: None,
        meets: None,
    }
}

/// One meet of `info --meets`.
#[derive(Debug, Serialize)]
pub struct MeetJson {
    /// The tiers it joins (GemCad line names), each once.
    pub tiers: Vec<String>,
    /// The facets through it.
    pub facets: Vec<String>,
    /// The point, in W.
    pub point: [f64; 3],
    /// How far the farthest of its planes passes from the point, in W.
    pub off: f64,
}

/// The meets of `cut`'s design: points where four or more facets pass within `tol` widths
/// W of one point (`info --meets`).
pub fn meets_json(cut: &Cut, tol: f64) -> Result<Vec<MeetJson>> {
    let model = crate::design::TierModel::of_cut(cut, tol)?;
    Ok(model
        .meets
        .iter()
        .map(|m| MeetJson {
            tiers: model.meet_tiers(m).iter().map(|t| t.to_string()).collect(),
            facets: m
                .facets
                .iter()
                .map(|&f| cut.solid.facets()[f].name.clone())
                .collect(),
            point: m.point.to_array(),
            off: m.gap,
        })
        .collect())
}

/// The meets as `facetlab info --meets` prints them, found with tolerance `tol`.
pub fn meets_text(meets: &[MeetJson], tol: f64) -> String {
    use std::fmt::Write;
    let worst = meets.iter().map(|m| m.off).fold(0.0, f64::max);
    let mut o = format!(
        "Meets ({} where four or more facets pass within {tol:e} W of one point; farthest plane {worst:.1e} W)\n",
        meets.len()
    );
    let _ = writeln!(
        o,
        "  {:<36} {:>8} {:>8} {:>8}  {:>8}",
        "tiers (facets)", "x", "y", "z", "off"
    );
    for m in meets {
        let tiers = format!("{} ({})", m.tiers.join(" "), m.facets.len());
        let [x, y, z] = m.point;
        let _ = writeln!(
            o,
            "  {tiers:<36} {x:>8.4} {y:>8.4} {z:>8.4}  {:>8.1e}",
            m.off
        );
    }
    o
}

/// The setting that sets a cut's parameter or turns a design's tier (`KEY=VALUE`), named in
/// [`info_text`] for each face to spell ([`crate::error::setting`]).
pub use crate::design::CUT_PARAMETER;

/// Human-readable `info`; the setting of a parameter is named as [`CUT_PARAMETER`], for the
/// face that prints it to spell ([`crate::error::spell_settings`]).
pub fn info_text(j: &InfoJson) -> String {
    use std::fmt::Write;
    let mut o = String::new();
    let fam = j
        .family
        .as_deref()
        .map(|f| format!(" ({f})"))
        .unwrap_or_default();
    let _ = writeln!(o, "{}{fam}", j.name);
    if let Some(d) = &j.design {
        for t in d.title.iter().filter(|t| !t.trim().is_empty()) {
            let _ = writeln!(o, "  {}", t.trim());
        }
        let ri = d.ri.map(|n| format!(", index {n}")).unwrap_or_default();
        let _ = writeln!(
            o,
            "  GemCad design: gear {} (offset {}), {}-fold symmetry{}{ri}",
            d.gear,
            d.gear_offset,
            d.symmetry,
            if d.mirror { " with mirror" } else { "" }
        );
        for f in &d.footnotes {
            let _ = writeln!(o, "  note: {f}");
        }
    }
    let p = &j.proportions;
    let pct = |v: f64| format!("{:6.1} %", v * 100.0);
    let _ = writeln!(o, "\nProportions (lengths as % of the width W)");
    let _ = writeln!(o, "  table            {}", pct(p.table));
    let _ = writeln!(o, "  crown angle      {:6.2} °", p.crown_angle);
    let _ = writeln!(o, "  pavilion angle   {:6.2} °", p.pavilion_angle);
    let _ = writeln!(o, "  crown height     {}", pct(p.crown_height));
    let _ = writeln!(o, "  pavilion depth   {}", pct(p.pavilion_depth));
    let _ = writeln!(o, "  total depth      {}", pct(p.total_depth));
    let _ = writeln!(o, "  girdle           {}", pct(p.girdle));
    let _ = writeln!(o, "\nTiers                 angle   count");
    for t in &j.tiers {
        let _ = writeln!(
            o,
            "  {:<16} {:8.2} ° {:5}   {}",
            t.name, t.angle, t.count, t.side
        );
    }
    if j.family.is_none() {
        let _ = writeln!(
            o,
            "  ({} TIER=DEG turns a tier; the depths follow so that the meets are kept)",
            setting(CUT_PARAMETER)
        );
    }
    let _ = writeln!(
        o,
        "\nFacets {}   vertices {}   volume {:.5} W³",
        j.facet_count, j.vertex_count, j.volume
    );
    let r = &j.ratios;
    let _ = writeln!(
        o,
        "Ratios L/W {:.3}   T/W {:.3}   P/W {:.3}   C/W {:.3}   H/W {:.3}   Vol/W³ {:.4}",
        r.l_w, r.t_w, r.p_w, r.c_w, r.h_w, r.vol_w3
    );
    let z = &j.size_mm;
    let _ = writeln!(
        o,
        "Size {:.2} × {:.2} × {:.2} mm (L × W × D)   weight {:.3} ct in {}",
        z.length, z.width, z.depth, j.carats, j.material
    );
    if j.material.starts_with("ri:") {
        let _ = writeln!(
            o,
            "  ({} has no density of its own: the weight uses diamond's, 3.515 g/cm³)",
            j.material
        );
    }
    let c = &j.checks;
    let _ = writeln!(
        o,
        "Checks: convex solid, {} (V − E + F = {}), smallest facet {:.3} of the mean area",
        if c.closed { "closed" } else { "NOT closed" },
        c.euler_characteristic,
        c.smallest_facet_ratio
    );
    if let Some(g) = &j.grade {
        let limit = if g.limiting.is_empty() {
            String::new()
        } else {
            format!(", limited by {}", g.limiting.join(", "))
        };
        let _ = writeln!(
            o,
            "Grade estimate: {}{limit} ({})",
            g.estimate.name(),
            g.note
        );
    }
    if !j.params.is_empty() {
        let _ = writeln!(o, "\nParameters ({} KEY=VALUE)", setting(CUT_PARAMETER));
        for (k, v) in &j.params {
            let _ = writeln!(o, "  {k:<16} {v}");
        }
    }
    o
}
