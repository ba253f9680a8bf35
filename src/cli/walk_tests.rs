//! Every flag of every command, walked through clap's own list of them (so a new flag is
//! walked too, or the test says it has no entry): a value no flag takes is refused with one
//! line naming the flag (the binary's exit code 2), a number far out of range is refused in a
//! short line, and every flag of `score`, with CUT arguments and with `--batch`, changes what
//! is written or is refused.

use super::{run, Cli};
use clap::{CommandFactory, FromArgMatches};
use std::path::Path;

/// A command line as the binary parses it (negative numbers are values, as `main.rs` says),
/// run: `Ok`, or the line the binary prints for it (clap's own errors by their first line).
fn line_of(args: &[String]) -> Result<(), String> {
    let cmd = Cli::command().mut_subcommands(|s| s.allow_negative_numbers(true));
    let argv = std::iter::once("facetlab".to_string()).chain(args.iter().cloned());
    let cli = cmd
        .try_get_matches_from(argv)
        .and_then(|m| Cli::from_arg_matches(&m))
        .map_err(|e| {
            super::flags::refused_value(&e).unwrap_or_else(|| {
                let text = e.render().to_string();
                let first = text.lines().next().unwrap_or_default();
                first.trim_start_matches("error: ").to_string()
            })
        })?;
    run(cli).map(|_| ()).map_err(|e| e.to_string())
}

/// The rest of a command line around a walked flag (its CUT, a quick run, outputs in `d`).
fn base(cmd: &str, d: &Path) -> String {
    let d = d.display();
    match cmd {
        "generate" => format!("tolkowsky -o {d}/g.asc"),
        "design" => format!("--from tolkowsky -o {d}/d.toml"),
        "info" => "tolkowsky".into(),
        "sheet" => format!("tolkowsky -o {d}/s.svg"),
        "trace" => "tolkowsky --photons 64".into(),
        "score" => "tolkowsky".into(),
        "optimize" => format!("{d}/c.toml --out {d}/opt"),
        "sweep" => format!("{d}/c.toml --x crown_angle:31:33:1 --out {d}/sw"),
        "report" => format!("tolkowsky -o {d}/r.html"),
        "retarget" => format!("tolkowsky --ri 1.54 -o {d}/rt.asc"),
        "plan" => format!("octahedron --size-mm 6 -o {d}/plan"),
        "merge" => format!("{d}/shards -o {d}/merged"),
        "render" => format!("tolkowsky -o {d}/r.png --size 16"),
        _ => String::new(),
    }
}

/// `base` with `flag` (and its value) left out, then `flag VALUE` and `extra`.
fn line(cmd: &str, d: &Path, flag: &str, value: &str, extra: &[&str]) -> Vec<String> {
    let mut out = vec![cmd.to_string()];
    let words: Vec<String> = base(cmd, d).split_whitespace().map(String::from).collect();
    let mut i = 0;
    while i < words.len() {
        if words[i] == flag || extra.contains(&words[i].as_str()) {
            i += 2;
            continue;
        }
        out.push(words[i].clone());
        i += 1;
    }
    out.extend([flag.to_string(), value.to_string()]);
    out.extend(extra.iter().map(|s| s.to_string()));
    out
}

/// Flags whose value is any text (a file to write, a title): no value is garbage to them.
const ANY_TEXT: &[(&str, &str)] = &[
    ("generate", "-o"),
    ("design", "-o"),
    ("sheet", "-o"),
    ("trace", "--json"),
    ("trace", "--plots"),
    ("score", "--json"),
    ("optimize", "--out"),
    ("sweep", "--out"),
    ("report", "--title"),
    ("retarget", "-o"),
    ("plan", "-o"),
    ("merge", "-o"),
    ("render", "--json"),
];

/// Flags refused only beside another: the flags that make the walked flag's value read.
const BESIDE: &[(&str, &str, &[&str])] = &[
    ("render", "--view", &["--light", "tent"]),
    ("render", "--distance", &["--light", "tent"]),
    ("render", "--ground", &["--light", "tent"]),
    (
        "render",
        "--ground-gap",
        &["--light", "tent", "--ground", "white"],
    ),
    ("render", "--light-rotation", &["--light", "tent"]),
    ("render", "--turn", &["--light", "tent"]),
    ("render", "--tone", &["--light", "tent"]),
    ("render", "--hdr-out", &["--light", "tent"]),
    ("render", "--bands", &["--light", "tent"]),
    ("render", "--colour-e", &["--material", "sapphire"]),
    ("render", "--optic-axis", &["--material", "sapphire"]),
    ("score", "--colour-e", &["--material", "sapphire"]),
    ("score", "--optic-axis", &["--material", "sapphire"]),
    ("trace", "--colour-e", &["--material", "sapphire"]),
    ("trace", "--optic-axis", &["--material", "sapphire"]),
    ("score", "--jsonl", &[]),
];

/// Every value-taking flag of every command, by its spelling (`--x`, or `-o` where it has
/// a short one).
fn flags() -> Vec<(String, String)> {
    let cmd = Cli::command();
    let mut out = Vec::new();
    for sub in cmd.get_subcommands() {
        for a in sub.get_arguments() {
            if a.is_positional() || !a.get_action().takes_values() {
                continue;
            }
            let flag = match (a.get_short(), a.get_long()) {
                (Some(c), _) => format!("-{c}"),
                (None, Some(l)) => format!("--{l}"),
                _ => continue,
            };
            out.push((sub.get_name().to_string(), flag));
        }
    }
    out
}

/// A tiny optimization config, for `optimize` and `sweep`.
const CONFIG: &str = "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30, 36]\n[score]\nri = 1.54\npolarization = false\n[method]\nstarts = 1\nmax_evaluations = 2\n[verify]\nwinners = 0\n";

/// Whether `line` spells a number in more than 20 digits (1e308 written out).
fn digits(line: &str) -> bool {
    line.split(|c: char| !c.is_ascii_digit())
        .any(|run| run.len() > 20)
}

#[test]
fn a_value_no_flag_takes_is_refused_in_one_line_naming_it() {
    let _one = crate::cli::interrupt::one_at_a_time();
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("c.toml"), CONFIG).unwrap();
    // A sweep's shards, for `merge`.
    let shards = d.path().join("shards").display().to_string();
    let c = d.path().join("c.toml").display().to_string();
    line_of(
        &[
            "sweep",
            &c,
            "--x",
            "crown_angle:31:33:1",
            "--shard",
            "1/1",
            "--out",
            &shards,
        ]
        .map(String::from),
    )
    .unwrap();
    let mut wrong = Vec::new();
    for (cmd, flag) in flags() {
        if ANY_TEXT.contains(&(cmd.as_str(), flag.as_str())) {
            continue;
        }
        let extra: &[&str] = BESIDE
            .iter()
            .find(|(c, f, _)| *c == cmd && *f == flag)
            .map_or(&[], |(_, _, e)| e);
        // Garbage, and numbers past any range (their digits are never spelled out).
        for value in ["zzz", "1e308", "-1e308"] {
            let args = line(&cmd, d.path(), &flag, value, extra);
            match line_of(&args) {
                Ok(()) => wrong.push(format!("{}: taken", args.join(" "))),
                Err(e) => {
                    // Named by its flag, or a file by its name.
                    let named = e.contains(flag.as_str()) || e.starts_with(&format!("{value}: "));
                    if e.contains('\n') || digits(&e) || !named {
                        wrong.push(format!("{}: {e}", args.join(" ")));
                    }
                }
            }
        }
    }
    // Numbers too small for a range that starts at 0, shown in their short form.
    for (cmd, flag, value, extra) in [
        ("render", "--distance", "1e-300", &["--light", "tent"][..]),
        ("sweep", "--x", "crown_angle:31:33:1e-300", &[][..]),
        ("render", "--view", "1e-300@1e300", &["--light", "tent"][..]),
        (
            "score",
            "--optic-axis",
            "45@1e300",
            &["--material", "sapphire"][..],
        ),
    ] {
        let args = line(cmd, d.path(), flag, value, extra);
        match line_of(&args) {
            Ok(()) => wrong.push(format!("{}: taken", args.join(" "))),
            Err(e) if digits(&e) || !e.contains(flag) => {
                wrong.push(format!("{}: {e}", args.join(" ")))
            }
            Err(_) => {}
        }
    }
    assert!(
        wrong.is_empty(),
        "{} flags not refused in a short line naming them:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
    // Nothing written by a refused command.
    let left: Vec<_> = std::fs::read_dir(d.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    let mut left = left;
    left.sort();
    assert_eq!(left, ["c.toml", "shards"]);
}

/// Each flag of `score` with a value that should change the scores (and the flags it needs
/// beside it to mean anything), or `None` where the flag is not a score setting.
const SCORE_VALUES: &[(&str, Option<&str>, &[&str])] = &[
    ("--material", Some("sapphire"), &[]),
    ("--ri", Some("1.6"), &[]),
    ("--colour", Some("#3050c0"), &[]),
    ("--colour-density", Some("3"), &["--material", "ruby"]),
    ("--diameter-mm", Some("12"), &["--material", "ruby"]),
    ("--size-mm", Some("12"), &["--material", "ruby"]),
    ("--birefringence", Some("off"), &["--material", "sapphire"]),
    ("--optic-axis", Some("90@30"), &["--material", "sapphire"]),
    (
        "--colour-e",
        Some("#30c050"),
        &["--material", "blue-sapphire"],
    ),
    ("--polarization", Some("off"), &[]),
    ("--head-shadow", Some("20"), &[]),
    ("--set", Some("crown_angle=30"), &[]),
    // Outputs and modes: what they write is checked by their own tests.
    ("--batch", None, &[]),
    ("--jsonl", None, &[]),
    ("--shard", None, &[]),
    ("--json", None, &[]),
    ("--verify", None, &[]),
];

/// `score`'s scores of one cut under `flags`: through `--json`, or the one line of
/// `--batch`'s JSON Lines; `Err` the refusal.
fn scores(d: &Path, batch: bool, flags: &[&str]) -> Result<serde_json::Value, String> {
    let n = std::fs::read_dir(d).unwrap().count();
    let out = d.join(format!("out-{n}.json"));
    let mut args: Vec<String> = vec!["score".into()];
    if batch {
        let list = d.join(format!("cuts-{n}.txt"));
        std::fs::write(&list, "tolkowsky\n").unwrap();
        args.extend(["--batch".into(), list.display().to_string()]);
        args.extend(["--jsonl".into(), out.display().to_string()]);
    } else {
        args.extend([
            "tolkowsky".into(),
            "--json".into(),
            out.display().to_string(),
        ]);
    }
    args.extend(flags.iter().map(|s| s.to_string()));
    line_of(&args)?;
    let text = std::fs::read_to_string(&out).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(text.trim()).unwrap();
    if let Some(e) = v.get("error") {
        return Err(e.to_string());
    }
    // The scores alone: not the settings as understood, nor the line and cut named.
    let m = v.as_object_mut().unwrap();
    for k in ["settings", "line", "input", "cut"] {
        m.remove(k);
    }
    Ok(v)
}

#[test]
fn every_flag_of_score_changes_the_scores_or_is_refused_with_cuts_and_with_a_batch() {
    let cmd = Cli::command();
    let score = cmd.find_subcommand("score").unwrap();
    for a in score.get_arguments() {
        if let (false, Some(l)) = (a.is_positional(), a.get_long()) {
            let flag = format!("--{l}");
            assert!(
                SCORE_VALUES.iter().any(|(f, _, _)| *f == flag) || !a.get_action().takes_values(),
                "{flag}: a flag of score with no value in SCORE_VALUES"
            );
        }
    }
    let d = tempfile::tempdir().unwrap();
    let mut baseline = std::collections::BTreeMap::new();
    for batch in [false, true] {
        for (flag, value, beside) in SCORE_VALUES {
            let Some(value) = value else { continue };
            let before = baseline
                .entry((batch, beside.to_vec()))
                .or_insert_with(|| scores(d.path(), batch, beside))
                .clone();
            let after = scores(d.path(), batch, &[beside, &[*flag, *value][..]].concat());
            match (before, after) {
                (Ok(b), Ok(a)) => assert_ne!(b, a, "{flag} {value} (batch {batch}): ignored"),
                (_, Err(e)) => assert!(
                    e.contains(flag) && !e.contains('\n'),
                    "{flag} {value} (batch {batch}): {e}"
                ),
                (Err(e), _) => panic!("{beside:?}: {e}"),
            }
        }
    }
}
