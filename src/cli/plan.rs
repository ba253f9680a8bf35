//! `facetlab plan ROUGH -o DIR`: the largest, best cuts inside a rough stone.
//!
//! ```text
//! facetlab plan cuts/rough-octahedron.obj -o results/rough            # every default family
//! facetlab plan octahedron --size-mm 6 --family round-brilliant --top 2 -o results/oct
//! facetlab plan scan.stl --size-mm 9.5 --config optim/plan/plan-value.toml -o results/scan
//! ```
//!
//! The planning is the library's ([`facetlab::plan`]); this file reads the flags, runs it with
//! a progress bar, scores the winners and writes the run folder (into a temporary folder
//! beside DIR, renamed to DIR at the end, so nothing half-written is left):
//!
//! - `summary.json` (keys in README, section "`facetlab plan`"),
//! - per plan `FAMILY-K.obj` and `FAMILY-K.toml` (the cut placed in the rough, mm),
//!   `FAMILY-K.asc` (the design itself: GemCad has no position), `FAMILY-K-views.png` (three
//!   views of the rough with the cut inside),
//! - `rough.obj` (the rough's convex hull), `scene.obj` (the rough and every plan's cut, one
//!   object each), `overview.png` (each family's best plan in the rough), `report.html` (the
//!   rough, every plan in a table, each family's best in the rough and its pictures and scores).

use super::interrupt;
use super::outputs::{refuse_overwrite, Exit};
use super::progress;
use facetlab::cut::Cut;
use facetlab::error::{Error, Result};
use facetlab::geometry::Polyhedron;
use facetlab::io::gltf::{write_gltf, GltfObject};
use facetlab::metrics::{score, ScoreConfig};
use facetlab::optics::Material;
use facetlab::plan::config::check_families;
use facetlab::plan::{
    load_rough, plan_warnings, Objective, Plan, PlanConfig, Planner, Rough, CRYSTALS,
};
use facetlab::plot::plan::{Overview, Placed, ThreeViews};
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// Flags of `facetlab plan`.
#[derive(clap::Args, Debug, Clone)]
pub struct PlanArgs {
    /// The rough: an .obj or .stl mesh in millimetres (its convex hull is planned), or a
    /// crystal form (octahedron, dodecahedron, cube, macle, or sphere: an exact ball) with --size-mm.
    #[arg(value_name = "ROUGH")]
    pub rough: String,
    /// A family to plan (repeat for more); default: the config's, or round-brilliant and the
    /// fancy shapes.
    #[arg(long = "family", value_name = "NAME")]
    pub families: Vec<String>,
    /// Plan config (objective, bounds, search; see README).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// The rough's largest extent in mm: scales a mesh in other units, sizes a crystal form.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    pub size_mm: Option<String>,
    /// Material for the carat weight and the scores (`facetlab materials`); default diamond.
    #[arg(long, value_name = "NAME")]
    pub material: Option<String>,
    /// Distinct plans kept per family (1–50); default the config's (3).
    #[arg(long, value_name = "K", allow_hyphen_values = true)]
    pub top: Option<String>,
    /// The run folder to write (must not exist, or be empty).
    #[arg(short = 'o', long = "out", value_name = "DIR")]
    pub out: PathBuf,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

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

#[derive(Serialize)]
struct PlanJson {
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
    scores: ScoresJson,
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
}

fn size_flag(s: &str) -> Result<f64> {
    facetlab::io::text::number(
        "--size-mm",
        s,
        1e-3,
        500.0,
        "the rough's largest extent in mm",
    )
}

/// Run `facetlab plan`. Exits 130 when Ctrl-C or SIGTERM stopped it (after writing the
/// families planned so far, if any).
pub fn run(a: &PlanArgs) -> Result<Exit> {
    let started = Instant::now();
    let mut config = match &a.config {
        Some(p) => PlanConfig::load(p)?,
        None => PlanConfig::default(),
    };
    if !a.families.is_empty() {
        config.families = check_families(&a.families).map_err(|m| Error::invalid("--family", m))?;
    }
    if let Some(t) = &a.top {
        config.top = facetlab::io::text::count("--top", t, 1, 50)? as usize;
    }
    if let Some(m) = &a.material {
        Material::by_name(m)?;
        config.material = m.clone();
    }
    let material = Material::by_name(&config.material)?;
    let size = a.size_mm.as_deref().map(size_flag).transpose()?;
    // Outputs: a new or empty folder that is none of the inputs (the rough, the config, the
    // price table it names).
    let mut inputs = vec![PathBuf::from(&a.rough)];
    inputs.extend(a.config.iter().cloned());
    inputs.extend(config.inputs());
    refuse_overwrite(&[("--out", a.out.clone())], &inputs)?;
    if a.out.is_file()
        || (a.out.is_dir() && a.out.read_dir().map_or(true, |mut d| d.next().is_some()))
    {
        return Err(Error::invalid(
            "--out",
            format!(
                "{} exists and is not an empty folder; choose a new folder",
                a.out.display()
            ),
        ));
    }
    let parent = a
        .out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !parent.is_dir() {
        return Err(Error::io(
            a.out.display().to_string(),
            format!("folder {} does not exist", parent.display()),
        ));
    }
    facetlab::io::check_writable(parent)?;
    let rough = load_rough(&a.rough, size).map_err(|e| match e {
        Error::Invalid { field, message }
            if field == "ROUGH"
                && !CRYSTALS.contains(&a.rough.as_str())
                && !Path::new(&a.rough).exists() =>
        {
            Error::io(
                &a.rough,
                format!("no such file, and not a crystal form; {message}"),
            )
        }
        other => other,
    })?;

    interrupt::install();
    let bar = progress::bar(
        (config.families.len() * config.starts) as u64,
        a.quiet,
        "{msg:>16} [{bar:40}] {pos}/{len} starts, {elapsed}",
    );
    let tick = || bar.inc(1);
    let family = |f: &str| {
        bar.set_message(f.to_string());
        true
    };
    let all = plan_families(
        &rough,
        &config,
        &material,
        &family,
        &tick,
        Some(&interrupt::STOP),
    );
    bar.finish_and_clear();
    let all = all?;
    let interrupted = interrupt::stopped();
    if interrupted && all.is_empty() {
        eprintln!(
            "facetlab: interrupted before any family was planned; nothing written (exit code 130)"
        );
        return Ok(Exit::Interrupted);
    }
    let warnings = plan_warnings(&config, &all);
    let run = Run {
        out: &a.out,
        input: &a.rough,
        config: &config,
        material: &material,
        rough: &rough,
        all: &all,
        started,
        warnings: &warnings,
    };
    write_folder(&run)?;
    print_summary(&run);
    for w in &warnings {
        eprintln!("facetlab: warning: {w}");
    }
    if interrupted {
        let done: Vec<&str> = all.iter().map(|(f, _)| f.as_str()).collect();
        let left: Vec<&str> = config
            .families
            .iter()
            .map(String::as_str)
            .filter(|f| !done.contains(f))
            .collect();
        eprintln!(
            "facetlab: interrupted; wrote the families planned ({}), not {} (exit code 130)",
            done.join(", "),
            left.join(", ")
        );
        return Ok(Exit::Interrupted);
    }
    Ok(Exit::Ok)
}

/// Plan each family of `config` in `rough` in turn: `family(name)` is asked before each
/// (false stops, keeping the families planned so far), `tick` runs after each start; a raised
/// `stop` ends the family being planned at once and drops it. Refuses a rough too small for
/// any cut (the widest plan narrower than `min_width_mm`).
pub fn plan_families(
    rough: &Rough,
    config: &PlanConfig,
    material: &Material,
    family: &dyn Fn(&str) -> bool,
    tick: &(dyn Fn() + Sync),
    stop: Option<&AtomicBool>,
) -> Result<Vec<(String, Vec<Plan>)>> {
    let mut planner = Planner::new(rough, config, material.density);
    if let Some(s) = stop {
        planner = planner.with_stop(s);
    }
    let mut all: Vec<(String, Vec<Plan>)> = Vec::new();
    for f in &config.families {
        if planner.stopped() || !family(f) {
            break;
        }
        let plans = planner.plan_family(f, tick)?;
        if planner.stopped() {
            break;
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
    pub out: &'r Path,
    pub input: &'r str,
    pub config: &'r PlanConfig,
    pub material: &'r Material,
    pub rough: &'r Rough,
    pub all: &'r [(String, Vec<Plan>)],
    pub started: Instant,
    /// What the run should tell its user (`summary.json`'s `warnings`).
    pub warnings: &'r [String],
}

/// Write the run folder (into a temporary folder beside it, renamed at the end; `out` must
/// not exist or be an empty folder).
pub fn write_folder(run: &Run<'_>) -> Result<()> {
    let out = run.out;
    let name = out
        .file_name()
        .map_or("plan".into(), |n| n.to_string_lossy().to_string());
    let parent = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let tmp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
    let result = write_into(&tmp, run).and_then(|()| {
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

/// The lines `facetlab plan` prints at the end: the rough, each family's best, the folder.
fn print_summary(run: &Run<'_>) {
    let rough = run.rough;
    let hull = match rough.mesh_volume {
        Some(v) => format!(
            " (the mesh {v:.3} mm³; its convex hull adds {:.2} %)",
            100.0 * rough.hull_excess()
        ),
        None => String::new(),
    };
    println!("rough {}: {:.3} mm³{hull}", rough.name, rough.volume());
    if rough.left_out > 0.0 {
        println!(
            "  planned in the hull of {} of its vertices, inside the full hull; the farthest vertex left out lies {:.1} µm outside it",
            rough.hull_vertices,
            1000.0 * rough.left_out
        );
    }
    for (fam, plans) in run.all {
        if let Some(p) = plans.first() {
            println!(
                "{fam:<16} {:.4} ct, yield {:.2} %, W {:.3} mm",
                p.carats,
                100.0 * p.yield_fraction,
                p.scale
            );
        }
    }
    println!("{}", run.out.display());
}

fn write(dir: &Path, file: &str, bytes: &[u8]) -> Result<()> {
    let p = dir.join(file);
    std::fs::write(&p, bytes).map_err(|e| Error::io(p.display().to_string(), e))
}

fn obj_object(out: &mut String, name: &str, s: &Polyhedron, base: &mut usize) {
    let _ = writeln!(out, "o {name}");
    for v in s.vertices() {
        let _ = writeln!(out, "v {} {} {}", v.x, v.y, v.z);
    }
    for f in s.facets() {
        let idx: Vec<String> = f
            .vertices
            .iter()
            .map(|i| (i + 1 + *base).to_string())
            .collect();
        let _ = writeln!(out, "f {}", idx.join(" "));
    }
    *base += s.vertices().len();
}

fn write_into(dir: &Path, run: &Run<'_>) -> Result<()> {
    let Run {
        input,
        config,
        material,
        rough,
        all,
        started,
        warnings,
        out: _,
    } = *run;
    std::fs::create_dir(dir).map_err(|e| Error::io(dir.display().to_string(), e))?;
    let header = format!(
        "# facetlab plan of {}: units mm, the rough's own coordinates\n",
        rough.name
    );
    let mut base = 0;
    let mut scene = header.clone();
    obj_object(&mut scene, "rough", &rough.solid, &mut base);
    let mut rough_obj = header.clone();
    obj_object(&mut rough_obj, "rough", &rough.solid, &mut 0);
    write(dir, "rough.obj", rough_obj.as_bytes())?;
    let mut score_cfg = ScoreConfig::fast();
    score_cfg.material = material.clone();
    let mut plans_json = Vec::new();
    let mut best: Vec<(Polyhedron, String, glam::DQuat)> = Vec::new();
    let mut scene_solids: Vec<(String, Polyhedron)> = Vec::new();
    for (fam, plans) in all {
        for (k, p) in plans.iter().enumerate() {
            let stem = format!("{fam}-{}", k + 1);
            let placed = p.placed_solid()?;
            let mut placed_cut = Cut::from_planes(&stem, &p.placed_planes())?;
            placed_cut.name = stem.clone();
            obj_object(&mut scene, &stem, &placed, &mut base);
            scene_solids.push((stem.clone(), placed.clone()));
            let mut obj = header.clone();
            obj.push_str(&facetlab::io::mesh::write_obj(&placed_cut));
            write(dir, &format!("{stem}.obj"), obj.as_bytes())?;
            write(
                dir,
                &format!("{stem}.toml"),
                facetlab::io::spec::write(&placed_cut).as_bytes(),
            )?;
            let mut design = p.cut.clone();
            design.name = stem.clone();
            write(
                dir,
                &format!("{stem}.asc"),
                facetlab::io::asc::write_for(&design, 96, material.ri_d()).as_bytes(),
            )?;
            let label = format!(
                "{stem}: {:.3} ct, yield {:.1} %",
                p.carats,
                100.0 * p.yield_fraction
            );
            let views = ThreeViews {
                rough: &rough.solid,
                cut: Placed {
                    solid: &placed,
                    label: label.clone(),
                    frame: p.rotation.inverse(),
                },
                title: format!("{} in {}", stem, rough.name),
            };
            facetlab::plot::save_to(
                &views,
                &dir.join(format!("{stem}-views.png")),
                &dir.join(format!("{stem}-views.svg")),
            )?;
            if k == 0 {
                best.push((placed.clone(), label, p.rotation.inverse()));
            }
            let s = score(&p.cut.solid, &score_cfg);
            let (lo, hi) = placed.bounding_box();
            let pr = p.cut.proportions();
            let up = p.up();
            plans_json.push(PlanJson {
                family: fam.clone(),
                rank: k + 1,
                stem,
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
                size_mm: (hi - lo).to_array(),
                params: p.cut.params.clone(),
                total_depth: pr.total_depth,
                crown_height: pr.crown_height,
                pavilion_depth: pr.pavilion_depth,
                rotation: p.rotation.to_array(),
                table_normal: up.to_array(),
                shift_mm: p.shift.to_array(),
                scores: ScoresJson {
                    brilliance: s.brilliance,
                    fire: s.fire,
                    scintillation: s.scintillation,
                },
            });
        }
    }
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
    let views: Vec<Vec<u8>> = all
        .iter()
        .map(|(fam, _)| {
            let p = dir.join(format!("{fam}-1-views.png"));
            std::fs::read(&p).map_err(|e| Error::io(p.display().to_string(), e))
        })
        .collect::<Result<_>>()?;
    let page = facetlab::report::plan_page(rough, all, &views, &score_cfg)?;
    write(dir, "report.html", page.as_bytes())?;
    let overview = Overview {
        rough: &rough.solid,
        cuts: best
            .iter()
            .map(|(s, l, frame)| Placed {
                solid: s,
                label: l.clone(),
                frame: *frame,
            })
            .collect(),
        title: format!("best plan of each family in {}", rough.name),
    };
    facetlab::plot::save_to(
        &overview,
        &dir.join("overview.png"),
        &dir.join("overview.svg"),
    )?;
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
        },
        currency: match &config.objective {
            Objective::Value(t) => Some(t.currency.clone()),
            Objective::Weight => None,
        },
        grade: config.grade.map(|g| g.name().to_string()),
        min_brilliance: config.min_brilliance,
        seed: config.seed,
        starts: config.starts,
        families: config.families.clone(),
        elapsed_s: started.elapsed().as_secs_f64(),
        plans: plans_json,
        warnings: warnings.to_vec(),
    };
    let json = serde_json::to_string_pretty(&summary)
        .map_err(|e| Error::invalid("summary.json", e.to_string()))?;
    write(dir, "summary.json", json.as_bytes())
}
