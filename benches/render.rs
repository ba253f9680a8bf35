//! Speed of the renderer: an 800×800 face-up ISO picture of tolkowsky at one wavelength, an
//! 8-band fire picture, and a 31-frame 512² rocking animation (the frames `facetlab render
//! --rock 10:31` draws). Prints each time with the trace's share. Then the same pictures as
//! a user waits for them: whole `facetlab render` processes (start-up, the picture, captions,
//! PNG encoding and writing), best of several runs (`-- commands`; the binary is built with the
//! bench).
//!
//! `cargo bench --bench render` (add `-- quick` for fewer repetitions, `-- instructions` for
//! one picture to count under callgrind).

use facetlab::beam::{Frame, Stone};
use facetlab::geometry::canonical::canonical;
use facetlab::render::{render, Light, RenderOptions, Tilt};
use std::time::Instant;

fn best_of(reps: usize, mut f: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..reps {
        let t = Instant::now();
        f();
        best = best.min(t.elapsed().as_secs_f64());
    }
    best
}

fn main() {
    // `instructions`: one 800² ISO picture and nothing else, to count instructions under
    // callgrind (`valgrind --tool=callgrind target/release/deps/render-… instructions`), which
    // unlike times does not depend on what else the machine is doing.
    if std::env::args().any(|a| a == "instructions") {
        let cut = facetlab::io::load_cut("tolkowsky").expect("preset");
        let mut iso = RenderOptions::new(Light::Iso);
        iso.size = 800;
        let img = render(&cut.solid, &iso);
        println!(
            "instructions: one 800² iso picture, mean {:.6}",
            img.stats.mean
        );
        return;
    }
    let quick = std::env::args().any(|a| a == "quick");
    if std::env::args().any(|a| a == "commands") {
        return commands(if quick { 3 } else { 10 });
    }
    let reps = if quick { 3 } else { 10 };
    let cut = facetlab::io::load_cut("tolkowsky").expect("preset");
    let solid = &cut.solid;

    let mut iso = RenderOptions::new(Light::Iso);
    iso.size = 800;
    let t_iso = best_of(reps, || {
        std::hint::black_box(render(solid, &iso));
    });
    // The trace alone (with footprints), for the share of the time the pixels take.
    let c = canonical(solid);
    let stone = Stone::new(&c);
    let opts = iso.trace_options();
    let ri = iso.material.ri(589.3);
    let t_trace = best_of(reps, || {
        std::hint::black_box(stone.trace(&Frame::overhead(), ri, 589.3, &opts));
    });
    println!(
        "iso 800² face-up: {:.1} ms (target 65 ms), of which the trace {:.1} ms",
        t_iso * 1e3,
        t_trace * 1e3
    );

    for size in [512, 800] {
        let mut fire = RenderOptions::new(Light::Fire);
        fire.size = size;
        let t = best_of(reps.min(5), || {
            std::hint::black_box(render(solid, &fire));
        });
        println!("fire {size}², 8 bands: {:.1} ms (target 300 ms)", t * 1e3);
    }

    let frames = 31;
    let t_rock = best_of(if quick { 1 } else { 3 }, || {
        for k in 0..frames {
            let mut o = RenderOptions::new(Light::Iso);
            o.size = 512;
            o.tilt = Tilt {
                tilt_deg: 10.0 * (std::f64::consts::TAU * k as f64 / frames as f64).sin(),
                azimuth_deg: 0.0,
            };
            std::hint::black_box(render(solid, &o));
        }
    });
    println!(
        "rocking ±10°, {frames} frames of 512²: {:.2} s (target 3 s)",
        t_rock
    );
}

/// Whole `facetlab render` processes, best of `reps` wall times each: what a user waits for.
fn commands(reps: usize) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let out = dir.path().join("picture.png");
    let runs: [(&str, &[&str], &str); 3] = [
        ("render tolkowsky --size 800", &["--size", "800"], "60 ms"),
        (
            "render tolkowsky --light fire (512²)",
            &["--light", "fire"],
            "60 ms",
        ),
        (
            "render tolkowsky --rock 15:31 (512²)",
            &["--rock", "15:31"],
            "1 s",
        ),
    ];
    for (name, extra, target) in runs {
        let t = best_of(reps, || {
            let st = std::process::Command::new(env!("CARGO_BIN_EXE_facetlab"))
                .args(["render", "tolkowsky", "--quiet", "--force", "-o"])
                .arg(&out)
                .args(extra)
                .stdout(std::process::Stdio::null())
                .status()
                .expect("run facetlab");
            assert!(st.success(), "{name} failed");
        });
        println!(
            "whole process `{name}`: {:.1} ms (target {target})",
            t * 1e3
        );
    }
}
