//! Photographs: `facetlab render --light tent|…|studio|env:FILE` writes PNG sheets, animated
//! PNG and GIF turntables, the linear picture, and JSON records; a map file is read (and a
//! malformed one refused in one line); photographic flags are refused with laboratory lights.

use super::{bad, files, ok};
use tempfile::tempdir;

fn json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

/// A small equirectangular OpenEXR map: 1 above the horizon, 0.1 below, one bright patch.
fn write_map(path: &std::path::Path) {
    let (w, h) = (64usize, 32usize);
    let rgb: Vec<[f32; 3]> = (0..w * h)
        .map(|k| {
            let (r, c) = (k / w, k % w);
            if r < 6 && (20..28).contains(&c) {
                [20.0, 18.0, 15.0]
            } else if r < h / 2 {
                [1.0; 3]
            } else {
                [0.1; 3]
            }
        })
        .collect();
    facetlab::io::hdr::write_hdr(
        path,
        &facetlab::io::hdr::HdrImage {
            width: w,
            height: h,
            rgb,
        },
    )
    .unwrap();
}

#[test]
fn a_photograph_with_its_record_ground_and_linear_picture() {
    let d = tempdir().unwrap();
    let p = d.path();
    write_map(&p.join("sky.exr"));
    let out = ok(
        p,
        &[
            "render",
            "tolkowsky",
            "--light",
            "env:sky.exr",
            "--view",
            "40@20",
            "--ground",
            "white",
            "--light-rotation",
            "30",
            "--size",
            "48",
            "--bare",
            "--json",
            "photo.json",
            "--hdr-out",
            "linear.exr",
            "-o",
            "photo.png",
        ],
    );
    assert!(
        out.contains("env:sky.exr photograph") && out.contains("photo.png"),
        "{out}"
    );
    let j = json(&p.join("photo.json"));
    assert_eq!(j["light"], "env:sky.exr");
    assert_eq!(j["view"]["elevation_deg"], 40.0);
    assert_eq!(j["view"]["azimuth_deg"], 20.0);
    assert_eq!(j["ground"], "white");
    assert_eq!(j["light_rotation_deg"], 30.0);
    assert_eq!(j["bands"], 7, "diamond: eight bands, the faint one merged");
    assert!(j["distance_mm"].is_null() && j.get("frames").is_none());
    let g = &j["ground_light"];
    let intercepted = g["intercepted"].as_f64().unwrap();
    assert!(intercepted > 0.0);
    assert!(
        g["balance"].as_f64().unwrap().abs() < 1e-9 * intercepted,
        "{g}"
    );
    // The linear picture: 48 × 48 linear RGB, the PNG its tone-mapped self.
    let lin = facetlab::io::hdr::read_hdr(&p.join("linear.exr")).unwrap();
    assert_eq!((lin.width, lin.height), (48, 48));
    assert!(lin.rgb.iter().any(|c| c[1] > 0.05));
    let dec = png::Decoder::new(std::fs::File::open(p.join("photo.png")).unwrap());
    let r = dec.read_info().unwrap();
    assert_eq!((r.info().width, r.info().height), (48, 48));
}

#[test]
fn turntables_as_gif_and_animated_png_and_perspective() {
    let d = tempdir().unwrap();
    let p = d.path();
    ok(
        p,
        &[
            "render",
            "princess",
            "--light",
            "darkfield",
            "--turn",
            "4",
            "--size",
            "32",
            "--ri",
            "2.4",
            "--bare",
            "--json",
            "turn.json",
            "-o",
            "turn.gif",
        ],
    );
    let j = json(&p.join("turn.json"));
    assert_eq!(j["turn_frames"], 4);
    let frames = j["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 4);
    assert_eq!(frames[2]["turn_deg"], 180.0);
    // The stone turns: a princess under point lights looks different at 90°... but the same
    // at 0° and after its own quarter turn? Its frames are pictures of it turned by 0, 90,
    // 180 and 270 degrees under fixed lights: the means differ.
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::RGBA);
    let mut dec = opts
        .read_info(std::fs::File::open(p.join("turn.gif")).unwrap())
        .unwrap();
    let mut n = 0;
    while let Some(f) = dec.read_next_frame().unwrap() {
        assert_eq!((f.width, f.height), (32, 32));
        n += 1;
    }
    assert_eq!(n, 4);
    ok(
        p,
        &[
            "render",
            "tolkowsky",
            "--light",
            "studio",
            "--turn",
            "3",
            "--size",
            "24",
            "--distance",
            "60",
            "--bare",
            "--json",
            "persp.json",
            "-o",
            "turn.png",
        ],
    );
    let j = json(&p.join("persp.json"));
    assert_eq!(j["distance_mm"], 60.0);
    assert_eq!(j["tile"], 32);
    let dec = png::Decoder::new(std::fs::File::open(p.join("turn.png")).unwrap());
    let r = dec.read_info().unwrap();
    assert_eq!(r.info().animation_control().map(|c| c.num_frames), Some(3));
}

/// The photograph's own checks (RenderOptions' and PhotoOptions' `validate`) name their
/// settings as the library does; the binary's one table (FLAGS) names the flag, the whole line
/// as before.
#[test]
fn a_photographs_own_checks_name_the_flag() {
    let d = tempdir().unwrap();
    let p = d.path();
    let cases: &[(&[&str], &str)] = &[
        (
            &["--view", "-10", "--ground", "white"],
            "facetlab: --view: -10° looks from under the ground; with a ground the camera's elevation is 0 to 90 degrees",
        ),
        (
            &["--distance", "5"],
            "facetlab: --distance: 5 mm is out of range; allowed 19.5 mm (three times the stone's width of 6.5 mm) to 100000 mm",
        ),
        (
            &["--distance", "100", "--aperture", "50"],
            "facetlab: --aperture: 50 mm is out of range; allowed 0 (a pinhole) to 35.3 mm, an entrance pupil seen within ±10° from 100 mm",
        ),
        (
            &["--aperture", "90"],
            "facetlab: --aperture: 90 mm is out of range; allowed 0 (a pinhole) to 88.2 mm, an entrance pupil seen within ±10° from 250 mm",
        ),
        (
            &["--aperture", "-1"],
            "facetlab: --aperture: `-1` is not allowed; give millimetres (0 = a pinhole) in [0, 100]",
        ),
        (
            &["--aperture", "nan"],
            "facetlab: --aperture: `nan` is not allowed; give millimetres (0 = a pinhole) in [0, 100]",
        ),
        (
            &["--aperture", "1e9"],
            "facetlab: --aperture: `1e9` is not allowed; give millimetres (0 = a pinhole) in [0, 100]",
        ),
    ];
    for (extra, line) in cases {
        let mut args = vec![
            "render",
            "tolkowsky",
            "--size",
            "16",
            "-o",
            "out.png",
            "--light",
            "tent",
        ];
        args.extend_from_slice(extra);
        assert_eq!(bad(p, &args, &[]), *line);
    }
    assert!(files(p).is_empty());
}

#[test]
fn bad_photographs_are_one_line_and_write_nothing() {
    let d = tempdir().unwrap();
    let p = d.path();
    std::fs::write(p.join("broken.exr"), b"not an exr").unwrap();
    std::fs::write(p.join("broken.hdr"), b"#?RADIANCE\nnonsense").unwrap();
    let cases: &[(&[&str], &[&str])] = &[
        (&["--light", "env:broken.exr"], &["broken.exr"]),
        (&["--light", "env:broken.hdr"], &["broken.hdr"]),
        (
            &["--light", "env:missing.exr"],
            &["missing.exr", "no such file"],
        ),
        (&["--light", "env:sky.png"], &["sky.png", ".exr"]),
        (&["--light", "tent", "--view", "95"], &["--view"]),
        (
            &["--light", "tent", "--view", "-10", "--ground", "white"],
            &["--view", "under the ground"],
        ),
        (&["--light", "tent", "--ground", "grass"], &["--ground"]),
        (
            &["--light", "tent", "--ground-gap", "-1"],
            &["--ground-gap"],
        ),
        // A gap above no ground would be ignored.
        (
            &["--light", "tent", "--ground-gap", "0.5"],
            &["--ground-gap: is the stone's height above a ground; give --ground white or black"],
        ),
        (
            &["--light", "tent", "--distance", "5"],
            &["--distance", "three times"],
        ),
        (&["--light", "tent", "--turn", "1"], &["--turn"]),
        (
            &["--light", "tent", "--turn", "4", "--rock", "10:4"],
            &["--turn"],
        ),
        (&["--light", "tent", "--tone", "hdr"], &["--tone"]),
        (&["--light", "tent", "--bands", "2"], &["--bands"]),
        (
            &["--light", "tent", "--hdr-out", "x.tiff"],
            &["--hdr-out", ".exr"],
        ),
        (
            &["--light", "tent", "--head-shadow", "10"],
            &["--head-shadow"],
        ),
        (
            &["--light", "iso", "--view", "30"],
            &["--view", "photographic"],
        ),
        (
            &["--light", "fire", "--ground", "white"],
            &["--ground", "photographic"],
        ),
        (
            &["--light", "aset", "--aperture", "0"],
            &["--aperture", "photographic"],
        ),
        (&["--light", "disco"], &["--light", "tent", "env:FILE"]),
    ];
    for (extra, needles) in cases {
        let mut args = vec!["render", "tolkowsky", "--size", "16", "-o", "out.png"];
        args.extend_from_slice(extra);
        bad(p, &args, needles);
    }
    assert_eq!(files(p), vec!["broken.exr", "broken.hdr"]);
}

/// A birefringent stone is photographed with its crystal settings (the note says so) and
/// casts its caustic on the ground, birefringent or not (a uniaxial stone's caustic was
/// once lost, counted as light escaping upward).
#[test]
fn a_birefringent_stone_casts_its_caustic() {
    let dir = tempdir().unwrap();
    let caustic = |extra: &[&str]| -> (f64, String) {
        let mut args = vec![
            "render",
            "oval",
            "--material",
            "quartz",
            "--light",
            "daylight",
            "--ground",
            "white",
            "--view",
            "35",
            "--size",
            "48",
            "-o",
            "q.png",
            "--force",
        ];
        args.extend_from_slice(extra);
        let out = super::run_in(dir.path(), &args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8_lossy(&out.stdout).to_string()
            + &String::from_utf8_lossy(&out.stderr);
        let share = text
            .split("caustics ")
            .nth(1)
            .and_then(|s| s.split_whitespace().next())
            .and_then(|s| s.parse::<f64>().ok())
            .unwrap_or_else(|| panic!("no caustics in {text}"));
        (share, text)
    };
    let (on, on_text) = caustic(&[]);
    let (off, off_text) = caustic(&["--birefringence", "off"]);
    assert!(on > 0.2 && off > 0.2, "{on} {off}");
    assert!((on - off).abs() < 0.05, "{on} {off}");
    assert!(off_text.contains("birefringence off"), "{off_text}");
    assert!(on_text.contains("optic axis"), "{on_text}");
}
