//! "See the stone": `facetlab render` writes PNG sheets (panels side by side, captions, legend),
//! animated PNGs with --rock, and the statistics as JSON; bad flags are one line, exit 2.

use super::{bad, files, ok};
use tempfile::tempdir;

/// Width, height and frame count (1 for a still PNG) of a PNG file.
fn png_info(path: &std::path::Path) -> (u32, u32, u32) {
    let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut r = dec.read_info().expect("a PNG");
    let frames = r.info().animation_control().map_or(1, |c| c.num_frames);
    let (w, h) = (r.info().width, r.info().height);
    let mut buf = vec![0; r.output_buffer_size()];
    // Every frame decodes.
    for _ in 0..frames {
        r.next_frame(&mut buf).expect("frame decodes");
    }
    (w, h, frames)
}

fn json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

#[test]
fn one_cut_and_three_side_by_side_with_statistics() {
    let d = tempdir().unwrap();
    let p = d.path();
    let out = ok(
        p,
        &[
            "render",
            "tolkowsky",
            "--size",
            "64",
            "--json",
            "one.json",
            "-o",
            "one.png",
        ],
    );
    assert!(
        out.contains("Tolkowsky") && out.contains("iso mean") && out.contains("one.png"),
        "{out}"
    );
    let (w1, h1, n) = png_info(&p.join("one.png"));
    assert_eq!(n, 1);
    assert!(w1 >= 64 && h1 > 64, "{w1}×{h1}");
    let j = json(&p.join("one.json"));
    assert_eq!(j["name"], "Tolkowsky");
    assert_eq!(j["light"], "iso");
    assert_eq!(j["size"], 64);
    let mean = j["mean"].as_f64().unwrap();
    assert!(mean > 0.3 && mean < 1.0, "{mean}");
    for k in ["tilt_deg", "azimuth_deg", "elapsed_s", "cut_off", "exits"] {
        assert!(j[k].is_number(), "{k}: {j}");
    }
    assert!(
        j.get("aset").is_none() && j.get("placement_fire").is_none() && j.get("frames").is_none()
    );

    // Three cuts under ASET: three panels wide, an array of records whose shares sum to 1.
    let out = ok(
        p,
        &[
            "render",
            "tolkowsky",
            "princess",
            "emerald",
            "--light",
            "aset",
            "--size",
            "64",
            "--json",
            "three.json",
            "-o",
            "three.png",
        ],
    );
    assert_eq!(out.lines().filter(|l| l.contains("three.png")).count(), 3);
    let (w3, h3, _) = png_info(&p.join("three.png"));
    assert_eq!(w3, 3 * w1);
    assert!(h3 > h1, "the legend adds rows: {h3} vs {h1}");
    let j = json(&p.join("three.json"));
    let arr = j.as_array().unwrap();
    assert_eq!(arr.len(), 3);
    for r in arr {
        assert_eq!(r["light"], "aset");
        let a = &r["aset"];
        let sum: f64 = ["blue", "red", "green", "leak", "port"]
            .iter()
            .map(|k| a[k].as_f64().unwrap())
            .sum();
        assert!((sum - 1.0).abs() < 1e-3, "{sum}: {a}");
    }
    assert_eq!(arr[1]["input"], "princess");
}

#[test]
fn fire_and_tilt_record_their_pose_and_value() {
    let d = tempdir().unwrap();
    let p = d.path();
    ok(
        p,
        &[
            "render",
            "tolkowsky",
            "--light",
            "fire",
            "--size",
            "64",
            "--tilt",
            "10@45",
            "--json",
            "f.json",
            "-o",
            "f.png",
        ],
    );
    let j = json(&p.join("f.json"));
    assert!(j["placement_fire"].as_f64().unwrap() > 0.0, "{j}");
    // One placement of the lights is not the score's fire, and is not called so.
    assert!(j.get("fire").is_none(), "{j}");
    assert_eq!(j["tilt_deg"], 10.0);
    assert_eq!(j["azimuth_deg"], 45.0);
    assert!(j.get("aset").is_none());
    assert_eq!(png_info(&p.join("f.png")).2, 1);
}

#[test]
fn rock_writes_an_animated_png_with_one_record_per_frame() {
    let d = tempdir().unwrap();
    let p = d.path();
    let out = ok(
        p,
        &[
            "render",
            "tolkowsky",
            "--size",
            "64",
            "--rock",
            "12:6",
            "--json",
            "r.json",
            "-o",
            "r.png",
        ],
    );
    assert!(out.contains("6 frames"), "{out}");
    let (_, _, n) = png_info(&p.join("r.png"));
    assert_eq!(n, 6);
    let j = json(&p.join("r.json"));
    let frames = j["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 6);
    assert_eq!(j["rock_deg"], 12.0);
    // Frame k is tilted 12·sin(2πk/6).
    let t1 = frames[1]["tilt_deg"].as_f64().unwrap();
    assert!((t1 - 12.0 * (std::f64::consts::TAU / 6.0).sin()).abs() < 1e-9);
    assert_eq!(frames[0]["tilt_deg"], 0.0);
}

#[test]
fn bad_flags_and_unsafe_outputs_are_refused_without_output() {
    let d = tempdir().unwrap();
    let p = d.path();
    let base = ["render", "tolkowsky", "--size", "64"];
    let with = |extra: &[&'static str]| {
        let mut v: Vec<&str> = base.to_vec();
        v.extend_from_slice(extra);
        v
    };
    bad(p, &with(&["--tilt", "10@x", "-o", "a.png"]), &["--tilt"]);
    bad(p, &with(&["--tilt", "120", "-o", "a.png"]), &["--tilt"]);
    bad(p, &with(&["--rock", "90:10", "-o", "a.png"]), &["--rock"]);
    bad(p, &with(&["--rock", "10:1", "-o", "a.png"]), &["--rock"]);
    bad(
        p,
        &with(&["--light", "sun", "-o", "a.png"]),
        &["--light", "aset"],
    );
    bad(p, &with(&["--size", "0", "-o", "a.png"]), &["--size"]);
    bad(
        p,
        &with(&["--exposure", "-1", "-o", "a.png"]),
        &["--exposure"],
    );
    bad(p, &with(&["-o", "a.jpg"]), &["-o", ".png"]);
    bad(p, &with(&[]), &["--output"]);
    // An output that is an input is refused, --force or not.
    ok(p, &["generate", "tolkowsky", "-o", "t.toml"]);
    bad(
        p,
        &["render", "t.toml", "--force", "-o", "t.toml"],
        &["-o", "would overwrite"],
    );
    bad(
        p,
        &["render", "t.toml", "--json", "./t.toml", "-o", "a.png"],
        &["--json", "would overwrite"],
    );
    assert_eq!(files(p), vec!["t.toml".to_string()]);
    // An existing picture is replaced only with --force.
    ok(p, &with(&["-o", "a.png"]));
    bad(p, &with(&["-o", "a.png"]), &["-o", "--force"]);
    ok(p, &with(&["-o", "a.png", "--force"]));
    assert_eq!(files(p), vec!["a.png".to_string(), "t.toml".to_string()]);
}

/// `report` writes one self-contained page with every cut's pictures, and refuses to write
/// over an input.
#[test]
fn report_writes_a_self_contained_page() {
    let d = tempdir().unwrap();
    let p = d.path();
    let out = ok(
        p,
        &[
            "report",
            "tolkowsky",
            "princess",
            "--size",
            "64",
            "-o",
            "r.html",
        ],
    );
    assert!(
        out.contains("grade estimate excellent") && out.contains("wrote r.html"),
        "{out}"
    );
    let page = std::fs::read_to_string(p.join("r.html")).unwrap();
    assert_eq!(page.matches("data:image/png;base64,").count(), 6);
    assert!(page.contains("<h2>Tolkowsky</h2>") && page.contains("<h2>Princess</h2>"));
    ok(p, &["generate", "tolkowsky", "-o", "t.asc"]);
    bad(p, &["report", "t.asc", "-o", "t.asc"], &["-o"]);
    bad(p, &["report", "tolkowsky", "-o", "r.txt"], &["-o", ".html"]);
    bad(p, &["report", "tolkowsky", "-o", "r.html"], &["--force"]);
    bad(
        p,
        &["report", "tolkowsky", "--size", "9", "-o", "s.html"],
        &["--size"],
    );
}

/// The first frame of a PNG as 8-bit RGB: width, height, pixels.
fn png_rgb(path: &std::path::Path) -> (usize, usize, Vec<u8>) {
    let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut r = dec.read_info().expect("a PNG");
    let mut buf = vec![0; r.output_buffer_size()];
    let info = r.next_frame(&mut buf).expect("frame decodes");
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf.truncate(info.buffer_size());
    (info.width as usize, info.height as usize, buf)
}

/// `--size PX` is the stone's picture: `--bare` writes it alone, exactly PX × PX; with
/// captions the same PX × PX picture sits inside a grey margin with the caption band below it.
#[test]
fn size_is_the_stones_picture_and_bare_is_it_alone() {
    let d = tempdir().unwrap();
    let p = d.path();
    let base = ["render", "tolkowsky", "--size", "200"];
    let with = |extra: &[&'static str]| [&base[..], extra].concat();
    ok(p, &with(&["--bare", "-o", "bare.png"]));
    ok(p, &with(&["-o", "sheet.png"]));
    let (bw, bh, bare) = png_rgb(&p.join("bare.png"));
    assert_eq!((bw, bh), (200, 200));
    let (w, h, sheet) = png_rgb(&p.join("sheet.png"));
    // The margin around the picture is the same on every side.
    assert!(w > 200 && (w - 200) % 2 == 0, "{w}×{h}");
    let pad = (w - 200) / 2;
    assert!(pad >= 4, "{pad}");
    let px = |x: usize, y: usize| &sheet[(y * w + x) * 3..(y * w + x) * 3 + 3];
    // The stone's region of the sheet is the bare picture, pixel for pixel, but for the
    // stone's outline: ground pixels beside the stone drawn dark on the sheet.
    let mut outlined = 0;
    for y in 0..200 {
        let row = &sheet[((pad + y) * w + pad) * 3..((pad + y) * w + pad + 200) * 3];
        for (s, b) in row.chunks(3).zip(bare[y * 600..(y + 1) * 600].chunks(3)) {
            if s != b {
                assert_eq!(
                    (b, s),
                    (&[102u8, 102, 102][..], &[28u8, 28, 28][..]),
                    "row {y}"
                );
                outlined += 1;
            }
        }
    }
    // About the outline's perimeter (π · 200 px), one pixel wide.
    assert!((400..1200).contains(&outlined), "{outlined} outline pixels");
    // Grey margin above and below the picture, then the caption band to the bottom.
    for y in [0, pad - 1, pad + 200, 2 * pad + 199] {
        assert_eq!(px(0, y), [102, 102, 102], "row {y}");
    }
    let band = h - (200 + 2 * pad);
    // Two caption lines (name, statistics) of 11–13 px text.
    assert!((30..=60).contains(&band), "caption band {band} px");
    for y in 200 + 2 * pad..h {
        assert_eq!(px(0, y), [236, 236, 236], "row {y}");
    }
    let dark = (200 + 2 * pad..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|&(x, y)| px(x, y)[0] < 100)
        .count();
    assert!(dark > 20, "no caption text: {dark}");
    // Two cuts bare: side by side, nothing between.
    ok(
        p,
        &[
            "render",
            "tolkowsky",
            "princess",
            "--size",
            "64",
            "--bare",
            "-o",
            "two.png",
        ],
    );
    assert_eq!(png_info(&p.join("two.png")), (128, 64, 1));
}
