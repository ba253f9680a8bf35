//! `facetlab score CUT...`: brilliance, fire, scintillation, ASET shares and overhead light
//! return from the beam tracer, one column per cut.
//!
//! ```text
//! facetlab score tolkowsky gia-reference
//! facetlab score tolkowsky --material cz --head-shadow 15
//! facetlab score mycut.toml --ri 2.42 --polarization off --json scores.json
//! ```
//!
//! Flags are read as text and validated here into [`ScoreConfig`], so every bad value ends in
//! a one-line error naming the flag and what is allowed. Score definitions and ranges are in
//! [`facetlab::metrics`].
//!
//! **JSON** (`--json FILE`, written atomically). One cut: a single object with `cut` (its
//! name), `overhead_light_return`, `brilliance`, `brilliance_iso`, `brilliance_cos`, `fire`,
//! `scintillation`, `aset.{blue,red,green,leak}`, `poses[].{tilt_deg,azimuth_deg,iso,cos}` (each
//! pose of the brilliance average with its ISO and COS light return: the mean of the picture
//! `facetlab render` draws of that pose with the same `--head-shadow`, 15 by default here) (the keys of [`Scores`]) and `settings` (the
//! run's configuration as understood: `material`, `ri` (null unless `--ri`), `polarization`,
//! `head_shadow_deg`, `wavelength_nm`, `bands`, `tilts`, `scintillation_tilts`, `resolution`,
//! `split_threshold`, `fire_split_threshold`, `face_up_split_threshold`, `threshold`, `ray_floor`, `narrow_forks`). Several cuts: `{"settings": {...}, "results": [one such
//! object per cut, without settings]}` in the order given. With `--verify` each object also gets `verify.{overhead_light_return, brilliance,
//! brilliance_iso, brilliance_cos}.{beam, photon, stderr, z, photons}`: the beam tracer's
//! value, the photon tracer's estimate and standard error, (beam − photon)/stderr, and the
//! photons per figure and pose (seed 1).

use super::flags;
use super::outputs::Exit;
use facetlab::document::score::score_table;
use facetlab::document::scoring::{score_cuts, ScoreJob, ScoreSink};
use facetlab::error::{Error, Result};
use facetlab::io::guard::{check_document_outputs, cut_files};
use facetlab::metrics::{NoteKind, ScoreConfig, Scores, StoneChoice};
use facetlab::verify::{Check, SIGMA};
use std::path::PathBuf;

/// Flags of `facetlab score`.
#[derive(clap::Args, Debug, Clone)]
pub struct ScoreArgs {
    /// Cuts to score: preset names (tolkowsky, gia-reference) or .toml/.asc/.gem/.obj/.stl files.
    #[arg(required_unless_present = "batch", value_name = "CUT")]
    pub cuts: Vec<String>,
    /// Score the cuts listed in FILE, one per line (a preset or path, optionally with
    /// `--set KEY=VALUE` pairs; `#` comments), into --jsonl OUT, resumably.
    #[arg(long, value_name = "FILE")]
    pub batch: Option<PathBuf>,
    /// Change a parameter of the cuts: a family's (`--set crown_angle=34.5`) or a design's
    /// tier angle (`--set P1=41.2`, its depths solved so its meets are kept). Repeatable;
    /// applied to every CUT.
    #[arg(long = "set", value_name = "KEY=VALUE", conflicts_with = "batch")]
    pub set: Vec<String>,
    /// With --batch: the JSON Lines file written, one line per cut (its scores or its error).
    #[arg(long, value_name = "OUT")]
    pub jsonl: Option<PathBuf>,
    /// With --batch: score only shard K of N (1-based), the cuts whose ordinal i has
    /// i mod N == K-1; default from a Slurm or Kubernetes job array's environment (`off`:
    /// all cuts, whatever the environment).
    #[arg(long, value_name = "K/N|off", value_parser = flags::shard)]
    pub shard: Option<flags::ShardFlag>,
    #[command(flatten)]
    pub material: super::flags::MaterialArgs,
    #[command(flatten)]
    pub colour: super::flags::ColourArgs,
    #[command(flatten)]
    pub crystal: super::flags::CrystalArgs,
    /// Track polarization with Stokes vectors and Mueller matrices (on) or use the
    /// unpolarized average (off).
    #[arg(long, default_value = "on", value_name = "on|off", action = clap::ArgAction::Set, value_parser = super::flags::on_off_parser("--polarization"))]
    pub polarization: bool,
    #[command(flatten)]
    pub head: super::flags::HeadShadowArgs,
    /// Write the scores as JSON to this file.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Replace an existing output file (an input is never replaced, even with --force).
    #[arg(long)]
    pub force: bool,
    /// Re-measure overhead light return and brilliance with this many photons of the photon
    /// tracer and print both with the difference in standard errors.
    #[arg(
        long,
        value_name = "PHOTONS",
        allow_hyphen_values = true,
        value_parser = flags::whole("--verify", 1, facetlab::photon::MAX_PHOTONS)
    )]
    pub verify: Option<u64>,
}

/// The flags, validated.
#[derive(Clone, Debug)]
pub struct Settings {
    /// Scoring configuration.
    pub config: ScoreConfig,
    /// Photons for `--verify`.
    pub verify: Option<u64>,
    /// The stones' material, colour, size and crystal settings.
    pub stone: StoneChoice,
}

/// Validate the flags into the library's types.
pub fn settings(a: &ScoreArgs) -> Result<Settings> {
    let mut stone = flags::stone_choice(a.material.material()?, &a.material, &a.colour, None)?;
    let material = stone.material.clone();
    let size = stone.size;
    let polarization = a.polarization;
    let head = a.head.head_shadow;
    let verify = a.verify;
    let config = ScoreConfig {
        material,
        size,
        head_shadow_deg: head,
        ..ScoreConfig::default()
    }
    .polarized(polarization);
    config.validate()?;
    stone.crystal = Some(a.crystal.choice(config.wavelength_nm));
    Ok(Settings {
        config,
        verify,
        stone,
    })
}

/// The exit status of `score`: a disagreement when any `--verify` check lies beyond
/// [`SIGMA`] standard errors.
pub fn verdict(checks: &[Vec<Check>]) -> Exit {
    if checks.iter().flatten().any(|c| c.beyond(SIGMA)) {
        Exit::Disagreement
    } else {
        Exit::Ok
    }
}

/// Run `facetlab score`; with `--verify`, a disagreement beyond [`SIGMA`] standard errors
/// exits 1 after the table and the JSON are written.
pub fn run(a: &ScoreArgs) -> Result<Exit> {
    let s = settings(a)?;
    if let Some(path) = &a.json {
        // Never overwrite a cut with its scores.
        check_document_outputs(Some(path), None, &cut_files(&a.cuts), a.force)?;
    }
    let cuts = a
        .cuts
        .iter()
        .map(|c| super::cuts::load_with_sets(c, &a.set))
        .collect::<Result<Vec<_>>>()?;
    if let Some(path) = &a.json {
        // Fail before the work, not after it (a folder's parent exists, so the order of the
        // two refusals does not matter).
        if path.is_dir() {
            return Err(Error::invalid(
                "--json",
                format!("{} is a folder; give a file name", path.display()),
            ));
        }
        facetlab::io::guard::check_folder_of(path)?;
    }
    let job = ScoreJob {
        cuts: &cuts,
        stone: &s.stone,
        fields: &flags::STONE_FIELDS,
        config: &s.config,
        verify: s.verify,
        json: a.json.as_deref(),
    };
    let scored = score_cuts(&job, &mut Printed)?;
    let exit = verdict(&scored.checks);
    if exit == Exit::Disagreement {
        eprintln!(
            "facetlab: the photon tracer disagrees with the beam tracer beyond {SIGMA} standard errors (exit code 1)"
        );
    }
    Ok(exit)
}

/// What `score` prints as it goes: the notes on stderr, the table and each cut's checks.
struct Printed;

impl ScoreSink for Printed {
    fn note(&mut self, kind: NoteKind, line: String) {
        flags::say(kind, line)
    }
    fn scored(&mut self, config: &ScoreConfig, results: &[(String, Scores)]) {
        print!("{}", score_table(config, results));
    }
    fn checking(&mut self, photons: u64) {
        println!(
            "\nphoton-tracer check, {photons} photons per figure and pose (value ± standard error; beam − photon in standard errors)"
        );
    }
    fn checked(&mut self, name: &str, checks: &[Check]) {
        println!("{name}");
        for c in checks {
            let flag = if c.beyond(SIGMA) {
                "  ⚠ beyond 4 se"
            } else {
                ""
            };
            println!(
                "  {:<24} beam {:.4}   photon {:.4} ± {:.4}   {:+.2} se{flag}",
                c.name, c.beam, c.photon, c.stderr, c.z
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use facetlab::document::score::score_json;

    fn parsed(extra: &[&str]) -> std::result::Result<ScoreArgs, clap::Error> {
        use clap::Parser;
        #[derive(Parser)]
        struct W {
            #[command(flatten)]
            a: ScoreArgs,
        }
        W::try_parse_from([&["score"], extra].concat()).map(|w| w.a)
    }

    fn args(extra: &[&str]) -> ScoreArgs {
        parsed(extra).unwrap()
    }

    /// The line a user sees: a typed flag's refusal, else the settings' error.
    fn line(extra: &[&str]) -> String {
        match parsed(extra) {
            Err(e) => crate::cli::flags::refused_value(&e).unwrap(),
            Ok(a) => settings(&a).unwrap_err().to_string(),
        }
    }

    #[test]
    fn flags_are_validated_into_one_line_errors() {
        let e = line;
        assert!(e(&["t", "--ri", "abc"]).starts_with("--ri:"));
        assert!(e(&["t", "--ri", "0.5"]).contains("allowed (1, 10]"));
        assert!(e(&["t", "--ri", "NaN"]).starts_with("--ri:"));
        assert!(e(&["t", "--ri", "2", "--material", "cz"]).contains("not both"));
        assert!(e(&["t", "--material", "unobtainium"]).starts_with("--material:"));
        assert!(e(&["t", "--polarization", "maybe"]).contains("on or off"));
        assert!(e(&["t", "--head-shadow", "-3"]).starts_with("--head-shadow:"));
        assert!(e(&["t", "--head-shadow", "90"]).contains("[0, 60]"));
        assert!(e(&["t", "--verify", "lots"]).starts_with("--verify:"));
        for msg in [e(&["t", "--ri", "abc"]), e(&["t", "--verify", "0"])] {
            assert!(!msg.contains('\n'));
        }
        let s = settings(&args(&[
            "t",
            "--ri",
            "2.42",
            "--polarization",
            "off",
            "--head-shadow",
            "15",
        ]))
        .unwrap();
        assert_eq!(s.config.material.ri(500.0), 2.42);
        assert!(!s.config.trace.polarization && s.config.head_shadow_deg == 15.0);
        // The flag's default is the library's, and 0 switches the head shadow off.
        let head = |extra: &[&str]| settings(&args(extra)).unwrap().config.head_shadow_deg;
        assert_eq!(head(&["t"]), facetlab::metrics::DEFAULT_HEAD_SHADOW_DEG);
        assert_eq!(head(&["t", "--head-shadow", "0"]), 0.0);
        assert_eq!(
            settings(&args(&["t", "--verify", "1e6"])).unwrap().verify,
            Some(1_000_000)
        );
    }

    #[test]
    fn verify_adds_photon_estimates_and_bad_cuts_fail_first() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("s.json");
        let p = path.to_str().unwrap();
        run(&args(&["tolkowsky", "--verify", "3000", "--json", p])).unwrap();
        let j: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        for k in [
            "overhead_light_return",
            "brilliance",
            "brilliance_iso",
            "brilliance_cos",
        ] {
            let v = &j["verify"][k];
            assert_eq!(v["beam"].as_f64(), j[k].as_f64(), "{k}");
            let (ph, se, z) = (
                v["photon"].as_f64().unwrap(),
                v["stderr"].as_f64().unwrap(),
                v["z"].as_f64().unwrap(),
            );
            assert!(
                se > 0.0 && ((j[k].as_f64().unwrap() - ph) / se - z).abs() < 1e-9,
                "{k}: {v}"
            );
            assert_eq!(v["photons"].as_u64(), Some(3000));
        }
        // Refused while the command line is read, the line naming the flag.
        let e = line(&["tolkowsky", "--verify", "0"]);
        assert!(e.starts_with("--verify"), "{e}");
        let e = run(&args(&["no-such-preset"])).unwrap_err().to_string();
        assert!(e.contains("unknown preset"), "{e}");
    }

    #[test]
    fn table_and_json_have_the_documented_shape() {
        let cfg = ScoreConfig::default();
        let s = Scores {
            fire: 0.25,
            poses: vec![facetlab::metrics::PoseScore {
                tilt_deg: 10.0,
                azimuth_deg: 72.0,
                iso: 0.8,
                cos: 0.7,
            }],
            ..Default::default()
        };
        let one = score_json(&cfg, &[("tolkowsky".into(), s.clone())], &[], 0).unwrap();
        let v: serde_json::Value = serde_json::from_str(&one).unwrap();
        for k in [
            "overhead_light_return",
            "brilliance",
            "brilliance_iso",
            "brilliance_cos",
            "fire",
            "scintillation",
        ] {
            assert!(v[k].is_number(), "{k} in {one}");
        }
        for k in ["blue", "red", "green", "leak", "port"] {
            assert!(v["aset"][k].is_number(), "aset.{k}");
        }
        for k in ["tilt_deg", "azimuth_deg", "iso", "cos"] {
            assert!(v["poses"][0][k].is_number(), "poses[].{k}");
        }
        assert_eq!(v["cut"], "tolkowsky");
        assert_eq!(v["settings"]["material"], "diamond");
        assert!(v["settings"]["ri"].is_null());
        let two = score_json(
            &cfg,
            &[("a".into(), s.clone()), ("b".into(), s.clone())],
            &[],
            0,
        )
        .unwrap();
        let v: serde_json::Value = serde_json::from_str(&two).unwrap();
        assert_eq!(v["results"][1]["cut"], "b");
        assert_eq!(v["results"][0]["fire"], 0.25);
        assert!(v["results"][0].get("settings").is_none() && v["settings"].is_object());
        let t = score_table(
            &cfg,
            &[("tolkowsky".into(), s.clone()), ("gia-reference".into(), s)],
        );
        assert_eq!(t.lines().count(), 13);
        assert!(t.lines().nth(1).unwrap().contains("gia-reference") && t.contains("0.2500"));
    }

    #[test]
    fn run_writes_json_atomically() {
        let dir = std::env::temp_dir().join(format!("facetlab-score-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("s.json");
        run(&args(&[
            "tolkowsky",
            "--ri",
            "2.4",
            "--json",
            path.to_str().unwrap(),
        ]))
        .unwrap();
        let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
        assert_eq!(v["cut"], "Tolkowsky");
        assert!(v["fire"].as_f64().unwrap().abs() < 1e-9);
        assert_eq!(v["settings"]["ri"], 2.4);
        // A folder that does not exist: an error naming the file, nothing written.
        let bad = dir.join("missing").join("s.json");
        let e = run(&args(&[
            "tolkowsky",
            "--ri",
            "2.4",
            "--json",
            bad.to_str().unwrap(),
        ]))
        .unwrap_err();
        assert!(e.to_string().contains("s.json") && !bad.exists());
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn a_flagged_check_exits_1_and_the_json_never_overwrites_a_cut() {
        let check = |z: f64| Check {
            name: "brilliance".into(),
            beam: 0.5,
            photon: 0.5 - z * 0.01,
            stderr: 0.01,
            z,
        };
        assert_eq!(verdict(&[]), Exit::Ok);
        assert_eq!(verdict(&[vec![check(1.0), check(-3.9)]]), Exit::Ok);
        assert_eq!(
            verdict(&[vec![check(0.5)], vec![check(1.0), check(-SIGMA - 0.1)]]),
            Exit::Disagreement
        );
        let d = tempfile::tempdir().unwrap();
        let cut = d.path().join("t.toml");
        std::fs::write(&cut, "not read").unwrap();
        let c = cut.to_str().unwrap();
        // As the binary says it (cli::run spells every error by its flags).
        let e = super::flags::to_flags(run(&args(&[c, "--json", c])).unwrap_err()).to_string();
        assert!(e.starts_with("--json: ") && e.contains("overwrite"), "{e}");
        assert_eq!(std::fs::read_to_string(&cut).unwrap(), "not read");
    }

    #[test]
    fn colour_flags_reach_the_configuration_or_name_the_flag() {
        let s = settings(&args(&[
            "t",
            "--material",
            "ruby",
            "--colour-density",
            "0.5",
            "--size-mm",
            "8",
        ]))
        .unwrap();
        let c = s.config.material.colour.as_ref().unwrap();
        assert_eq!((c.name.as_str(), c.density), ("ruby", 0.5));
        assert_eq!(s.config.size, facetlab::optics::StoneSize::Length(8.0));
        let s = settings(&args(&["t", "--colour", "lab(40,30,-40)@10mm"])).unwrap();
        assert_eq!(s.config.material.name, "diamond");
        assert!(s.config.material.colour.is_some());
        // No colour flags: today's configuration.
        let s = settings(&args(&["t"])).unwrap();
        assert!(s.config.material.colour.is_none());
        assert_eq!(s.config.size, facetlab::optics::StoneSize::default());
        let e = line;
        assert!(e(&["t", "--colour", "blue"]).starts_with("--colour: `blue` is not a colour"));
        assert!(
            e(&["t", "--colour-density", "2"]).starts_with("--colour-density: there is no colour")
        );
        assert!(e(&["t", "--material", "ruby", "--colour-density", "x"])
            .starts_with("--colour-density: `x`"));
        assert!(e(&["t", "--size-mm", "0"]).starts_with("--size-mm:"));
        assert!(e(&["t", "--diameter-mm", "-1"]).starts_with("--diameter-mm:"));
    }
}
