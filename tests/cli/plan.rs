//! `facetlab plan`: a small run writes its folder; bad input (an open or flat mesh, a mesh not
//! in mm without --size-mm, a rough too small for any cut, unknown forms and families) is one
//! line, exit code 2, nothing written (issue 26's check 4).

use super::{bad, files, ok};
use std::path::Path;

/// A closed tetrahedron (mm) as OBJ, its last face left out when `open`.
fn tetra(dir: &Path, name: &str, scale: f64, open: bool) -> String {
    let mut s = String::new();
    for v in [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ] {
        s.push_str(&format!(
            "v {} {} {}\n",
            v[0] * scale,
            v[1] * scale,
            v[2] * scale
        ));
    }
    s.push_str("f 1 3 2\nf 1 2 4\nf 2 3 4\n");
    if !open {
        s.push_str("f 1 4 3\n");
    }
    std::fs::write(dir.join(name), s).unwrap();
    name.to_string()
}

/// `plan octahedron` (6 mm) in `p` with `p/plan.toml`, one plan of `family`, into `p/run`.
fn plan_octahedron(p: &Path, family: &str) {
    ok(
        p,
        &[
            "plan",
            "octahedron",
            "--size-mm",
            "6",
            "--family",
            family,
            "--top",
            "1",
            "--config",
            "plan.toml",
            "--quiet",
            "-o",
            "run",
        ],
    );
}

#[test]
fn a_crystal_plan_writes_its_folder() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    let cfg = "seed = 3\n[search]\nstarts = 2\nmax_iterations = 60\n";
    std::fs::write(p.join("plan.toml"), cfg).unwrap();
    plan_octahedron(p, "round-brilliant");
    let got = files(&p.join("run"));
    for f in [
        "summary.json",
        "report.html",
        "rough.obj",
        "scene.obj",
        "scene.gltf",
        "overview.png",
        "round-brilliant-1.obj",
        "round-brilliant-1.toml",
        "round-brilliant-1.asc",
        "round-brilliant-1-views.png",
    ] {
        assert!(got.iter().any(|g| g == f), "{f} missing: {got:?}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p.join("run/summary.json")).unwrap())
            .unwrap();
    let plan = &json["plans"][0];
    let y = plan["yield"].as_f64().unwrap();
    assert!(y > 0.3 && y < 1.0, "{y}");
    assert_eq!(json["rough"]["volume_mm3"].as_f64().unwrap().round(), 36.0);
    // The glTF scene holds the rough and every plan, in metres.
    let gltf: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p.join("run/scene.gltf")).unwrap()).unwrap();
    assert_eq!(gltf["asset"]["version"], "2.0");
    assert_eq!(
        gltf["nodes"].as_array().unwrap().len(),
        1 + json["plans"].as_array().unwrap().len()
    );
    // The written cut is the planned one: read back, its volume is yield × rough volume.
    let back = ok(p, &["info", "run/round-brilliant-1.toml", "--json"]);
    assert!(back.contains("volume"), "{back}");
    // Only the run folder is left (no temporary folder).
    assert_eq!(files(p), vec!["plan.toml", "run"]);
}

/// `[rough] c_axis` places a uniaxial stone's optic axis: each plan's summary names its
/// optic axis in the cut's frame, its design carries the notes `F Material: sapphire` and
/// `F Optic axis: …` that `score` reads, and scoring that design says it is traced with
/// that axis.
#[test]
fn a_rough_with_its_c_axis_plans_each_cut_in_its_true_orientation() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    let cfg = "seed = 3\nmaterial = \"sapphire\"\n[rough]\nc_axis = [0.3, -0.2, 0.9]\n\
               [search]\nstarts = 2\nmax_iterations = 40\n";
    std::fs::write(p.join("plan.toml"), cfg).unwrap();
    plan_octahedron(p, "oval");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p.join("run/summary.json")).unwrap())
            .unwrap();
    let axis = json["plans"][0]["optic_axis"].as_str().unwrap().to_string();
    let asc = std::fs::read_to_string(p.join("run/oval-1.asc")).unwrap();
    assert!(
        asc.lines().any(|l| l == format!("F Optic axis: {axis}")),
        "{axis}: {asc}"
    );
    let tilt: f64 = axis.split('@').next().unwrap().parse().unwrap();
    assert!((0.0..=90.0).contains(&tilt), "{axis}");
    assert!(asc.lines().any(|l| l == "F Material: sapphire"), "{asc}");
    let scored = super::run_in(p, &["score", "run/oval-1.asc"]);
    assert!(scored.status.success());
    let note = String::from_utf8_lossy(&scored.stderr);
    assert!(
        note.contains("sapphire: birefringent") && note.contains(&format!("({axis})")),
        "{axis}: {note}"
    );
}

/// `[objective] kind = "colour"` (issue 41): a ruby rough with its c-axis plans by weight and
/// ranks by face-up colour, `summary.json` saying so and giving each plan's colour (its
/// objective is the colour's C*); a colourless rough refuses it in one line naming
/// `objective.kind`, writing nothing.
#[test]
fn a_coloured_rough_ranks_its_plans_by_face_up_colour() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    let cfg = "seed = 3\nmaterial = \"ruby\"\n[objective]\nkind = \"colour\"\n\
               [rough]\nc_axis = [0.3, -0.2, 0.9]\n[search]\nstarts = 2\nmax_iterations = 40\n";
    std::fs::write(p.join("plan.toml"), cfg).unwrap();
    plan_octahedron(p, "oval");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p.join("run/summary.json")).unwrap())
            .unwrap();
    assert_eq!(json["objective"], "colour");
    let plan = &json["plans"][0];
    let c = plan["colour"]["c"].as_f64().expect("the plan's colour");
    assert!(c > 5.0, "a ruby's colour: {plan}");
    assert_eq!(plan["objective"].as_f64(), Some(c));
    assert!(plan["colour"]["extinction"].as_f64().is_some(), "{plan}");

    let cfg = "material = \"sapphire\"\n[objective]\nkind = \"colour\"\n";
    std::fs::write(p.join("clear.toml"), cfg).unwrap();
    bad(
        p,
        &[
            "plan",
            "octahedron",
            "--size-mm",
            "6",
            "--family",
            "oval",
            "--config",
            "clear.toml",
            "--quiet",
            "-o",
            "clear",
        ],
        &["objective.kind", "sapphire"],
    );
    assert!(!p.join("clear").exists());
}

#[test]
fn bad_roughs_are_one_line_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    let open = tetra(p, "open.obj", 5.0, true);
    bad(
        p,
        &["plan", &open, "-o", "out"],
        &["open.obj", "not closed"],
    );
    let tiny = tetra(p, "tiny.obj", 0.01, false);
    bad(p, &["plan", &tiny, "-o", "out"], &["tiny.obj", "--size-mm"]);
    std::fs::write(
        p.join("unit.obj"),
        "# units: girdle diameters\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n",
    )
    .unwrap();
    bad(
        p,
        &["plan", "unit.obj", "-o", "out"],
        &["unit.obj", "not millimetres"],
    );
    std::fs::write(
        p.join("flat.obj"),
        "v 0 0 0\nv 5 0 0\nv 0 5 0\nv 5 5 0\nf 1 2 3\nf 2 4 3\nf 1 3 2\nf 2 3 4\n",
    )
    .unwrap();
    bad(p, &["plan", "flat.obj", "-o", "out"], &["flat.obj"]);
    bad(
        p,
        &[
            "plan",
            "octahedron",
            "--size-mm",
            "0.5",
            "--family",
            "oval",
            "--quiet",
            "-o",
            "out",
        ],
        &["too small", "min_width_mm"],
    );
    bad(
        p,
        &["plan", "octahedron", "-o", "out"],
        &["--size-mm", "octahedron"],
    );
    bad(
        p,
        &["plan", "pyramid", "--size-mm", "5", "-o", "out"],
        &["pyramid", "octahedron"],
    );
    bad(
        p,
        &[
            "plan",
            "cube",
            "--size-mm",
            "5",
            "--family",
            "heart",
            "-o",
            "out",
        ],
        &["--family", "heart"],
    );
    bad(
        p,
        &["plan", "cube", "--size-mm", "-5", "-o", "out"],
        &["--size-mm"],
    );
    // The library's one range of a rough's size (the web page's and Python's too).
    bad(
        p,
        &["plan", "cube", "--size-mm", "600", "-o", "out"],
        &["--size-mm: 600 is not allowed; give the rough's largest extent in (0, 500] mm"],
    );
    let closed = tetra(p, "closed.obj", 5.0, false);
    bad(p, &["plan", &closed, "-o", &closed], &["--out"]);
    let mut left = files(p);
    left.retain(|f| !f.ends_with(".obj"));
    assert!(left.is_empty(), "{left:?}");
}

#[test]
fn bad_layout_flags_are_one_line_and_write_nothing() {
    // Issue 54's flags: each refusal is one line naming the flag or the file, exit code 2,
    // and no run folder is made.
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    let rough = tetra(p, "rough.obj", 8.0, false);
    let open = tetra(p, "open.obj", 0.5, true);
    std::fs::write(p.join("garbled.obj"), "v 0 0 zero\nf 1 2 3\n").unwrap();
    let run = |extra: &[&str], needles: &[&str]| {
        let mut args = vec!["plan", rough.as_str(), "--quiet", "-o", "out"];
        args.extend_from_slice(extra);
        bad(p, &args, needles);
    };
    run(&["--stones", "0"], &["--stones"]);
    run(&["--stones", "9"], &["--stones", "8"]);
    run(&["--stones", "two"], &["--stones"]);
    run(&["--kerf", "-0.1"], &["--kerf"]);
    run(&["--kerf", "11"], &["--kerf"]);
    run(&["--allowance", "-1"], &["--allowance"]);
    run(&["--allowance", "nan"], &["--allowance"]);
    run(&["--margin", "-0.3"], &["--margin"]);
    run(&["--margin", "x"], &["--margin"]);
    run(&["--cutter", "water-jet"], &["--cutter", "saw", "laser"]);
    run(&["--inclusion", "missing.obj"], &["missing.obj"]);
    run(&["--inclusion", "garbled.obj"], &["garbled.obj"]);
    run(&["--inclusion", &open], &["open.obj", "not closed"]);
    // The same keys in a config file name the key.
    std::fs::write(p.join("bad.toml"), "[rough]\nkerf_mm = -1\n").unwrap();
    run(&["--config", "bad.toml"], &["kerf_mm"]);
    std::fs::write(p.join("many.toml"), "[rough]\nstones = 20\n").unwrap();
    run(&["--config", "many.toml"], &["stones"]);
    std::fs::write(p.join("cutter.toml"), "[rough]\ncutter = \"wire\"\n").unwrap();
    run(&["--config", "cutter.toml"], &["rough.cutter", "laser"]);
    let mut left = files(p);
    left.retain(|f| !f.ends_with(".obj") && !f.ends_with(".toml"));
    assert!(left.is_empty(), "{left:?}");
}

/// A coloured rough's layout ranked by value × colour (issue 54): `--stones 2` with `kind =
/// "colour"` and a price table (cheaper per carat above 0.06 ct: two stones are worth more
/// than one) writes each stone's worth (its price), face-up colour and
/// colour factor beside its carats and yield, its objective their product and the layout's
/// total their sum; a colourless rough refuses it in one line naming `objective.kind`,
/// writing nothing.
#[test]
fn a_coloured_rough_ranks_its_layout_by_value_times_colour() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    std::fs::write(
        p.join("prices.toml"),
        "currency = \"EUR\"\n[[band]]\nfrom_carats = 0\nper_carat = 1000\n\
         [[band]]\nfrom_carats = 0.06\nper_carat = 300\n",
    )
    .unwrap();
    let cfg =
        "seed = 3\nmaterial = \"ruby\"\n[objective]\nkind = \"colour\"\nprices = \"prices.toml\"\n\
               [rough]\nc_axis = [0.3, -0.2, 0.9]\n\
               [search]\nstarts = 2\nmax_iterations = 40\nsaw_offsets = 2\n";
    std::fs::write(p.join("plan.toml"), cfg).unwrap();
    let args = |config: &'static str, out: &'static str| {
        [
            "plan",
            "octahedron",
            "--size-mm",
            "5",
            "--family",
            "oval",
            "--top",
            "1",
            "--stones",
            "2",
            "--config",
            config,
            "--quiet",
            "-o",
            out,
        ]
    };
    let stdout = ok(p, &args("plan.toml", "run"));
    assert!(stdout.contains("× colour"), "{stdout}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p.join("run/summary.json")).unwrap())
            .unwrap();
    assert_eq!(json["objective"], "colour");
    assert_eq!(json["currency"], "EUR");
    let layout = &json["layout"];
    let reference = layout["colour_reference_c"]
        .as_f64()
        .expect("the reference");
    assert!(reference > 0.0, "{layout}");
    let stones = json["stones"].as_array().unwrap();
    assert_eq!(stones.len(), 2, "{json}");
    let (mut total, mut worth) = (0.0, 0.0);
    for s in stones {
        let f = |k: &str| s[k].as_f64().unwrap_or_else(|| panic!("{k}: {s}"));
        let c = s["colour"]["c"].as_f64().expect("the stone's colour");
        assert!(f("yield") > 0.0 && f("carats") > 0.0, "{s}");
        let per_carat = if f("carats") >= 0.06 { 300.0 } else { 1000.0 };
        assert!(
            (f("worth") - per_carat * f("carats")).abs() < 1e-9 * f("worth"),
            "{s}"
        );
        assert!((f("colour_factor") - c / reference).abs() < 1e-12, "{s}");
        assert!(
            (f("objective") - f("worth") * f("colour_factor")).abs() < 1e-9 * f("worth"),
            "{s}"
        );
        total += f("objective");
        worth += f("worth");
    }
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b;
    assert!(
        near(layout["total_objective"].as_f64().unwrap(), total),
        "{layout}"
    );
    assert!(
        near(layout["total_worth"].as_f64().unwrap(), worth),
        "{layout}"
    );
    // Each stone's plan gives the same colour.
    assert_eq!(json["plans"][0]["colour"], stones[0]["colour"]);

    std::fs::write(
        p.join("clear.toml"),
        "material = \"diamond\"\n[objective]\nkind = \"colour\"\n",
    )
    .unwrap();
    bad(
        p,
        &args("clear.toml", "clear"),
        &["objective.kind", "diamond"],
    );
    assert!(!p.join("clear").exists());
}
