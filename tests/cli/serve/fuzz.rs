//! A fuzz loop against `facetlab serve`: random and broken requests must be refused one by
//! one, never kill the server.

use super::*;
use rand::{Rng, SeedableRng};

#[test]
fn serve_survives_a_fuzz_loop() {
    let mut s = Server::start();
    let mut rng = rand::rngs::SmallRng::seed_from_u64(20261201);
    // Cheap valid bodies to mutate: small pictures, quick scores.
    let seeds = [
        (
            "/api/render",
            r#"{"cut": "princess", "set": {"crown_angle": 35}, "light": "iso", "size": 16, "tilt": 3}"#,
        ),
        ("/api/score", r#"{"cut": "sphere", "quick": true}"#),
        (
            "/api/cut",
            r#"{"cut": "tolkowsky", "set": {"table": 0.55, "star": 0.5}}"#,
        ),
        ("/api/export", r#"{"cut": "oval", "to": "asc"}"#),
        (
            "/api/cut",
            r#"{"cut": "g 96 0.0\nI 2.42\na 41.0 0.5 0 24 48 72 n crown\na 0 0.3 0 n table\na -41.0 0.5 0 24 48 72 n pav\n", "format": "asc", "name": "oct.asc"}"#,
        ),
        (
            "/api/cut",
            r#"{"cut": "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\nf 1 3 5\nf 2 4 6\n", "format": "obj"}"#,
        ),
        (
            "/api/cut",
            r#"{"cut": "family = \"round-brilliant\"\n[params]\ntable = 0.5\n", "format": "toml"}"#,
        ),
        (
            "/api/cut",
            r#"{"cut": "c29saWQ=", "format": "stl", "encoding": "base64"}"#,
        ),
    ];
    let junk: [&str; 14] = [
        "null",
        "1e999",
        "-1",
        "0",
        "\"\"",
        "[]",
        "{}",
        "true",
        "\"../../../etc/passwd\"",
        "18446744073709551616",
        "[[[[[[[[[[[[[[[[[[[[]]]]]]]]]]]]]]]]]]]]",
        "\"\\u0000\"",
        "3.5",
        "\"NaN\"",
    ];
    let keys = [
        "cut", "format", "encoding", "name", "set", "light", "size", "tilt", "quick", "to",
        "exposure",
    ];
    let paths = [
        "/api/cut",
        "/api/render",
        "/api/export",
        "/api/score",
        "/api/nothing",
    ];
    let t = Instant::now();
    let (mut ok, mut refused) = (0, 0);
    for i in 0..400 {
        let (path, seed) = seeds[rng.random_range(0..seeds.len())];
        let mut path = path.to_string();
        let mut body: Vec<u8> = seed.as_bytes().to_vec();
        match i % 4 {
            // Byte mutations: flips, deletions, insertions, truncation.
            0 => {
                for _ in 0..rng.random_range(1..6) {
                    let k = rng.random_range(0..body.len());
                    match rng.random_range(0..4) {
                        0 => body[k] = rng.random(),
                        1 => {
                            body.remove(k);
                        }
                        2 => body.insert(k, b"{}[]\",:0-e\\"[rng.random_range(0..11)]),
                        _ => body.truncate(k),
                    }
                    if body.is_empty() {
                        break;
                    }
                }
            }
            // Structured: a valid object with a field replaced by junk.
            1 | 2 => {
                let mut v: serde_json::Value = serde_json::from_str(seed).unwrap();
                let k = keys[rng.random_range(0..keys.len())];
                let j: serde_json::Value =
                    serde_json::from_str(junk[rng.random_range(0..junk.len())]).unwrap_or_default();
                if k == "set" && rng.random_bool(0.5) {
                    v["set"] = serde_json::json!({ "pavilion_angle": j });
                } else {
                    v[k] = j;
                }
                if k == "quick" || k == "size" {
                    // Keep the work small when a junk value happens to be valid.
                    v["size"] = serde_json::json!(16);
                    path = "/api/render".into();
                }
                body = v.to_string().into_bytes();
            }
            // Random bytes to a random endpoint.
            _ => {
                let n = rng.random_range(0..200);
                body = (0..n).map(|_| rng.random()).collect();
                path = paths[rng.random_range(0..paths.len())].to_string();
            }
        }
        let r = try_request(&s.addr, "POST", &path, &body).unwrap_or_else(|e| {
            panic!(
                "request {i} failed ({e}): {}",
                String::from_utf8_lossy(&body)
            )
        });
        assert!(
            r.status < 500,
            "request {i} to {path}: status {} for {}: {}",
            r.status,
            String::from_utf8_lossy(&body),
            String::from_utf8_lossy(&r.body)
        );
        if r.status == 200 {
            ok += 1;
        } else {
            refused += 1;
            let j = r.json();
            assert!(j["error"].is_string() && j["field"].is_string(), "{j}");
        }
    }
    eprintln!(
        "fuzz: 400 requests in {:.1} s, {ok} answered, {refused} refused",
        t.elapsed().as_secs_f64()
    );
    assert!(ok >= 20 && refused > 100, "{ok} {refused}");
    assert!(s.alive(), "the server died");
}
