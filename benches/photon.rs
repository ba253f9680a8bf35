//! Photon tracer throughput: `tolkowsky`, directed light straight down (a beam just covering
//! the stone), depth 6, the thesis's absorption roulette, polarization off and on, on 1 and
//! 2 threads. Plain `Instant` timing after a warm-up; prints photons shot per second.
//!
//! `cargo bench --bench photon` (release). `PHOTONS=N` sets the photons per timed run.

use facetlab::photon::{trace, Light, TraceConfig};
use std::time::Instant;

/// CPU seconds used by this process so far (Linux `/proc/self/stat`, 100 ticks/s); `None`
/// elsewhere. Shown beside wall-clock time because the machine may be shared.
fn cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/stat").ok()?;
    let rest = &s[s.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks: f64 = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

fn main() {
    let cut = facetlab::io::load_cut("tolkowsky").expect("preset");
    let light = Light::directed(0.0);
    let photons: u64 = std::env::var("PHOTONS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20_000_000);
    println!(
        "tolkowsky, directed light at 0°, depth 6, thesis absorption; {photons} photons per run"
    );
    for pol in [false, true] {
        for threads in [1usize, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool");
            let cfg = TraceConfig {
                photons,
                polarization: pol,
                ..TraceConfig::thesis()
            };
            let warm = TraceConfig {
                photons: photons / 10,
                ..cfg.clone()
            };
            pool.install(|| trace(&cut.solid, &light, &warm, None).expect("trace"));
            let start = Instant::now();
            let cpu0 = cpu_seconds();
            let t = pool.install(|| trace(&cut.solid, &light, &cfg, None).expect("trace"));
            let s = start.elapsed().as_secs_f64();
            let cpu = cpu_seconds()
                .zip(cpu0)
                .map(|(a, b)| a - b)
                .filter(|c| *c > 0.0);
            println!(
                "polarization {:3}, {threads} thread{}: {:7.2} M photons/s wall ({:.2} s), {} M photons per CPU-second; {} hit, light return {:.4}",
                if pol { "on" } else { "off" },
                if threads == 1 { " " } else { "s" },
                photons as f64 / s / 1e6,
                s,
                cpu.map(|c| format!("{:5.2}", photons as f64 / c / 1e6)).unwrap_or_else(|| "?".into()),
                t.counts.hit,
                t.light_return().0
            );
        }
    }
}
