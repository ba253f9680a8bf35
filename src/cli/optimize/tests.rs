use super::run::optimize_exit;
use super::sweep::{map_title, run_sweep_env};
use super::*;
use crate::cli::outputs::Exit;
use facetlab::cut::Cut;
use facetlab::error::Result;
use facetlab::optimize::Config;
use facetlab::optimize::ScoreSet;
use facetlab::sweep::{Axis, Grid, SweepScore};
use std::sync::atomic::Ordering;

fn bump(cut: &Cut) -> Result<ScoreSet> {
    let (c, p) = (cut.params["crown_angle"], cut.params["pavilion_angle"]);
    Ok(ScoreSet::new(
        (-((c - 34.5) / 3.0).powi(2) - (p - 40.8).powi(2)).exp(),
        0.0,
        0.0,
    ))
}

fn bumps(_: &Config) -> Scorers {
    (Box::new(bump), None)
}

#[test]
fn optimize_and_sweep_write_their_files() {
    let _one = crate::cli::interrupt::one_at_a_time();
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("small.toml");
    std::fs::write(
        &cfg,
        "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30.0, 38.0]\npavilion_angle = [39.5, 42.5]\n[method]\nstarts = 2\nmax_evaluations = 120\n",
    )
    .unwrap();
    let out = dir.path().join("run");
    let a = OptimizeArgs {
        config: cfg.clone(),
        out: Some(out.clone()),
        seed: Some(9),
        head_shadow: Some(0.0),
        no_verify: false,
        quiet: true,
        force: false,
    };
    assert_eq!(run_optimize(&a, &bumps).unwrap(), Exit::Ok);
    assert!(out.join("report.md").is_file());
    let used = std::fs::read_to_string(out.join("config.toml")).unwrap();
    assert!(used.contains("seed = 9"));
    // --head-shadow overrides the config's (default 15) and is written back with it.
    assert!(used.contains("head_shadow = 0"), "{used}");
    let s = SweepArgs {
        config: cfg.clone(),
        x: Some("crown_angle:30:38:1".into()),
        y: Some("pavilion_angle:39.5:42.5:0.5".into()),
        axis: vec![],
        map: None,
        at: vec![],
        shard: None,
        score: SweepScore::Objective,
        run: Some(out.clone()),
        out: Some(dir.path().join("map.png")),
        quiet: true,
    };
    run_sweep(&s, &bumps).unwrap();
    assert!(dir.path().join("map.csv").is_file() && dir.path().join("map.svg").is_file());
    let bad = SweepArgs {
        run: Some(dir.path().join("nope")),
        ..s
    };
    let e = run_sweep(&bad, &bumps).unwrap_err().to_string();
    assert!(e.starts_with("--run:"), "{e}");
    let e = run_optimize(
        &OptimizeArgs {
            config: dir.path().join("missing.toml"),
            out: None,
            seed: None,
            head_shadow: None,
            no_verify: true,
            quiet: true,
            force: false,
        },
        &bumps,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("missing.toml: no such file"), "{e}");

    // The folder of the first run is not empty: refused, unless --force.
    let e = run_optimize(&a, &bumps).unwrap_err().to_string();
    assert!(e.starts_with("--out: ") && e.contains("--force"), "{e}");
    // A folder holding the config as `config.toml` is refused even with --force.
    let inside = OptimizeArgs {
        config: out.join("config.toml"),
        force: true,
        ..a
    };
    let before = std::fs::read_to_string(out.join("config.toml")).unwrap();
    let e = run_optimize(&inside, &bumps).unwrap_err().to_string();
    assert!(e.starts_with("--out: ") && e.contains("overwrite"), "{e}");
    assert_eq!(
        std::fs::read_to_string(out.join("config.toml")).unwrap(),
        before
    );

    // A signal during the search: the folder is still written and the exit status is 130.
    // (Here, not in a test of its own: the stop flag is one per process.)
    fn pressing(cut: &Cut) -> Result<ScoreSet> {
        static CALLS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        if CALLS.fetch_add(1, Ordering::SeqCst) >= 10 {
            STOP.store(true, Ordering::SeqCst);
        }
        bump(cut)
    }
    let stopped = dir.path().join("stopped");
    let a = OptimizeArgs {
        out: Some(stopped.clone()),
        force: true,
        ..inside
    };
    let a = OptimizeArgs {
        config: cfg.clone(),
        ..a
    };
    fn pressings(_: &Config) -> Scorers {
        (Box::new(pressing), None)
    }
    let e = run_optimize(&a, &pressings).unwrap();
    assert_eq!(e, Exit::Interrupted);
    assert_eq!(e.code(), 130);
    assert!(stopped.join("history.csv").is_file() && stopped.join("report.md").is_file());
    assert_eq!(optimize_exit(false), Exit::Ok);
}

/// A small config in `dir` (a round brilliant, its crown angle free) and a sweep of it over
/// the crown angle (30–38° by 2) into `dir/out`, brilliance scored, quiet.
fn small_sweep(dir: &std::path::Path, out: &str) -> (std::path::PathBuf, SweepArgs) {
    let cfg = dir.join("small.toml");
    std::fs::write(
        &cfg,
        "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30.0, 38.0]\n",
    )
    .unwrap();
    let s = SweepArgs {
        config: cfg.clone(),
        x: Some("crown_angle:30:38:2".into()),
        y: None,
        axis: vec![],
        map: None,
        at: vec![],
        shard: None,
        score: SweepScore::BRILLIANCE,
        run: None,
        out: Some(dir.join(out)),
        quiet: true,
    };
    (cfg, s)
}

#[test]
fn a_profile_writes_one_row_per_x_and_outputs_never_overwrite_inputs() {
    let _one = crate::cli::interrupt::one_at_a_time();
    let dir = tempfile::tempdir().unwrap();
    let (cfg, s) = small_sweep(dir.path(), "prof");
    assert_eq!(run_sweep(&s, &bumps).unwrap(), Exit::Ok);
    let csv = std::fs::read_to_string(dir.path().join("prof/sweep.csv")).unwrap();
    assert!(csv.starts_with("crown_angle,brilliance,fire,scintillation,objective\n30,"));
    assert_eq!(csv.lines().count(), 1 + 5);
    assert!(dir.path().join("prof/sweep.png").is_file());
    // --run needs a map.
    let e = run_sweep(
        &SweepArgs {
            run: Some(dir.path().into()),
            ..s.clone()
        },
        &bumps,
    )
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("--run: ") && e.contains("--y"), "{e}");
    // `--out small.csv` beside `small.toml` is fine; `--out small.toml` is not.
    let e = run_sweep(
        &SweepArgs {
            out: Some(cfg.clone()),
            ..s.clone()
        },
        &bumps,
    )
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("--out: ") && e.contains("overwrite"), "{e}");
    assert!(std::fs::read_to_string(&cfg).unwrap().starts_with("[cut]"));
}

#[test]
fn three_axes_map_any_two_held_where_asked() {
    let _one = crate::cli::interrupt::one_at_a_time();
    let dir = tempfile::tempdir().unwrap();
    let (cfg, s) = small_sweep(dir.path(), "three");
    let s = SweepArgs {
        y: Some("pavilion_angle:40:41:0.5".into()),
        axis: vec!["table:0.55:0.58:0.01".into()],
        map: Some("table,crown_angle".into()),
        at: vec!["pavilion_angle=40.9".into()],
        ..s
    };
    let no_env = |_: &str| None;
    assert_eq!(run_sweep_env(&s, &bumps, &no_env).unwrap(), Exit::Ok);
    let csv = std::fs::read_to_string(dir.path().join("three/sweep.csv")).unwrap();
    assert!(csv.starts_with("crown_angle,pavilion_angle,table,brilliance,"));
    assert_eq!(csv.lines().count(), 1 + 5 * 3 * 4);
    let grid = Grid::new(vec![
        Axis::parse("--x", "crown_angle:30:38:2", &Config::load(&cfg).unwrap()).unwrap(),
        Axis::parse(
            "--y",
            "pavilion_angle:40:41:0.5",
            &Config::load(&cfg).unwrap(),
        )
        .unwrap(),
        Axis::parse(
            "--axis",
            "table:0.55:0.58:0.01",
            &Config::load(&cfg).unwrap(),
        )
        .unwrap(),
    ])
    .unwrap();
    let spec = facetlab::sweep::MapSpec::new(&grid, s.map.as_deref(), &s.at).unwrap();
    assert_eq!(
        (spec.axes.clone(), spec.fixed.clone()),
        (vec![2, 0], vec![2, 2, 1]),
        "a tie at the middle (0.565) goes to the lower value"
    );
    let names = Names {
        name: "n".into(),
        family: "round-brilliant".into(),
        file: "small.toml".into(),
    };
    assert_eq!(
        map_title(&names, &grid, &SweepScore::FIRE, &spec),
        "fire of round-brilliant over table and crown_angle at pavilion_angle = 41 (others as in small.toml)"
    );
    for (change, want) in [
        (
            SweepArgs {
                map: Some("table,girdle".into()),
                ..s.clone()
            },
            "--map: `girdle` is not an axis",
        ),
        (
            SweepArgs {
                at: vec!["table=0.9".into()],
                ..s.clone()
            },
            "--at: table = 0.9 is outside",
        ),
        (
            SweepArgs {
                axis: vec!["crown_angle:30:31:1".into()],
                ..s.clone()
            },
            "sweeps `crown_angle` on two axes",
        ),
        (
            SweepArgs {
                x: None,
                ..s.clone()
            },
            "--y: needs --x",
        ),
    ] {
        let e = crate::cli::flags::to_flags(run_sweep_env(&change, &bumps, &no_env).unwrap_err())
            .to_string();
        assert!(e.contains(want), "{e}");
    }
    // A bad --shard is refused while the command line is read, in the same words.
    let e = crate::cli::flags::shard("0/2").unwrap_err().to_string();
    assert!(e.contains("--shard: `0/2` is not K/N"), "{e}");
}
