//! "Scores you can trust": outputs never overwrite inputs, the exit status says how a command
//! ended, and a one-parameter sweep writes a profile.

use super::{bad, files, ok};
use tempfile::tempdir;

#[test]
fn an_output_equal_to_an_input_is_refused_before_any_work() {
    let d = tempdir().unwrap();
    let p = d.path();
    ok(p, &["generate", "tolkowsky", "-o", "t.toml"]);
    let cut = std::fs::read_to_string(p.join("t.toml")).unwrap();
    std::fs::create_dir(p.join("sub")).unwrap();
    // The same file, also when spelled through another folder.
    bad(
        p,
        &["score", "t.toml", "--json", "t.toml"],
        &["--json", "t.toml", "overwrite"],
    );
    bad(
        p,
        &["score", "tolkowsky", "t.toml", "--json", "sub/../t.toml"],
        &["--json", "overwrite"],
    );
    bad(
        p,
        &["generate", "t.toml", "--set", "table=0.55", "-o", "t.toml"],
        &["-o", "overwrite"],
    );
    bad(
        p,
        &["trace", "t.toml", "--photons", "1000", "--json", "./t.toml"],
        &["--json", "overwrite"],
    );
    assert_eq!(std::fs::read_to_string(p.join("t.toml")).unwrap(), cut);
    assert_eq!(files(p), ["sub", "t.toml"]);
    // A sweep's CSV would replace the config it reads (`--out c.png` → c.csv, c.png, c.svg).
    std::fs::write(
        p.join("c.csv"),
        "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30.0, 38.0]\n",
    )
    .unwrap();
    std::fs::copy(p.join("c.csv"), p.join("c.toml")).unwrap();
    bad(
        p,
        &[
            "sweep",
            "c.toml",
            "--x",
            "crown_angle:30:38:4",
            "--out",
            "c.toml",
        ],
        &["--out", "overwrite"],
    );
    // An output folder that cannot be made is refused before the search, naming it.
    bad(
        p,
        &["optimize", "c.toml", "--out", "t.toml/run", "--no-verify"],
        &["t.toml", "not a folder"],
    );
    // A folder that is not empty needs --force.
    bad(
        p,
        &["optimize", "c.toml", "--out", "sub/..", "--no-verify"],
        &["--out", "not empty", "--force"],
    );
    assert_eq!(files(p), ["c.csv", "c.toml", "sub", "t.toml"]);
}

/// One overwrite rule for every command that writes a file: an existing file is replaced only
/// with --force (as render, report and retarget always did), and an input never, even with it.
#[test]
fn an_existing_output_is_replaced_only_with_force() {
    let d = tempdir().unwrap();
    let p = d.path();
    ok(p, &["generate", "tolkowsky", "-o", "t.toml"]);
    for (args, flag) in [
        (vec!["generate", "princess", "-o", "o.asc"], "-o"),
        (vec!["score", "princess", "--json", "o.json"], "--json"),
        (
            vec!["trace", "princess", "--photons", "1000", "--json", "o.json"],
            "--json",
        ),
    ] {
        let out = args[args.len() - 1];
        std::fs::write(p.join(out), "mine").unwrap();
        bad(p, &args, &[flag, out, "--force"]);
        assert_eq!(std::fs::read_to_string(p.join(out)).unwrap(), "mine");
        let forced: Vec<&str> = args.iter().copied().chain(["--force"]).collect();
        ok(p, &forced);
        assert_ne!(std::fs::read_to_string(p.join(out)).unwrap(), "mine");
        std::fs::remove_file(p.join(out)).unwrap();
    }
    // An input stays an input with --force.
    let cut = std::fs::read_to_string(p.join("t.toml")).unwrap();
    bad(
        p,
        &["generate", "t.toml", "-o", "t.toml", "--force"],
        &["-o", "overwrite"],
    );
    assert_eq!(std::fs::read_to_string(p.join("t.toml")).unwrap(), cut);
}

#[test]
fn a_sweep_without_y_writes_a_profile_csv_and_chart() {
    let d = tempdir().unwrap();
    let p = d.path();
    std::fs::write(
        p.join("prof.toml"),
        "name = \"prof\"\n[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30.0, 38.0]\n",
    )
    .unwrap();
    let out = ok(
        p,
        &[
            "sweep",
            "prof.toml",
            "--x",
            "crown_angle:31:35:2",
            "--quiet",
        ],
    );
    assert!(out.contains("highest brilliance"), "{out}");
    let dir = p.join("results/sweep-prof-crown_angle");
    let csv = std::fs::read_to_string(dir.join("sweep.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert!(
        lines[0].starts_with("crown_angle,brilliance,fire,scintillation,objective"),
        "{}",
        lines[0]
    );
    assert_eq!(lines.len(), 4, "{csv}");
    for (line, x) in lines[1..].iter().zip(["31", "33", "35"]) {
        let cols: Vec<&str> = line.split(',').collect();
        assert_eq!(cols[0], x);
        let b: f64 = cols[1].parse().unwrap();
        assert!(b > 0.0 && b < 1.0, "brilliance {b}");
    }
    let png = std::fs::read(dir.join("sweep.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    assert!(dir.join("sweep.svg").is_file());
    bad(
        p,
        &[
            "sweep",
            "prof.toml",
            "--x",
            "crown_angle:31:35:2",
            "--run",
            "results",
        ],
        &["--run", "--y"],
    );
}

/// Whether process `pid` catches signal `sig` (its `SigCgt` mask in /proc).
#[cfg(target_os = "linux")]
fn catches(pid: u32, sig: i32) -> bool {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("SigCgt:"))
        .and_then(|m| u64::from_str_radix(m.trim(), 16).ok())
        .is_some_and(|m| m & (1 << (sig - 1)) != 0)
}

#[cfg(target_os = "linux")]
#[test]
fn sigterm_stops_optimize_which_writes_its_folder_and_exits_130() {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    let d = tempdir().unwrap();
    let p = d.path();
    std::fs::write(
        p.join("long.toml"),
        "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30.0, 38.0]\npavilion_angle = [39.5, 42.5]\n[method]\nname = \"particle-swarm\"\nparticles = 4\nmax_iterations = 1000000\nmax_evaluations = 100000000\n",
    )
    .unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_facetlab"))
        .args([
            "optimize",
            "long.toml",
            "--out",
            "run",
            "--no-verify",
            "--quiet",
        ])
        .current_dir(p)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Send the signal once the handler is installed (not after a guessed delay); the bounds
    // below only keep a broken build from hanging the suite.
    let start = Instant::now();
    while !catches(child.id(), libc::SIGTERM) {
        assert!(child.try_wait().unwrap().is_none(), "optimize ended early");
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "no SIGTERM handler"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(!p.join("run").exists(), "the folder is made only to write");
    // SAFETY: kill with a valid signal on our own child's pid.
    assert_eq!(unsafe { libc::kill(child.id() as i32, libc::SIGTERM) }, 0);
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > Duration::from_secs(600) {
            let _ = child.kill();
            panic!("optimize did not stop after SIGTERM");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let mut err = String::new();
    std::io::Read::read_to_string(child.stderr.as_mut().unwrap(), &mut err).unwrap();
    assert_eq!(status.code(), Some(130), "{err}");
    assert!(err.contains("interrupted"), "{err}");
    assert!(p.join("run/history.csv").is_file() && p.join("run/report.md").is_file());
    let md = std::fs::read_to_string(p.join("run/report.md")).unwrap();
    assert!(md.contains("interrupted"), "{md}");
}
