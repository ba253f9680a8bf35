//! A rough plan's run: the families planned in turn ([`plan_families`]) and the run folder
//! written from the plans ([`write_folder`]), into a temporary folder beside it, renamed at
//! the end, so nothing half-written is left:
//!
//! - `summary.json` ([`crate::plan::summary`]),
//! - per plan `FAMILY-K.obj` and `FAMILY-K.toml` (the cut placed in the rough, mm),
//!   `FAMILY-K.asc` (the design itself: GemCad has no position), `FAMILY-K-views.png` (three
//!   views of the rough with the cut inside),
//! - `rough.obj` (the rough's convex hull), `scene.obj` and `scene.gltf` (the rough and every
//!   plan's cut, one object each), `overview.png` (each family's best plan in the rough),
//!   `report.html` (the rough, every plan in a table, each family's best in the rough and its
//!   pictures and scores).
//!
//! The pictures and the page are drawn by the floors above the planner, through
//! [`Drawings`] (the real ones are `crate::report::PlanDrawings`).

use super::layout::{Inclusion, Layout};
use super::summary::{summary_json, PlanJson, SummaryOf};
use super::{Plan, PlanConfig, Planner, Rough};
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::geometry::{DVec3, Polyhedron};
use crate::io::gltf::{write_gltf, GltfObject};
use crate::io::mesh::write_obj_objects;
use crate::metrics::{score, ScoreConfig};
use crate::optics::Material;
use glam::DQuat;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// Plan each family of `config` in `rough` in turn: `family(name)` is asked before each
/// (false stops, keeping the families planned so far), `tick` runs after each start; a raised
/// `stop` ends the family being planned at once and drops it. With `[objective] kind =
/// "colour"` each family's plans are ranked by their face-up colour ([`super::colour`]).
/// Refuses a rough too small for any cut (the widest plan narrower than `min_width_mm`), and
/// the colour objective for a colourless material.
pub fn plan_families(
    rough: &Rough,
    config: &PlanConfig,
    material: &Material,
    family: &dyn Fn(&str) -> bool,
    tick: &(dyn Fn() + Sync),
    stop: Option<&AtomicBool>,
) -> Result<Vec<(String, Vec<Plan>)>> {
    super::colour::check(config, material)?;
    let mut planner = Planner::new(rough, config, material.density);
    if let Some(s) = stop {
        planner = planner.with_stop(s);
    }
    let mut all: Vec<(String, Vec<Plan>)> = Vec::new();
    for f in &config.families {
        if planner.stopped() || !family(f) {
            break;
        }
        let mut plans = planner.plan_family(f, tick)?;
        if planner.stopped() {
            break;
        }
        if matches!(config.objective, super::Objective::Colour(_)) {
            super::colour::rank_by_colour(&mut plans, config, material, |p| planner.meets_grade(p));
        }
        all.push((f.clone(), plans));
    }
    // Too small: the best plan of every family is narrower than the config allows.
    let widest = all
        .iter()
        .flat_map(|(_, p)| p.iter().map(|p| p.scale))
        .fold(0.0, f64::max);
    if !all.is_empty() && widest < config.min_width_mm {
        return Err(Error::invalid(
            "ROUGH",
            format!(
                "the rough is too small: the widest cut that fits is {widest:.3} mm across; allowed ≥ {} mm (min_width_mm in the config)",
                config.min_width_mm
            ),
        ));
    }
    Ok(all)
}

/// What a finished plan writes: the run folder `out`, for the rough given as `input`.
pub struct Run<'r> {
    /// The run folder (must not exist, or be an empty folder).
    pub out: &'r Path,
    /// The rough as given (a path or a crystal form's name).
    pub input: &'r str,
    /// The plan config as understood.
    pub config: &'r PlanConfig,
    /// The material of the weights and scores.
    pub material: &'r Material,
    /// The rough.
    pub rough: &'r Rough,
    /// The plans of each family, best first ([`plan_families`]).
    pub all: &'r [(String, Vec<Plan>)],
    /// When the run started (for `summary.json`'s `elapsed_s`).
    pub started: Instant,
    /// What the run should tell its user (`summary.json`'s `warnings`).
    pub warnings: &'r [String],
    /// A layout of several stones (`--stones N`, inclusions): written instead of `all`, its
    /// stones as `stone-K`.
    pub layout: Option<&'r Layout>,
    /// The inclusions kept out of the stones.
    pub inclusions: &'r [Inclusion],
}

/// A layout as its picture shows it: the stones placed, the saw planes `(normal, offset)` in
/// cutting order and the inclusions' hulls.
pub struct LayoutShown<'a> {
    /// The stones placed in the rough.
    pub stones: Vec<PlacedPlan<'a>>,
    /// The saw planes `(normal, offset, the piece it cuts)`, in cutting order.
    pub saw: Vec<(DVec3, f64, &'a Polyhedron)>,
    /// The inclusions' hulls (mm).
    pub inclusions: Vec<&'a Polyhedron>,
}

/// One plan's cut placed in the rough, as a picture shows it.
pub struct PlacedPlan<'a> {
    /// The placed cut (mm, the rough's coordinates).
    pub solid: &'a Polyhedron,
    /// Its caption (`round-brilliant-1: 0.529 ct, yield 52.4 %`).
    pub label: &'a str,
    /// Rough's frame → the cut's frame.
    pub frame: DQuat,
}

/// The pictures and the page of a plan's folder, drawn by the floors above the planner.
pub trait Drawings {
    /// Plan `stem`'s three views in `rough`, written to `png` and `svg`.
    fn views(
        &self,
        rough: &Rough,
        stem: &str,
        plan: &PlacedPlan<'_>,
        png: &Path,
        svg: &Path,
    ) -> Result<()>;
    /// Each family's best plan in `rough`, one panel each, written to `png` and `svg`.
    fn overview(
        &self,
        rough: &Rough,
        best: &[PlacedPlan<'_>],
        png: &Path,
        svg: &Path,
    ) -> Result<()>;
    /// A layout of several stones in `rough` (the rough see-through, the saw planes, the
    /// inclusions, each stone), written to `png` and `svg`.
    fn layout(&self, rough: &Rough, shown: &LayoutShown<'_>, png: &Path, svg: &Path) -> Result<()>;
    /// `report.html`: the rough, every plan, and each family's best with its three views
    /// (`views`, PNG bytes, one per family) scored with `score`.
    fn page(
        &self,
        rough: &Rough,
        all: &[(String, Vec<Plan>)],
        views: &[Vec<u8>],
        score: &ScoreConfig,
    ) -> Result<String>;
}

/// Write the run folder (into a temporary folder beside it, renamed at the end; `out` must
/// not exist or be an empty folder), its pictures and page drawn by `drawings`.
pub fn write_folder(run: &Run<'_>, drawings: &dyn Drawings) -> Result<()> {
    let out = run.out;
    let name = out
        .file_name()
        .map_or("plan".into(), |n| n.to_string_lossy().to_string());
    let parent = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let tmp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
    let result = write_into(&tmp, run, drawings).and_then(|()| {
        if out.is_dir() {
            std::fs::remove_dir(out).map_err(|e| Error::io(out.display().to_string(), e))?;
        }
        std::fs::rename(&tmp, out).map_err(|e| Error::io(out.display().to_string(), e))
    });
    if result.is_err() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    result
}

fn write(dir: &Path, file: &str, bytes: &[u8]) -> Result<()> {
    let p = dir.join(file);
    std::fs::write(&p, bytes).map_err(|e| Error::io(p.display().to_string(), e))
}

fn write_into(dir: &Path, run: &Run<'_>, drawings: &dyn Drawings) -> Result<()> {
    let Run {
        input,
        config,
        material,
        rough,
        all,
        started,
        warnings,
        layout,
        inclusions,
        out: _,
    } = *run;
    // What is written: each family's plans, or the layout's stones.
    type Entry<'p> = (String, usize, String, &'p Plan);
    let entries: Vec<Entry<'_>> = match layout {
        Some(l) => l
            .stones
            .iter()
            .enumerate()
            .map(|(k, s)| (s.family.clone(), k + 1, format!("stone-{}", k + 1), &s.plan))
            .collect(),
        None => all
            .iter()
            .flat_map(|(fam, plans)| {
                plans
                    .iter()
                    .enumerate()
                    .map(move |(k, p)| (fam.clone(), k + 1, format!("{fam}-{}", k + 1), p))
            })
            .collect(),
    };
    let page_all: Vec<(String, Vec<Plan>)> = match layout {
        Some(l) => l
            .stones
            .iter()
            .enumerate()
            .map(|(k, s)| {
                (
                    format!("stone-{} ({})", k + 1, s.family),
                    vec![s.plan.clone()],
                )
            })
            .collect(),
        None => all.to_vec(),
    };
    let view_files: Vec<String> = match layout {
        Some(l) => (1..=l.stones.len())
            .map(|k| format!("stone-{k}-views.png"))
            .collect(),
        None => all
            .iter()
            .map(|(fam, _)| format!("{fam}-1-views.png"))
            .collect(),
    };
    std::fs::create_dir(dir).map_err(|e| Error::io(dir.display().to_string(), e))?;
    let header = format!(
        "# facetlab plan of {}: units mm, the rough's own coordinates\n",
        rough.name
    );
    let mut rough_obj = header.clone();
    rough_obj.push_str(&write_obj_objects(&[("rough", &rough.solid)]));
    write(dir, "rough.obj", rough_obj.as_bytes())?;
    let mut score_cfg = ScoreConfig::fast();
    score_cfg.material = material.clone();
    let mut plans_json = Vec::new();
    let mut best: Vec<(Polyhedron, String, DQuat)> = Vec::new();
    let mut scene_solids: Vec<(String, Polyhedron)> = Vec::new();
    for (fam, rank, stem, p) in &entries {
        let (fam, stem, p) = (fam.as_str(), stem.clone(), *p);
        {
            let placed = p.placed_solid()?;
            let mut placed_cut = Cut::from_planes(&stem, &p.placed_planes())?;
            placed_cut.name = stem.clone();
            scene_solids.push((stem.clone(), placed.clone()));
            let mut obj = header.clone();
            obj.push_str(&crate::io::mesh::write_obj(&placed_cut));
            write(dir, &format!("{stem}.obj"), obj.as_bytes())?;
            write(
                dir,
                &format!("{stem}.toml"),
                crate::io::spec::write(&placed_cut).as_bytes(),
            )?;
            let mut design = p.cut.clone();
            design.name = stem.clone();
            // A uniaxial stone's optic axis where the rough's c-axis puts it in this plan:
            // scored so, and noted in the design with its material, as `score` reads them.
            let axis = config.c_axis.map(|c| p.optic_axis(c));
            let plan_cfg = match axis {
                Some(a) => {
                    let mut m = material.clone();
                    if let Some(u) = m.uniaxial.as_mut() {
                        u.axis = a;
                    }
                    if design.record.is_none() {
                        design.record = Some(crate::cut::GemcadRecord::generated(
                            &design,
                            0,
                            material.ri_d(),
                        ));
                    }
                    if let Some(r) = design.record.as_mut() {
                        r.footnotes.push(format!("Material: {}", material.name));
                        r.footnotes.push(format!("Optic axis: {}", a.label()));
                    }
                    ScoreConfig {
                        material: m,
                        ..score_cfg.clone()
                    }
                }
                None => score_cfg.clone(),
            };
            write(
                dir,
                &format!("{stem}.asc"),
                crate::io::asc::write_for(&design, 96, material.ri_d()).as_bytes(),
            )?;
            let label = match layout {
                Some(_) => format!(
                    "{stem} ({fam}): {:.3} ct, yield {:.1} %",
                    p.carats,
                    100.0 * p.yield_fraction
                ),
                None => format!(
                    "{stem}: {:.3} ct, yield {:.1} %",
                    p.carats,
                    100.0 * p.yield_fraction
                ),
            };
            let shown = PlacedPlan {
                solid: &placed,
                label: &label,
                frame: p.rotation.inverse(),
            };
            drawings.views(
                rough,
                &stem,
                &shown,
                &dir.join(format!("{stem}-views.png")),
                &dir.join(format!("{stem}-views.svg")),
            )?;
            if *rank == 1 || layout.is_some() {
                best.push((placed.clone(), label.clone(), p.rotation.inverse()));
            }
            let s = score(&p.cut.solid, &plan_cfg);
            let (lo, hi) = placed.bounding_box();
            plans_json.push(PlanJson::new(
                fam,
                *rank,
                &stem,
                p,
                (hi - lo).to_array(),
                &s,
                config,
            ));
        }
    }
    let mut scene = header;
    let mut objects: Vec<(&str, &Polyhedron)> = vec![("rough", &rough.solid)];
    objects.extend(scene_solids.iter().map(|(n, s)| (n.as_str(), s)));
    scene.push_str(&write_obj_objects(&objects));
    write(dir, "scene.obj", scene.as_bytes())?;
    // The same scene as glTF (metres): the rough see-through, the plans in four colours in turn.
    let palette = [
        [1.0, 1.0, 1.0, 1.0],
        [1.0, 0.55, 0.2, 1.0],
        [0.3, 0.8, 0.3, 1.0],
        [0.9, 0.3, 0.6, 1.0],
    ];
    let mut objects = vec![GltfObject {
        name: "rough",
        solid: &rough.solid,
        rgba: [0.75, 0.85, 1.0, 0.25],
    }];
    for (k, (stem, solid)) in scene_solids.iter().enumerate() {
        objects.push(GltfObject {
            name: stem,
            solid,
            rgba: palette[k % palette.len()],
        });
    }
    let generator = format!("facetlab {} plan", env!("CARGO_PKG_VERSION"));
    write(
        dir,
        "scene.gltf",
        write_gltf(&objects, &generator).as_bytes(),
    )?;
    let views: Vec<Vec<u8>> = view_files
        .iter()
        .map(|f| {
            let p = dir.join(f);
            std::fs::read(&p).map_err(|e| Error::io(p.display().to_string(), e))
        })
        .collect::<Result<_>>()?;
    let page = drawings.page(rough, &page_all, &views, &score_cfg)?;
    write(dir, "report.html", page.as_bytes())?;
    let best: Vec<PlacedPlan> = best
        .iter()
        .map(|(s, l, frame)| PlacedPlan {
            solid: s,
            label: l,
            frame: *frame,
        })
        .collect();
    match layout {
        Some(l) => drawings.layout(
            rough,
            &LayoutShown {
                stones: best,
                saw: l
                    .saw
                    .iter()
                    .map(|c| (c.normal, c.offset, &c.piece_solid))
                    .collect(),
                inclusions: inclusions.iter().map(|i| &i.hull).collect(),
            },
            &dir.join("overview.png"),
            &dir.join("overview.svg"),
        )?,
        None => drawings.overview(
            rough,
            &best,
            &dir.join("overview.png"),
            &dir.join("overview.svg"),
        )?,
    }
    let of = SummaryOf {
        input,
        rough,
        config,
        material,
        elapsed_s: started.elapsed().as_secs_f64(),
        warnings,
        layout,
        inclusions,
    };
    write(
        dir,
        "summary.json",
        summary_json(&of, plans_json)?.as_bytes(),
    )
}
