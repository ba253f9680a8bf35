//! Issue 14: N-axis sweeps, shards run as separate processes and merged exactly, resume,
//! job-array environments, and batch scoring.

use super::{bad, ok};
use std::path::Path;
use std::process::Command;
use tempfile::tempdir;

/// A cheap objective: a fixed index (no spectral bands) without polarization.
const CONFIG: &str = r#"
name = "tiny"
[cut]
family = "round-brilliant"
[cut.params]
table = 0.57
crown_angle = 34.0
pavilion_angle = 41.0
[free]
crown_angle = [30.0, 38.0]
[score]
ri = 1.54
polarization = false
"#;

const AXES: [&str; 6] = [
    "--x",
    "crown_angle:33:34:1",
    "--y",
    "pavilion_angle:40:41:1",
    "--axis",
    "table:0.55:0.56:0.01",
];

fn sweep_args<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut v = vec!["sweep", "tiny.toml"];
    v.extend_from_slice(&AXES);
    v.extend_from_slice(extra);
    v.push("--quiet");
    v
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

#[test]
fn three_shards_in_three_processes_merge_to_one_run_and_resume() {
    let d = tempdir().unwrap();
    let p = d.path();
    std::fs::write(p.join("tiny.toml"), CONFIG).unwrap();
    ok(p, &sweep_args(&["--out", "one"]));
    let whole = read(&p.join("one/sweep.csv"));
    assert!(
        whole.starts_with(
            "crown_angle,pavilion_angle,table,brilliance,fire,scintillation,objective"
        ),
        "three axis columns: {whole}"
    );
    assert_eq!(whole.lines().count(), 1 + 8);
    assert!(
        whole.lines().nth(2).unwrap().starts_with("34,40,0.55,"),
        "first axis fastest"
    );
    // Three shards as separate processes, at the same time.
    let children: Vec<_> = (1..=3)
        .map(|k| {
            let shard = format!("{k}/3");
            Command::new(env!("CARGO_BIN_EXE_facetlab"))
                .args(sweep_args(&["--shard", &shard, "--out", "big"]))
                .current_dir(p)
                .stdout(std::process::Stdio::piped())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .unwrap()
        })
        .collect();
    for c in children {
        let out = c.wait_with_output().unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let rec: serde_json::Value =
        serde_json::from_str(&read(&p.join("big/shard-2-of-3/shard.json"))).unwrap();
    assert_eq!(rec["k"], 2);
    assert_eq!(rec["n"], 3);
    assert_eq!(rec["grid_size"], 8);
    assert_eq!(rec["indices_done"], serde_json::json!([1, 4, 7]));
    assert_eq!(rec["axes"][2]["key"], "table");
    ok(
        p,
        &[
            "merge",
            "big/shard-1-of-3",
            "big/shard-2-of-3",
            "big/shard-3-of-3",
            "-o",
            "merged",
        ],
    );
    assert_eq!(read(&p.join("merged/sweep.csv")), whole, "byte for byte");
    assert_eq!(
        std::fs::read(p.join("merged/sweep.png")).unwrap(),
        std::fs::read(p.join("one/sweep.png")).unwrap()
    );
    // Re-running a finished shard recomputes nothing.
    let rows = read(&p.join("big/shard-2-of-3/rows.csv"));
    let again = ok(p, &sweep_args(&["--shard", "2/3", "--out", "big"]));
    assert!(again.contains("resumed: 3 of 3 done"), "{again}");
    assert!(again.contains("computed 0;"), "{again}");
    let rec: serde_json::Value =
        serde_json::from_str(&read(&p.join("big/shard-2-of-3/shard.json"))).unwrap();
    assert_eq!(
        (rec["resumed"].as_u64(), rec["computed"].as_u64()),
        (Some(3), Some(0))
    );
    assert_eq!(read(&p.join("big/shard-2-of-3/rows.csv")), rows);
    // A row cut short by a hard kill is dropped and redone.
    let mut cut = rows.clone();
    cut.truncate(rows.len() - 10);
    std::fs::write(p.join("big/shard-2-of-3/rows.csv"), &cut).unwrap();
    let again = ok(p, &sweep_args(&["--shard", "2/3", "--out", "big"]));
    assert!(
        again.contains("resumed: 2 of 3 done") && again.contains("computed 1;"),
        "{again}"
    );
    ok(p, &["merge", "big", "-o", "merged2"]);
    assert_eq!(read(&p.join("merged2/sweep.csv")), whole);

    // A missing shard, a duplicated one, one of another sweep: exit 2, naming it.
    bad(
        p,
        &["merge", "big/shard-1-of-3", "big/shard-3-of-3", "-o", "m3"],
        &["shard 2/3", "missing"],
    );
    copy_dir(&p.join("big/shard-3-of-3"), &p.join("dup"));
    bad(
        p,
        &[
            "merge",
            "big/shard-1-of-3",
            "big/shard-2-of-3",
            "big/shard-3-of-3",
            "dup",
            "-o",
            "m4",
        ],
        &["big/shard-3-of-3", "dup", "both shard 3/3"],
    );
    std::fs::write(
        p.join("tiny.toml"),
        CONFIG.replace("ri = 1.54", "ri = 1.55"),
    )
    .unwrap();
    ok(p, &sweep_args(&["--shard", "3/3", "--out", "other"]));
    bad(
        p,
        &[
            "merge",
            "big/shard-1-of-3",
            "big/shard-2-of-3",
            "other/shard-3-of-3",
            "-o",
            "m5",
        ],
        &["other/shard-3-of-3", "another sweep", "config hash"],
    );
    bad(p, &["merge", "one", "-o", "m6"], &["one", "no shard.json"]);
    for m in ["m3", "m4", "m5", "m6"] {
        assert!(!p.join(m).exists(), "{m} written");
    }
    // A shard folder of another sweep is not resumed into.
    bad(
        p,
        &sweep_args(&["--shard", "3/3", "--out", "big"]),
        &["--out", "another sweep"],
    );
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
    }
}

#[test]
fn job_array_environments_pick_the_shard() {
    let d = tempdir().unwrap();
    let p = d.path();
    std::fs::write(p.join("tiny.toml"), CONFIG).unwrap();
    let run_with = |extra: &[&str], env: &[(&str, &str)]| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_facetlab"));
        c.args(sweep_args(extra)).current_dir(p);
        for v in [
            "SLURM_ARRAY_TASK_ID",
            "SLURM_ARRAY_TASK_MIN",
            "SLURM_ARRAY_TASK_COUNT",
            "SLURM_ARRAY_TASK_STEP",
            "JOB_COMPLETION_INDEX",
            "JOB_COMPLETION_COUNT",
        ] {
            c.env_remove(v);
        }
        c.envs(env.iter().copied()).output().unwrap()
    };
    let run = |env: &[(&str, &str)]| run_with(&["--out", "arr"], env);
    let out = run(&[
        ("SLURM_ARRAY_TASK_ID", "11"),
        ("SLURM_ARRAY_TASK_MIN", "10"),
        ("SLURM_ARRAY_TASK_COUNT", "4"),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("shard 2/4 (from SLURM_ARRAY_TASK_ID=11"),
        "{stdout}"
    );
    let rec: serde_json::Value =
        serde_json::from_str(&read(&p.join("arr/shard-2-of-4/shard.json"))).unwrap();
    assert_eq!(rec["indices_done"], serde_json::json!([1, 5]));
    let out = run(&[("JOB_COMPLETION_INDEX", "3"), ("JOB_COMPLETION_COUNT", "4")]);
    assert!(out.status.success());
    assert!(p.join("arr/shard-4-of-4/rows.csv").is_file());
    let out = run(&[("JOB_COMPLETION_INDEX", "3")]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("JOB_COMPLETION_COUNT"));
    // `--shard off`: an ordinary sweep inside an array job.
    let out = run_with(
        &["--shard", "off", "--out", "plain"],
        &[("JOB_COMPLETION_INDEX", "3"), ("JOB_COMPLETION_COUNT", "4")],
    );
    assert!(out.status.success());
    assert_eq!(read(&p.join("plain/sweep.csv")).lines().count(), 1 + 8);
    bad(p, &sweep_args(&["--shard", "5/4"]), &["--shard", "K/N"]);
}

#[test]
fn batch_scores_every_line_records_errors_and_resumes() {
    let d = tempdir().unwrap();
    let p = d.path();
    std::fs::write(
        p.join("cuts.txt"),
        "# three cuts and a typo\n\ntolkowsky\nno-such-preset\n  tolkowsky --set crown_angle=33.5\n",
    )
    .unwrap();
    let args = [
        "score",
        "--batch",
        "cuts.txt",
        "--jsonl",
        "out.jsonl",
        "--ri",
        "1.54",
        "--polarization",
        "off",
    ];
    let first = ok(p, &args);
    assert!(first.contains("scored 2, errors 1"), "{first}");
    let text = read(&p.join("out.jsonl"));
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 3);
    assert_eq!(lines[0]["line"], 3);
    assert_eq!(lines[0]["cut"], "Tolkowsky");
    for k in [
        "brilliance",
        "fire",
        "scintillation",
        "overhead_light_return",
    ] {
        assert!(lines[0][k].is_number(), "{k}");
    }
    assert!(lines[0]["aset"]["red"].is_number() && lines[0]["poses"].is_array());
    assert_eq!(lines[1]["line"], 4);
    assert_eq!(lines[1]["cut"], "no-such-preset");
    assert!(lines[1]["error"]
        .as_str()
        .unwrap()
        .contains("unknown preset"));
    assert_eq!(lines[2]["line"], 5);
    assert_ne!(
        lines[2]["brilliance"], lines[0]["brilliance"],
        "--set reached the cut"
    );
    // Re-run: nothing recomputed, nothing added.
    let again = ok(p, &args);
    assert!(
        again.contains("resumed: 3 of 3 done") && again.contains("scored 0"),
        "{again}"
    );
    assert_eq!(read(&p.join("out.jsonl")), text);
    // A last line cut short is redone.
    std::fs::write(p.join("out.jsonl"), &text[..text.len() - 7]).unwrap();
    let again = ok(p, &args);
    assert!(
        again.contains("resumed: 2 of 3 done") && again.contains("scored 1"),
        "{again}"
    );
    assert_eq!(read(&p.join("out.jsonl")), text);
    // Shards: ordinals 0, 1, 2 of the cut lines; 2/2 gets the typo only.
    let mut sharded = args.to_vec();
    sharded[4] = "two.jsonl";
    sharded.extend(["--shard", "2/2"]);
    let out = ok(p, &sharded);
    assert!(
        out.contains("shard 2/2") && out.contains("errors 1"),
        "{out}"
    );
    assert_eq!(read(&p.join("two.jsonl")).lines().count(), 1);
    bad(p, &["score", "--batch", "cuts.txt"], &["--jsonl"]);
}

#[test]
fn sigterm_stops_a_shard_which_resumes_where_it_stopped() {
    use std::process::Stdio;
    use std::time::{Duration, Instant};
    let d = tempdir().unwrap();
    let p = d.path();
    std::fs::write(p.join("tiny.toml"), CONFIG).unwrap();
    let args = [
        "sweep",
        "tiny.toml",
        "--x",
        "crown_angle:30:38:0.5",
        "--y",
        "pavilion_angle:39.5:42.5:0.5",
        "--shard",
        "1/1",
        "--out",
        "s",
        "--quiet",
    ];
    let mut child = Command::new(env!("CARGO_BIN_EXE_facetlab"))
        .args(args)
        .current_dir(p)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Rows are appended only after the handler is installed: wait for two.
    let rows = p.join("s/shard-1-of-1/rows.csv");
    let start = Instant::now();
    while std::fs::read_to_string(&rows).map_or(0, |t| t.lines().count()) < 3 {
        assert!(child.try_wait().unwrap().is_none(), "the shard ended early");
        assert!(start.elapsed() < Duration::from_secs(120), "no rows");
        std::thread::sleep(Duration::from_millis(10));
    }
    // SAFETY: kill with a valid signal on our own child's pid.
    assert_eq!(unsafe { libc::kill(child.id() as i32, libc::SIGTERM) }, 0);
    let out = child.wait_with_output().unwrap();
    assert_eq!(
        out.status.code(),
        Some(130),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rec: serde_json::Value =
        serde_json::from_str(&read(&p.join("s/shard-1-of-1/shard.json"))).unwrap();
    let done = rec["done"].as_u64().unwrap();
    assert_eq!(rec["complete"], false);
    assert!((2..119).contains(&done), "{rec}");
    assert_eq!(read(&rows).lines().count() as u64, 1 + done);
    let again = ok(p, &args);
    assert!(
        again.contains(&format!("resumed: {done} of 119 done")),
        "{again}"
    );
    assert!(
        again.contains(&format!("computed {};", 119 - done)),
        "{again}"
    );
    ok(p, &["merge", "s", "-o", "m.csv"]);
    let merged = read(&p.join("m.csv"));
    assert_eq!(merged.lines().count(), 1 + 119);
    assert!(merged.lines().nth(1).unwrap().starts_with("30,39.5,"));
}
