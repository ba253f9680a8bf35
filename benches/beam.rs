//! Beam tracer benchmarks (Instant-based, with warm-up). Run: `cargo bench --bench beam`.
//!
//! Reports: one pose at one wavelength for `tolkowsky` on one thread.

use facetlab::beam::{Frame, Stone, TraceOptions};
use std::time::{Duration, Instant};

fn time<F: FnMut()>(mut f: F, min_time: Duration) -> (Duration, usize) {
    // Warm-up.
    let t0 = Instant::now();
    while t0.elapsed() < min_time / 4 {
        f();
    }
    let t0 = Instant::now();
    let mut n = 0;
    while t0.elapsed() < min_time || n < 5 {
        f();
        n += 1;
    }
    (t0.elapsed() / n as u32, n)
}

fn main() {
    let cut = facetlab::io::load_cut("tolkowsky").expect("preset");
    let stone = Stone::new(&cut.solid);
    let ri = facetlab::optics::Material::diamond().ri(589.3);
    let frame = Frame::overhead();
    let filter = std::env::args().nth(1).filter(|a| !a.starts_with('-'));
    let run = |name: &str| filter.as_deref().is_none_or(|f| name.contains(f));
    if run("pose") {
        for split in [1e-3, 1e-4, 1e-5] {
            let opts = TraceOptions {
                split_threshold: split,
                ..Default::default()
            };
            let tree = stone.trace(&frame, ri, 589.3, &opts);
            let (dt, n) = time(
                || {
                    std::hint::black_box(stone.trace(&frame, ri, 589.3, &opts));
                },
                Duration::from_secs(2),
            );
            println!(
                "pose tolkowsky 589.3nm split {split:e}: {:.3} ms/trace ({n} runs), beams {} rays {} exits {} cut-off {:.1e}",
                dt.as_secs_f64() * 1e3,
                tree.stats.beams,
                tree.stats.rays,
                tree.stats.exits,
                tree.stats.cut_off
            );
        }
    }
}
