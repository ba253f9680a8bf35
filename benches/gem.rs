//! Reading GemCad's binary `.gem` (target: a 1 MB file in ≤ 10 ms), beside the `.asc` text of
//! the same design read in the same run. Run: `cargo bench --bench gem`.
//!
//! The 1 MB design is made here, byte by byte as GemCad lays a file out: rings of 96 facets at
//! 0.5° steps of angle, each facet with four vertices (as many as a real design's facets have
//! on average), until the file passes 1 MiB (about 7,000 facets; a real design has 50–300).
//! Its `.asc` twin is written alongside. Reading is the file's bytes from disk to the design:
//! its facet planes, names, tiers and notes ([`facetlab::io::gem::read`] without building the
//! solid, which for 7,000 planes is a different matter). For scale, a bundled preset is also
//! read whole (`.gem` → the cut, its solid built and scaled) and written. `-- instructions`
//! reads the big file once, for counting instructions under callgrind.

mod common;

use common::median;
use facetlab::geometry::facet_normal;

fn push_str(b: &mut Vec<u8>, s: &str) {
    b.push(u8::try_from(s.len()).expect("short string"));
    b.extend_from_slice(s.as_bytes());
}

/// The big design as `.gem` bytes and as `.asc` text.
fn big_design() -> (Vec<u8>, String, usize) {
    let mut gem = Vec::new();
    let mut asc = String::from("GemCad 5.0\ng 96 0.0\ny 96 n\nI 1.54\nH Bench design\n");
    let mut facets = 0;
    let mut tier = 0i32;
    while gem.len() < 1 << 20 {
        tier += 1;
        let angle = -89.5 + 0.5 * f64::from(tier);
        let dist = 0.5 + 0.001 * f64::from(tier);
        asc += &format!("a {angle:.6} {dist:.8}");
        for i in 1..=96 {
            let az = 90.0 - 3.75 * f64::from(i);
            let p = facet_normal(angle.abs(), az, angle >= 0.0) / dist;
            for v in [p.x, p.y, p.z] {
                gem.extend_from_slice(&v.to_le_bytes());
            }
            gem.extend_from_slice(&tier.to_le_bytes());
            if i == 1 {
                push_str(&mut gem, &format!("T{tier}\tMeet the tier before"));
                asc += &format!(" {i} n T{tier}");
            } else {
                push_str(&mut gem, "\tMeet the tier before");
                asc += &format!(" {i}");
            }
            for k in 0..4 {
                gem.extend_from_slice(&1i32.to_le_bytes());
                for c in [p.x, p.y, f64::from(k)] {
                    gem.extend_from_slice(&c.to_le_bytes());
                }
            }
            gem.extend_from_slice(&0i32.to_le_bytes());
            facets += 1;
        }
        asc += " G Meet the tier before\n";
    }
    gem.extend_from_slice(&(-99999.0f64).to_le_bytes());
    for v in [96i32, 0, 96] {
        gem.extend_from_slice(&v.to_le_bytes());
    }
    gem.extend_from_slice(&1.54f64.to_le_bytes());
    gem.extend_from_slice(&0x7FFFu32.to_le_bytes());
    gem.extend_from_slice(&0.0f64.to_le_bytes());
    push_str(&mut gem, "Bench design");
    for _ in 0..7 {
        push_str(&mut gem, "");
    }
    (gem, asc, facets)
}

fn main() {
    let dir = std::env::temp_dir().join(format!("facetlab-gem-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp folder");
    let (gem, asc, facets) = big_design();
    let (gem_path, asc_path) = (dir.join("big.gem"), dir.join("big.asc"));
    std::fs::write(&gem_path, &gem).expect("write");
    std::fs::write(&asc_path, &asc).expect("write");
    let d = facetlab::io::gem::parse(&gem, "big.gem").expect("the big design reads");
    assert_eq!(d.planes.len(), facets);
    let read_gem = || {
        let bytes = std::fs::read(&gem_path).expect("read");
        facetlab::io::gem::parse(&bytes, "big.gem").expect("reads")
    };
    let read_asc = || {
        let bytes = std::fs::read(&asc_path).expect("read");
        facetlab::io::asc::parse(&bytes, "big.asc").expect("reads")
    };
    if std::env::args().any(|a| a == "instructions") {
        // One read, for counting instructions (valgrind --tool=callgrind).
        read_gem();
        let _ = std::fs::remove_dir_all(&dir);
        return;
    }
    // Warm the page cache and the allocator.
    read_gem();
    read_asc();
    let (mut tg, mut ta) = (Vec::new(), Vec::new());
    for _ in 0..5 {
        tg.push(median(11, || {
            read_gem();
        }));
        ta.push(median(11, || {
            read_asc();
        }));
    }
    tg.sort_by(f64::total_cmp);
    ta.sort_by(f64::total_cmp);
    let (g, a) = (tg[2], ta[2]);
    println!(
        "1 MB .gem ({} bytes, {facets} facets) read to its design: {:.2} ms (target ≤ 10 ms); its .asc ({} bytes): {:.2} ms; .gem/.asc {:.2}",
        gem.len(),
        g * 1e3,
        asc.len(),
        a * 1e3,
        g / a
    );
    for name in ["tolkowsky", "oval"] {
        let cut = facetlab::io::load_cut(name).expect("preset");
        let bytes = facetlab::io::gem::write(&cut, 0).expect("writes");
        let path = dir.join(format!("{name}.gem"));
        std::fs::write(&path, &bytes).expect("write");
        let read = median(21, || {
            facetlab::io::gem::read(&path).expect("reads");
        });
        let write = median(21, || {
            facetlab::io::gem::write(&cut, 0).expect("writes");
        });
        println!(
            "{name}.gem ({} bytes, {} facets): read to the cut {:.3} ms, written {:.3} ms",
            bytes.len(),
            cut.solid.facets().len(),
            read * 1e3,
            write * 1e3
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
