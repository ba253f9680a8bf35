//! Refused, not ignored, and said in one short line (issue 51): a batch's crystal flags, and
//! errors that name their flag with the value in its shortest form.

use super::hostile::OCTA;
use super::{bad, files, ok};

/// Issue 51 item 5: `score --batch` takes the crystal flags as `score` does. A value no stone
/// takes is refused before OUT is touched; a valid one reaches every line (the brilliance of
/// a sapphire changes with its optic axis); a stone that cannot take it (a diamond given an
/// axis) is that line's error.
#[test]
fn a_batch_takes_the_crystal_flags_or_refuses_them() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path();
    std::fs::write(p.join("cuts.txt"), "tolkowsky\nprincess\n").unwrap();
    let batch = |out: &str, extra: &[&str]| -> Vec<String> {
        [&["score", "--batch", "cuts.txt", "--jsonl", out][..], extra]
            .concat()
            .iter()
            .map(|s| s.to_string())
            .collect()
    };
    for (flag, value) in [
        ("--optic-axis", "nan@5"),
        ("--optic-axis", "45@1e300"),
        ("--birefringence", "maybe"),
        ("--colour-e", "zzz"),
    ] {
        let args = batch("x.jsonl", &[flag, value]);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        bad(p, &args, &[flag]);
    }
    // A chosen material that takes no axis: refused before any line.
    let args = batch("x.jsonl", &["--material", "peridot", "--optic-axis", "30"]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    bad(p, &args, &["--optic-axis: peridot is biaxial"]);
    assert_eq!(files(p), ["cuts.txt"]);
    let brilliance = |out: &str, extra: &[&str]| -> Vec<serde_json::Value> {
        let args = batch(
            out,
            &[
                &["--material", "sapphire", "--polarization", "off"][..],
                extra,
            ]
            .concat(),
        );
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        ok(p, &args);
        std::fs::read_to_string(p.join(out))
            .unwrap()
            .lines()
            .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap()["brilliance"].clone())
            .collect()
    };
    let upright = brilliance("c0.jsonl", &["--optic-axis", "0"]);
    let lying = brilliance("c90.jsonl", &["--optic-axis", "90@30"]);
    let off = brilliance("off.jsonl", &["--birefringence", "off"]);
    assert_eq!(upright.len(), 2);
    for i in 0..2 {
        assert!(upright[i].is_number() && lying[i].is_number() && off[i].is_number());
        assert_ne!(upright[i], lying[i], "line {i}: the axis reached it");
        assert_ne!(upright[i], off[i], "line {i}: birefringence off reached it");
    }
    // As `score` scores the same cut under the same flags.
    ok(
        p,
        &[
            "score",
            "tolkowsky",
            "--material",
            "sapphire",
            "--polarization",
            "off",
            "--optic-axis",
            "90@30",
            "--json",
            "one.json",
        ],
    );
    let one: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p.join("one.json")).unwrap()).unwrap();
    assert_eq!(one["brilliance"], lying[0]);
    // The default diamond takes no axis: each line says so, the batch goes on.
    ok(
        p,
        &[
            "score",
            "--batch",
            "cuts.txt",
            "--jsonl",
            "dia.jsonl",
            "--optic-axis",
            "30",
        ],
    );
    let text = std::fs::read_to_string(p.join("dia.jsonl")).unwrap();
    assert_eq!(text.lines().count(), 2);
    for l in text.lines() {
        let v: serde_json::Value = serde_json::from_str(l).unwrap();
        let e = v["error"].as_str().unwrap();
        assert!(
            e.starts_with("--optic-axis: diamond is singly refractive"),
            "{e}"
        );
    }
}

/// Issue 51 item 9: each error is one short line naming what the user gave.
#[test]
fn errors_name_the_flag_in_one_short_line() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path();
    std::fs::write(p.join("octa.asc"), OCTA).unwrap();
    // A tier turned so far that no solid is left: named by --set, not "geometry".
    bad(
        p,
        &["info", "octa.asc", "--set", "crown=0.001"],
        &["--set: `crown=1e-3` makes no solid"],
    );
    // A binary .gem named .asc.
    ok(p, &["generate", "tolkowsky", "-o", "t.gem"]);
    std::fs::copy(p.join("t.gem"), p.join("t.asc")).unwrap();
    bad(
        p,
        &["info", "t.asc"],
        &["t.asc: not a GemCad .asc: it is a binary GemCad .gem file; name it .gem"],
    );
    // A GIF is a photograph's animation.
    bad(
        p,
        &["render", "tolkowsky", "-o", "x.gif"],
        &["-o: x.gif does not end in .png", "--turn"],
    );
    // A preset's typo.
    bad(
        p,
        &["info", "tolkowski"],
        &["unknown preset (did you mean `tolkowsky`?)"],
    );
    // Numbers in their short form.
    let e = bad(
        p,
        &[
            "render",
            "tolkowsky",
            "--light",
            "tent",
            "--distance",
            "1e-300",
            "-o",
            "a.png",
        ],
        &["--distance: 1e-300 mm is out of range"],
    );
    assert!(e.len() < 200, "{e}");
    bad(
        p,
        &[
            "score",
            "tolkowsky",
            "--material",
            "sapphire",
            "--optic-axis",
            "45@1e300",
        ],
        &["--optic-axis: `45@1e300`", "[-360, 360]"],
    );
    // An error comes alone, no stone's note before it.
    bad(
        p,
        &[
            "score",
            "tolkowsky",
            "--material",
            "peridot",
            "--optic-axis",
            "30",
        ],
        &["--optic-axis: peridot is biaxial"],
    );
    // A config's key of the wrong type says what it takes.
    std::fs::write(
        p.join("c.toml"),
        "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30, 38]\n[score]\noptic_axis = true\n",
    )
    .unwrap();
    let e = bad(
        p,
        &["optimize", "c.toml", "--out", "r"],
        &["c.toml:6", "expected a number of degrees"],
    );
    assert!(!e.contains("untagged") && !e.contains("RawAxis"), "{e}");
    let fine =
        "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30, 38]\n[score]\nri = 1.54\n";
    std::fs::write(p.join("s.toml"), fine).unwrap();
    let e = bad(
        p,
        &[
            "sweep",
            "s.toml",
            "--x",
            "crown_angle:30:34:1e-300",
            "--out",
            "sw",
        ],
        &["--x"],
    );
    assert!(e.len() < 200 && !e.contains("00000000"), "{e}");
    assert_eq!(files(p), ["c.toml", "octa.asc", "s.toml", "t.asc", "t.gem"]);
}
