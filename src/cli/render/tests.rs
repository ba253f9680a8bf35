use super::*;
use clap::Parser;
use facetlab::plot::render::{delay_ms, settings_line, stats_lines};
use facetlab::render::{self, Stats};
use facetlab::render::{Light, Tilt};

#[derive(clap::Parser)]
struct Cli {
    #[command(flatten)]
    args: RenderArgs,
}

fn parse(extra: &[&str]) -> RenderArgs {
    let mut v = vec!["render", "tolkowsky", "-o", "x.png"];
    v.extend_from_slice(extra);
    Cli::try_parse_from(v).unwrap().args
}

/// A laboratory picture's settings from the flags (as `run` reads them).
fn lab_settings(
    a: &RenderArgs,
) -> facetlab::error::Result<(
    facetlab::render::LabPictures,
    facetlab::metrics::StoneChoice,
)> {
    settings(a).map(|(p, stone)| match p {
        facetlab::render::Pictures::Lab(p) => (p, stone),
        facetlab::render::Pictures::Photo(_) => panic!("a photograph"),
    })
}

/// The line a user sees for `extra`: a typed flag's refusal, else the settings' error.
fn first_error(extra: &[&str]) -> String {
    let mut v = vec!["render", "tolkowsky", "-o", "x.png"];
    v.extend_from_slice(extra);
    match Cli::try_parse_from(v) {
        Err(e) => crate::cli::flags::refused_value(&e).unwrap(),
        Ok(c) => lab_settings(&c.args).unwrap_err().to_string(),
    }
}

#[test]
fn defaults_and_flags_become_render_options() {
    let (s, _) = lab_settings(&parse(&[])).unwrap();
    assert_eq!(s.opts.light, Light::Iso);
    assert_eq!(s.opts.size, 512);
    assert_eq!(s.opts.tilt, Tilt::FACE_UP);
    assert_eq!((s.exposure, s.frames()), (1.0, 1));
    let (s, _) = lab_settings(&parse(&[
        "--light",
        "ASET",
        "--size",
        "64",
        "--tilt",
        "10@45",
        "--rock",
        "15:24",
        "--head-shadow",
        "12",
        "--ri",
        "1.54",
        "--polarization",
        "off",
    ]))
    .unwrap();
    assert_eq!(s.opts.light, Light::Aset);
    assert_eq!(
        s.opts.tilt,
        Tilt {
            tilt_deg: 10.0,
            azimuth_deg: 45.0
        }
    );
    assert_eq!(s.rock, Some((15.0, 24)));
    assert_eq!(s.opts.head_shadow(), 12.0);
    assert!(!s.opts.trace.polarization && s.opts.material.ri(500.0) == 1.54);
    // A quarter period in: the full amplitude on top of the base tilt.
    assert!((s.frame_tilt(6).tilt_deg - 25.0).abs() < 1e-9);
    assert!((s.frame_tilt(18).tilt_deg + 5.0).abs() < 1e-9);
    assert_eq!(s.frame_tilt(0).azimuth_deg, 45.0);
    assert_eq!(delay_ms(24, false), 100);
}

#[test]
fn bad_flags_are_one_line_naming_the_flag() {
    for (extra, flag) in [
        (&["--light", "sun"][..], "--light"),
        (&["--size", "4"], "--size"),
        (&["--size", "big"], "--size"),
        (&["--tilt", "x"], "--tilt"),
        (&["--tilt", "95"], "--tilt"),
        (&["--tilt", "10@"], "--tilt"),
        (&["--tilt", "10@45@3"], "--tilt"),
        (&["--tilt", "NaN"], "--tilt"),
        (&["--rock", "0:10"], "--rock"),
        (&["--rock", "61:10"], "--rock"),
        (&["--rock", "10:1"], "--rock"),
        (&["--rock", "10:241"], "--rock"),
        (&["--rock", "10"], "--rock"),
        (&["--rock", "40:10", "--tilt", "60"], "--rock"),
        (&["--rock", "10:240", "--size", "2048"], "--rock"),
        (&["--head-shadow", "70"], "--head-shadow"),
        (&["--ri", "0.5"], "--ri"),
        (&["--material", "kryptonite"], "--material"),
        (&["--polarization", "maybe"], "--polarization"),
        (&["--exposure", "0"], "--exposure"),
        (&["--colour", "teal"], "--colour"),
        (&["--colour-density", "2"], "--colour-density"),
        (&["--size-mm", "0"], "--size-mm"),
    ] {
        let e = first_error(extra);
        assert!(e.starts_with(flag), "{extra:?}: {e}");
        assert!(!e.contains('\n'), "{e}");
    }
}

#[test]
fn captions_carry_the_statistics() {
    let s = Stats {
        mean: 0.5,
        aset: Some(render::AsetShares {
            blue: 0.4,
            red: 0.3,
            green: 0.1,
            leak: 0.15,
            port: 0.05,
        }),
        ..Stats::default()
    };
    let l = stats_lines(Light::Aset, &s);
    assert!(
        l[0].contains("blue 40.0") && l[1].contains("port 5.0"),
        "{l:?}"
    );
    assert_eq!(stats_lines(Light::Iso, &s), vec!["iso mean 50.0 %"]);
    let f = Stats {
        fire: Some(0.75),
        ..s
    };
    assert!(stats_lines(Light::Fire, &f)[0].starts_with("placement fire 0.75"));
    let (s, _) = lab_settings(&parse(&[
        "--light",
        "cos",
        "--head-shadow",
        "15",
        "--exposure",
        "2",
    ]))
    .unwrap();
    assert_eq!(
        settings_line(&s.opts, s.exposure).as_deref(),
        Some("head shadow 15°, exposure ×2")
    );
    let (s, _) = lab_settings(&parse(&["--light", "aset", "--exposure", "2"])).unwrap();
    assert_eq!(settings_line(&s.opts, s.exposure), None);
}
