//! Beam tracer benchmarks (Instant-based, with warm-up). Run: `cargo bench --bench beam`
//! (optionally with a filter: `pose`, `score`, `photons`).
//!
//! Reports:
//! * `pose`: one pose (overhead / face-up, where the stone's 16 symmetries apply) at one
//!   wavelength for `tolkowsky`, one thread, at several split thresholds (the default is
//!   1e-4), with the tree's size; a tilted pose (no symmetry), also at the scores' settings (their
//!   ray floor), with its narrow beams cut off (the exact part alone), a fire band's face-up
//!   trace with and without its narrow beams; the paper's depth-8 setting;
//! * `score`: the full default `score` of `tolkowsky` on the global rayon pool and on one thread,
//!   without fire and scintillation (what the default optimize's search computes), and as a
//!   coloured stone (blue sapphire against colourless sapphire, one thread, and their ratio);
//! * `birefringence`: the full default score of birefringent stones (sapphire, zircon; the
//!   optic axis up, in the table, tilted) against the same stones at their ordinary index
//!   alone, one thread, as alternated ratios (issue 41's ≤ 3× target), and what the pruning
//!   leaves out (a face-up trace at the scores' settings, on and off: the light handed to
//!   narrow rays, the light cut off, the rays' segments);
//! * `topology`: how much of fire's band traces' exit power follows facet sequences that
//!   every band's trace has (exact beams and narrow rays apart);
//! * `instructions` (only when named): ten tilted traces with no timing loop, to run under
//!   `valgrind --tool=callgrind` for repeatable instruction counts; `instructions-exact` the
//!   same with the narrow beams cut off (the difference over the segments is a narrow-ray
//!   segment's cost), `instructions-score` one default score on one thread;
//! * `photons`: how many photons a Monte Carlo photon tracer needs to match the beam tracer's
//!   `overhead_light_return` to 1e-4 (one standard error), and the time ratio, measured with
//!   the real photon tracer (`facetlab::photon::trace`: directed light from above, unpolarized,
//!   no absorption, one wavelength).

use facetlab::beam::{Frame, Medium, Stone, TraceOptions};
use facetlab::metrics::{overhead_light_return_with, score, ScoreConfig};
use std::time::{Duration, Instant};

fn time<F: FnMut()>(mut f: F, min_time: Duration) -> (Duration, usize) {
    let t0 = Instant::now();
    while t0.elapsed() < min_time / 4 {
        f();
    }
    let t0 = Instant::now();
    let mut n = 0;
    while t0.elapsed() < min_time || n < 3 {
        f();
        n += 1;
    }
    (t0.elapsed() / n as u32, n)
}

fn main() {
    let cut = facetlab::io::load_cut("tolkowsky").expect("preset");
    let solid = &cut.solid;
    let stone = Stone::new(solid);
    let ri = facetlab::optics::Material::diamond().ri(589.3);
    let frame = Frame::overhead();
    let filter = std::env::args().skip(1).find(|a| !a.starts_with('-'));
    let run = |name: &str| filter.as_deref().is_none_or(|f| name.contains(f));
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    println!("rayon threads: {}", rayon::current_num_threads());
    // One trace of tolkowsky at 589.3 nm (its tree, for the counts) and its time per trace.
    let trace_timed = |frame: &Frame, opts: &TraceOptions| {
        let tree = stone.trace(frame, ri, 589.3, opts);
        let (dt, n) = time(
            || {
                std::hint::black_box(stone.trace(frame, ri, 589.3, opts));
            },
            Duration::from_secs(2),
        );
        (tree, dt, n)
    };

    if run("pose") {
        for split in [1e-3, 1e-4, 1e-5] {
            let opts = TraceOptions {
                split_threshold: split,
                ..Default::default()
            };
            let (tree, dt, n) = trace_timed(&frame, &opts);
            println!(
                "pose tolkowsky 589.3 nm, split {split:e}: {:.3} ms/trace ({n} runs); beams {}, rays {} \
                 ({} segments), exits {}, cut-off {:.1e}, light return {:.6}",
                dt.as_secs_f64() * 1e3,
                tree.stats.beams,
                tree.stats.rays,
                tree.stats.ray_segments,
                tree.stats.exits,
                tree.stats.cut_off,
                tree.exits.iter().filter(|e| e.direction.z > 0.0).map(|e| e.power).sum::<f64>()
            );
        }
        // A tilted view (10° toward azimuth 30°): no symmetry left to use.
        let tilted = facetlab::beam::Frame::viewer(
            facetlab::metrics::Tilt {
                tilt_deg: 10.0,
                azimuth_deg: 30.0,
            }
            .rotation(),
        );
        let opts = TraceOptions::default();
        let (tree, dt, n) = trace_timed(&tilted, &opts);
        println!(
            "pose tolkowsky tilted 10° (no symmetry), split 1e-4: {:.3} ms/trace ({n} runs); beams {}, rays {} ({} segments), exits {}",
            dt.as_secs_f64() * 1e3,
            tree.stats.beams,
            tree.stats.rays,
            tree.stats.ray_segments,
            tree.stats.exits
        );
        // The same pose as the scores trace it: narrow beams' rays stop at the score's ray
        // floor (the rest is handed back with the late exits' mean).
        let opts = facetlab::metrics::ScoreConfig::default().trace;
        let (tree, dt2, n) = trace_timed(&tilted, &opts);
        println!(
            "pose tolkowsky tilted 10°, the scores' settings (ray floor {}): {:.3} ms/trace ({n} \
             runs, {:.2} of the above); rays {} ({} segments), closed {:.1e}",
            opts.ray_floor,
            dt2.as_secs_f64() * 1e3,
            dt2.as_secs_f64() / dt.as_secs_f64(),
            tree.stats.rays,
            tree.stats.ray_segments,
            tree.stats.ray_closed
        );
        // The same with every narrow beam cut off instead of followed: the exact part alone,
        // what the trace would cost if narrow rays cost nothing.
        let exact_part = TraceOptions {
            threshold: opts.split_threshold,
            ..opts
        };
        let (_, dt4, n) = trace_timed(&tilted, &exact_part);
        println!(
            "pose tolkowsky tilted 10°, the scores' settings with narrow beams cut off (the exact \
             part alone): {:.3} ms/trace ({n} runs, {:.2} of the scores' settings)",
            dt4.as_secs_f64() * 1e3,
            dt4.as_secs_f64() / dt2.as_secs_f64(),
        );
        // One of fire's band traces as the scores make it (face-up, split to the fire split
        // threshold), with its narrow rays and without: the trace alone (the scores also draw
        // each exit's footprint into fire's pictures, which this collecting sink does not).
        let cfg = ScoreConfig::default();
        let fire_opts = TraceOptions {
            split_threshold: cfg.fire_split_threshold,
            ..cfg.trace
        };
        let (tree, dt5, n) = trace_timed(&frame, &fire_opts);
        let (_, dt6, _) = trace_timed(
            &frame,
            &TraceOptions {
                threshold: fire_opts.split_threshold,
                ..fire_opts
            },
        );
        println!(
            "pose tolkowsky face-up, a fire band's settings (split {:e}, no footprints): {:.3} ms/trace ({n} runs); \
             rays {} ({} segments); narrow beams cut off: {:.3} ms ({:.2})",
            fire_opts.split_threshold,
            dt5.as_secs_f64() * 1e3,
            tree.stats.rays,
            tree.stats.ray_segments,
            dt6.as_secs_f64() * 1e3,
            dt6.as_secs_f64() / dt5.as_secs_f64(),
        );
        // The narrow beams as forking discs (`[score] narrow_forks`), at the split threshold
        // and ray floor they are measured with.
        let opts = TraceOptions {
            narrow_forks: true,
            split_threshold: 3e-4,
            ray_floor: 0.02,
            ..opts
        };
        let (tree, dt3, n) = trace_timed(&tilted, &opts);
        println!(
            "pose tolkowsky tilted 10°, narrow beams forking (split 3e-4, ray floor 0.02): \
             {:.3} ms/trace ({n} runs, {:.2} of the scores' settings); rays {} ({} segments)",
            dt3.as_secs_f64() * 1e3,
            dt3.as_secs_f64() / dt2.as_secs_f64(),
            tree.stats.rays,
            tree.stats.ray_segments,
        );
        // The paper's setting: exact splitting, depth 8, nothing below 1e-6.
        let opts = TraceOptions {
            max_depth: 8,
            ..TraceOptions::exact(1e-6)
        };
        let (tree, dt, n) = trace_timed(&frame, &opts);
        println!(
            "pose tolkowsky, exact to depth 8 (paper-style): {:.3} ms/trace ({n} runs); beams {}, cut-off {:.2e}",
            dt.as_secs_f64() * 1e3,
            tree.stats.beams,
            tree.stats.cut_off
        );
    }

    // How far fire's band traces share their beam tree (the lever of tracing the bands as one
    // traversal): per band, the share of its exit power whose facet sequence every band's
    // trace also has, for the exact exits and the narrow rays' exits apart.
    if run("birefringence") {
        // Issue 41's speed: a birefringent score against the same stone traced at its
        // ordinary index alone (`--birefringence off`), one thread, alternated (off, on, off,
        // on, …) and the median ratio taken, so that a loaded machine moves both alike. The
        // axis up keeps the stone's symmetry; tilted ones keep fewer turns (90@0: the mirror
        // through the axis; 35@20: none), which costs the birefringent trace its wedge.
        let stones = [
            ("sapphire", "tolkowsky", "0"),
            ("zircon", "princess", "0"),
            ("zircon", "princess", "90@0"),
            ("zircon", "princess", "35@20"),
        ];
        for (material, preset, axis) in stones {
            let cut = facetlab::io::load_cut(preset).expect("preset");
            let mut m = facetlab::optics::Material::by_name(material).expect("material");
            let u = m.uniaxial.as_mut().expect("uniaxial");
            u.axis = facetlab::optics::OpticAxis::parse(axis, "axis").expect("axis");
            let mut ratios = Vec::new();
            let mut times = [Vec::new(), Vec::new()];
            for _ in 0..3 {
                for (k, traced) in [false, true].into_iter().enumerate() {
                    let mut mk = m.clone();
                    mk.uniaxial.as_mut().expect("uniaxial").traced = traced;
                    let cfg = ScoreConfig {
                        material: mk,
                        ..ScoreConfig::default()
                    };
                    let (dt, _) = time(
                        || {
                            one.install(|| std::hint::black_box(score(&cut.solid, &cfg)));
                        },
                        Duration::from_secs(2),
                    );
                    times[k].push(dt.as_secs_f64());
                }
                let n = times[0].len() - 1;
                ratios.push(times[1][n] / times[0][n]);
            }
            // What pruning leaves out: one face-up trace at the scores' settings, on and
            // off — the light handed to narrow rays (found by one ray each, not split
            // exactly), the light cut off (below the threshold, past the depth limit or the
            // ray floor), and the segments the rays ran.
            let stone_b = Stone::new(&cut.solid);
            let opts = ScoreConfig::default().trace;
            let c = m.uniaxial.as_ref().expect("uniaxial").axis.vector();
            for traced in [false, true] {
                let mut mk = m.clone();
                mk.uniaxial.as_mut().expect("uniaxial").traced = traced;
                let medium = Medium::of(&mk, 589.3, c, 0.0, false);
                let tree = stone_b.trace_medium(&frame, &medium, 589.3, &opts);
                let st = &tree.stats;
                println!(
                    "  face-up trace at the scores' settings, birefringence {}: exact beams {}, \
                     rays {} ({} segments), light to rays {:.4}, cut off {:.2e} (of it ray floor \
                     {:.2e}) of power in {:.6}",
                    if traced { "on " } else { "off" },
                    st.beams,
                    st.rays,
                    st.ray_segments,
                    st.ray_power,
                    st.cut_off,
                    st.ray_closed,
                    st.power_in
                );
            }
            ratios.sort_by(f64::total_cmp);
            let med = |v: &mut Vec<f64>| {
                v.sort_by(f64::total_cmp);
                v[v.len() / 2] * 1e3
            };
            println!(
                "score {preset} in {material}, optic axis {axis}, 1 thread: off {:.0} ms, on {:.0} ms \
                 (median ratio of 3 alternated pairs {:.2}×; target ≤ 3×)",
                med(&mut times[0]),
                med(&mut times[1]),
                ratios[1]
            );
        }
    }

    if run("topology") {
        let cfg = ScoreConfig::default();
        let opts = TraceOptions {
            split_threshold: cfg.fire_split_threshold,
            ..cfg.trace
        };
        let bands =
            facetlab::optics::color::traced_bands(cfg.bands, facetlab::optics::color::FAINT_BAND);
        type Seqs = std::collections::HashMap<(bool, Vec<usize>), f64>;
        let trees: Vec<Seqs> = bands
            .iter()
            .map(|&(l, _)| {
                let tree = stone.trace(&frame, cfg.material.ri(l), l, &opts);
                let mut m = Seqs::new();
                for e in &tree.exits {
                    *m.entry((e.narrow, tree.sequence(e))).or_default() += e.power;
                }
                m
            })
            .collect();
        for narrow in [false, true] {
            let (mut lo, mut hi, mut kinds) = (f64::INFINITY, 0.0f64, 0usize);
            for m in &trees {
                let (mut all, mut shared) = (0.0, 0.0);
                for ((nw, seq), p) in m {
                    if *nw != narrow {
                        continue;
                    }
                    all += p;
                    // A narrow ray's sequence counts as shared when every band has it,
                    // narrow or exact.
                    let key = |w: bool| (w, seq.clone());
                    if trees
                        .iter()
                        .all(|o| o.contains_key(&key(false)) || o.contains_key(&key(true)))
                    {
                        shared += p;
                    }
                }
                let f = if all > 0.0 { shared / all } else { 1.0 };
                lo = lo.min(f);
                hi = hi.max(f);
                kinds = kinds.max(m.keys().filter(|k| k.0 == narrow).count());
            }
            println!(
                "topology: tolkowsky face-up, {} fire bands at split {:e}: {} exits' power in facet \
                 sequences every band has: {:.4}–{:.4} of each band's (up to {kinds} sequences a band)",
                bands.len(),
                opts.split_threshold,
                if narrow { "narrow rays'" } else { "exact beams'" },
                lo,
                hi
            );
        }
    }

    // Exactly ten traces of the tilted pose and nothing else, no timing loop: for instruction
    // counts (`valgrind --tool=callgrind …/beam-… --bench instructions`), which unlike the
    // wall clock do not swing with the machine's load. Only on request.
    // `instructions-exact` runs the same ten traces with every narrow beam cut off instead of
    // followed (the exact part alone): the difference of the two counts over the segments is
    // what a narrow-ray segment costs. `instructions-score` runs one default score of
    // tolkowsky on one thread.
    if let Some(which) = filter.as_deref().filter(|f| f.starts_with("instructions")) {
        let exact = which.ends_with("-exact");
        if which.starts_with("instructions-score") {
            let cfg = ScoreConfig::default();
            let s = one.install(|| std::hint::black_box(score(solid, &cfg)));
            println!(
                "{which}: one default score of tolkowsky done (brilliance {:.6})",
                s.brilliance
            );
        } else {
            let tilted = facetlab::beam::Frame::viewer(
                facetlab::metrics::Tilt {
                    tilt_deg: 10.0,
                    azimuth_deg: 30.0,
                }
                .rotation(),
            );
            let opts = TraceOptions::default();
            let opts = if exact {
                TraceOptions {
                    threshold: opts.split_threshold,
                    ..opts
                }
            } else {
                opts
            };
            let mut segments = 0;
            for _ in 0..10 {
                segments += std::hint::black_box(stone.trace(&tilted, ri, 589.3, &opts))
                    .stats
                    .ray_segments;
            }
            println!("{which}: 10 tilted traces done ({segments} narrow-ray segments)");
        }
    }

    if run("score") {
        let cfg = ScoreConfig::default();
        let (dt, n) = time(
            || {
                std::hint::black_box(score(solid, &cfg));
            },
            Duration::from_secs(4),
        );
        println!(
            "score tolkowsky, default config: {:.1} ms ({n} runs, global pool)",
            dt.as_secs_f64() * 1e3
        );
        let (dt1, n1) = time(
            || {
                one.install(|| std::hint::black_box(score(solid, &cfg)));
            },
            Duration::from_secs(4),
        );
        println!(
            "score tolkowsky, default config: {:.1} ms ({n1} runs, 1 thread)",
            dt1.as_secs_f64() * 1e3
        );
        // What the default optimize climbs: brilliance alone (fire and scintillation left out).
        let lean = ScoreConfig {
            parts: facetlab::metrics::Parts {
                fire: false,
                scintillation: false,
            },
            ..ScoreConfig::default()
        };
        let (dt, n) = time(
            || {
                std::hint::black_box(score(solid, &lean));
            },
            Duration::from_secs(4),
        );
        println!(
            "score tolkowsky, default config without fire and scintillation (the default \
             optimize's search): {:.1} ms ({n} runs, global pool)",
            dt.as_secs_f64() * 1e3
        );
        // A coloured stone (its face-up colour drawn on fire's band traces), as a ratio to
        // the same material colourless (issue 25: ≤ 1.5×), both on one thread.
        let blue = facetlab::optics::Material::by_name("blue-sapphire").expect("a variety");
        let mut ms = [0.0; 2];
        for (k, colour) in [None, blue.colour.clone()].into_iter().enumerate() {
            let cfg = ScoreConfig {
                material: facetlab::optics::Material {
                    colour,
                    ..blue.clone()
                },
                ..ScoreConfig::default()
            };
            let (dt, _) = time(
                || {
                    one.install(|| std::hint::black_box(score(solid, &cfg)));
                },
                Duration::from_secs(4),
            );
            ms[k] = dt.as_secs_f64() * 1e3;
        }
        println!(
            "score tolkowsky in sapphire, default config, 1 thread: colourless {:.1} ms, as a \
             blue sapphire {:.1} ms ({:.2}×)",
            ms[0],
            ms[1],
            ms[1] / ms[0]
        );
        let fast = ScoreConfig::fast();
        let (dt, n) = time(
            || {
                std::hint::black_box(score(solid, &fast));
            },
            Duration::from_secs(4),
        );
        println!(
            "score tolkowsky, ScoreConfig::fast(): {:.1} ms ({n} runs, global pool)",
            dt.as_secs_f64() * 1e3
        );
    }

    if run("photons") {
        // Beam tracer, unpolarized like the photon stand-in; accurate settings for the reference.
        let accurate = TraceOptions {
            polarization: false,
            split_threshold: 1e-5,
            ..Default::default()
        };
        let p = overhead_light_return_with(&stone, &Medium::Isotropic(ri), &accurate);
        let default = TraceOptions {
            polarization: false,
            ..Default::default()
        };
        let p_default = overhead_light_return_with(&stone, &Medium::Isotropic(ri), &default);
        let (beam_dt, _) = time(
            || {
                std::hint::black_box(overhead_light_return_with(
                    &stone,
                    &Medium::Isotropic(ri),
                    &default,
                ));
            },
            Duration::from_secs(2),
        );
        // The real photon tracer on the same light: directed straight down over the stone, no
        // absorption, unlimited depth, one wavelength, unpolarized; both threads.
        let pc = facetlab::photon::TraceConfig {
            photons: 4_000_000,
            until_hit: false,
            depth: None,
            absorption: facetlab::photon::Absorption::None,
            polarization: false,
            material: facetlab::optics::Material::diamond(),
            wavelengths: facetlab::photon::WavelengthSampling::Fixed(589.3),
            seed: 1,
            record_paths: 0,
        };
        let t0 = Instant::now();
        let t = facetlab::photon::trace(solid, &facetlab::photon::Light::directed(0.0), &pc, None)
            .expect("trace");
        let per_photon = t0.elapsed().as_secs_f64() / t.counts.hit as f64;
        let (q, se) = t.light_return();
        let hit = t.counts.hit;
        let need = p * (1.0 - p) / 1e-8;
        let photon_time = need * per_photon;
        println!(
            "photons: beam light return {p:.6} (split 1e-5; default settings {p_default:.6}, {:.2} ms), \
             photon tracer {q:.5} ± {se:.5} from {hit} photons ({:.3} µs/photon on {} threads, {:+.1} SE)",
            beam_dt.as_secs_f64() * 1e3,
            per_photon * 1e6,
            rayon::current_num_threads(),
            (q - p) / se
        );
        println!(
            "photons needed for a standard error of 1e-4: {need:.3e}, {photon_time:.1} s on this machine; \
             ratio to one default beam trace: {:.0}×",
            photon_time / beam_dt.as_secs_f64()
        );
    }
}
