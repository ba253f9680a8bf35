//! The plan document: a rough plan's `summary.json` (keys in docs/plan.md, section
//! "`facetlab plan`"): the rough, the material and the objective as understood, and every plan
//! with its weight, yield, grade, pose and scores ([`PlanJson`], made as the folder is
//! written by [`crate::plan::run`]).

use super::layout::{Inclusion, Layout};
use super::{Objective, Plan, PlanConfig, Rough};
use crate::error::{Error, Result};
use crate::metrics::Scores;
use crate::optics::Material;
use serde::Serialize;
use std::collections::BTreeMap;

#[derive(Serialize)]
struct RoughJson {
    name: String,
    input: String,
    volume_mm3: f64,
    mesh_volume_mm3: Option<f64>,
    hull_excess: f64,
    size_mm: f64,
    planes: usize,
    hull_vertices: usize,
    left_out_mm: f64,
}

#[derive(Serialize)]
struct ScoresJson {
    brilliance: f64,
    fire: f64,
    scintillation: f64,
}

/// One plan as `summary.json`'s `plans[]` lists it.
#[derive(Serialize)]
pub struct PlanJson {
    family: String,
    rank: usize,
    stem: String,
    carats: f64,
    volume_mm3: f64,
    #[serde(rename = "yield")]
    yield_fraction: f64,
    objective: f64,
    grade: Option<String>,
    meets_grade: bool,
    meets_brilliance: bool,
    width_mm: f64,
    size_mm: [f64; 3],
    params: BTreeMap<String, f64>,
    total_depth: f64,
    crown_height: f64,
    pavilion_depth: f64,
    rotation: [f64; 4],
    table_normal: [f64; 3],
    shift_mm: [f64; 3],
    /// The optic axis where `[rough] c_axis` puts it (`DEG@AZ`), when given.
    #[serde(skip_serializing_if = "Option::is_none")]
    optic_axis: Option<String>,
    scores: ScoresJson,
    /// The face-up colour the plan was ranked by (`[objective] kind = "colour"`).
    #[serde(skip_serializing_if = "Option::is_none")]
    colour: Option<crate::render::ColourStats>,
}

impl PlanJson {
    /// Plan `p`, ranked `rank` (from 1) in `family` and written as `stem`, with the extent
    /// `size_mm` of its placed cut and its scores `s`, judged against `config`'s grade and
    /// minimum brilliance.
    pub fn new(
        family: &str,
        rank: usize,
        stem: &str,
        p: &Plan,
        size_mm: [f64; 3],
        s: &Scores,
        config: &PlanConfig,
    ) -> PlanJson {
        let pr = p.cut.proportions();
        PlanJson {
            family: family.to_string(),
            rank,
            stem: stem.to_string(),
            carats: p.carats,
            volume_mm3: p.volume_mm3,
            yield_fraction: p.yield_fraction,
            objective: p.objective,
            grade: p.grade.map(|g| g.name().to_string()),
            meets_grade: match (config.grade, p.grade) {
                (Some(w), Some(g)) => g <= w,
                _ => true,
            },
            meets_brilliance: config.min_brilliance.is_none_or(|m| s.brilliance >= m),
            width_mm: p.scale,
            size_mm,
            params: p.cut.params.clone(),
            total_depth: pr.total_depth,
            crown_height: pr.crown_height,
            pavilion_depth: pr.pavilion_depth,
            rotation: p.rotation.to_array(),
            table_normal: p.up().to_array(),
            shift_mm: p.shift.to_array(),
            optic_axis: config.c_axis.map(|c| p.optic_axis(c).label()),
            scores: ScoresJson {
                brilliance: s.brilliance,
                fire: s.fire,
                scintillation: s.scintillation,
            },
            colour: p.colour,
        }
    }
}

/// One stone of a layout as `summary.json`'s `stones[]` lists it (its full plan is
/// `plans[]`'s entry of the same `stem`).
#[derive(Serialize)]
struct StoneJson {
    stem: String,
    family: String,
    piece: String,
    carats: f64,
    objective: f64,
    #[serde(rename = "yield")]
    yield_fraction: f64,
    width_mm: f64,
    /// Where it lies: its centroid in the rough's coordinates (mm).
    centre_mm: Option<[f64; 3]>,
    piece_volume_mm3: f64,
    /// Half-spaces `normal·x <= offset_mm` that keep the inclusions off it.
    keep_off: Vec<KeepOffJson>,
    /// Inclusions it holds (at the price table's `included` factor).
    holds: Vec<String>,
    /// Ranked by colour: its worth (price-table value, else carats), face-up colour and
    /// colour factor; `objective` is worth × factor.
    #[serde(skip_serializing_if = "Option::is_none")]
    worth: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    colour: Option<crate::render::ColourStats>,
    #[serde(skip_serializing_if = "Option::is_none")]
    colour_factor: Option<f64>,
}

#[derive(Serialize)]
struct KeepOffJson {
    inclusion: String,
    normal: [f64; 3],
    offset_mm: f64,
}

/// One saw cut of a layout, in cutting order.
#[derive(Serialize)]
struct SawJson {
    order: usize,
    piece: String,
    normal: [f64; 3],
    offset_mm: f64,
    kerf_loss_mm3: f64,
}

/// A plane between two stones: the kerf's middle plane, the first stone below it.
#[derive(Serialize)]
struct PairJson {
    stones: [String; 2],
    normal: [f64; 3],
    offset_mm: f64,
}

/// The layout's totals and settings.
#[derive(Serialize)]
struct LayoutJson {
    cutter: &'static str,
    stones_asked: usize,
    stones: usize,
    kerf_mm: f64,
    allowance_mm: f64,
    inclusion_margin_mm: f64,
    inclusions: Vec<String>,
    total_objective: f64,
    total_carats: f64,
    #[serde(rename = "yield")]
    yield_fraction: f64,
    kerf_loss_mm3: f64,
    pairs: Vec<PairJson>,
    /// Ranked by colour: the stones' worth before colour, and the reference chroma.
    #[serde(skip_serializing_if = "Option::is_none")]
    total_worth: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    colour_reference_c: Option<f64>,
}

#[derive(Serialize)]
struct SummaryJson {
    rough: RoughJson,
    material: String,
    density: f64,
    objective: String,
    currency: Option<String>,
    grade: Option<String>,
    min_brilliance: Option<f64>,
    seed: u64,
    starts: usize,
    families: Vec<String>,
    elapsed_s: f64,
    plans: Vec<PlanJson>,
    warnings: Vec<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    layout: Option<LayoutJson>,
    #[serde(skip_serializing_if = "Option::is_none")]
    stones: Option<Vec<StoneJson>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    saw_plan: Option<Vec<SawJson>>,
}

/// What `summary.json` is made of besides the plans.
pub struct SummaryOf<'a> {
    /// The rough as given (a path or a crystal form's name).
    pub input: &'a str,
    /// The rough.
    pub rough: &'a Rough,
    /// The plan config as understood.
    pub config: &'a PlanConfig,
    /// The material of the weights and scores.
    pub material: &'a Material,
    /// Seconds the run took.
    pub elapsed_s: f64,
    /// What the run should tell its user.
    pub warnings: &'a [String],
    /// A layout of several stones, when one was planned.
    pub layout: Option<&'a Layout>,
    /// The inclusions kept out.
    pub inclusions: &'a [Inclusion],
}

/// `summary.json`, pretty-printed: the run `of` with its `plans` in order.
pub fn summary_json(of: &SummaryOf<'_>, plans: Vec<PlanJson>) -> Result<String> {
    let SummaryOf {
        input,
        rough,
        config,
        material,
        elapsed_s,
        warnings,
        layout,
        inclusions,
    } = *of;
    let name = |i: usize| inclusions.get(i).map_or(String::new(), |x| x.name.clone());
    let stones = layout.map(|l| {
        l.stones
            .iter()
            .enumerate()
            .map(|(k, s)| StoneJson {
                stem: format!("stone-{}", k + 1),
                family: s.family.clone(),
                piece: s.piece.clone(),
                carats: s.plan.carats,
                objective: s.plan.objective,
                yield_fraction: s.plan.yield_fraction,
                width_mm: s.plan.scale,
                centre_mm: s.plan.placed_solid().ok().map(|p| p.centroid().to_array()),
                piece_volume_mm3: s.piece_solid.volume(),
                keep_off: s
                    .separations
                    .iter()
                    .map(|(i, p)| KeepOffJson {
                        inclusion: name(*i),
                        normal: p.normal.to_array(),
                        offset_mm: p.offset,
                    })
                    .collect(),
                holds: s.holds.iter().map(|i| name(*i)).collect(),
                worth: s.colour.map(|c| c.worth),
                colour: s.colour.and(s.plan.colour),
                colour_factor: s.colour.map(|c| c.factor),
            })
            .collect()
    });
    let saw_plan = layout.map(|l| {
        l.saw
            .iter()
            .enumerate()
            .map(|(k, c)| SawJson {
                order: k + 1,
                piece: c.piece.clone(),
                normal: c.normal.to_array(),
                offset_mm: c.offset,
                kerf_loss_mm3: c.kerf_loss_mm3,
            })
            .collect()
    });
    let layout_json = layout.map(|l| LayoutJson {
        cutter: l.cutter.name(),
        stones_asked: config.stones,
        stones: l.stones.len(),
        kerf_mm: config.kerf_mm,
        allowance_mm: config.allowance_mm,
        inclusion_margin_mm: config.margin_mm,
        inclusions: inclusions.iter().map(|i| i.name.clone()).collect(),
        total_objective: l.total,
        total_carats: l.carats,
        yield_fraction: l.yield_fraction,
        kerf_loss_mm3: l.kerf_loss_mm3,
        pairs: l
            .pairs
            .iter()
            .map(|p| PairJson {
                stones: p.stones.map(|k| format!("stone-{}", k + 1)),
                normal: p.normal.to_array(),
                offset_mm: p.offset,
            })
            .collect(),
        total_worth: l.colour_reference.map(|_| {
            l.stones
                .iter()
                .filter_map(|s| s.colour)
                .map(|c| c.worth)
                .sum()
        }),
        colour_reference_c: l.colour_reference,
    });
    let summary = SummaryJson {
        rough: RoughJson {
            name: rough.name.clone(),
            input: input.to_string(),
            volume_mm3: rough.volume(),
            mesh_volume_mm3: rough.mesh_volume,
            hull_excess: rough.hull_excess(),
            size_mm: rough.size(),
            planes: rough.solid.facets().len(),
            hull_vertices: rough.hull_vertices,
            left_out_mm: rough.left_out,
        },
        material: material.name.clone(),
        density: material.density,
        objective: match &config.objective {
            Objective::Weight => "weight".into(),
            Objective::Value(_) => "value".into(),
            Objective::Colour(_) => "colour".into(),
        },
        currency: match &config.objective {
            Objective::Value(t) | Objective::Colour(Some(t)) => Some(t.currency.clone()),
            Objective::Weight | Objective::Colour(None) => None,
        },
        grade: config.grade.map(|g| g.name().to_string()),
        min_brilliance: config.min_brilliance,
        seed: config.seed,
        starts: config.starts,
        families: config.families.clone(),
        elapsed_s,
        plans,
        warnings: warnings.to_vec(),
        layout: layout_json,
        stones,
        saw_plan,
    };
    serde_json::to_string_pretty(&summary)
        .map_err(|e| Error::invalid("summary.json", e.to_string()))
}
