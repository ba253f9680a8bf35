//! `facetlab serve`: the API as a client sees it (the built binary on a free port), a fuzz loop
//! that must not kill the server, and the page in a real browser (Chromium, when present).

use rand::{Rng, SeedableRng};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// The server as a child process; killed when dropped.
struct Server {
    child: Child,
    addr: String,
}

impl Server {
    /// Start `facetlab serve --port 0` and wait until it answers.
    fn start() -> Server {
        // FACETLAB_SERVE_BIN runs another build (a release build, to measure latency).
        let bin = std::env::var("FACETLAB_SERVE_BIN")
            .unwrap_or_else(|_| env!("CARGO_BIN_EXE_facetlab").to_string());
        let mut child = Command::new(bin)
            .args(["serve", "--port", "0"])
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("facetlab serve starts");
        let stdout = child.stdout.take().unwrap();
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let _ = BufReader::new(stdout).read_line(&mut line);
            let _ = tx.send(line);
        });
        let mut server = Server {
            child,
            addr: String::new(),
        };
        let line = rx
            .recv_timeout(Duration::from_secs(20))
            .expect("serve prints its URL");
        let url = line
            .split_whitespace()
            .find(|w| w.starts_with("http://"))
            .unwrap_or_else(|| panic!("no URL in {line:?}"));
        server.addr = url
            .trim_start_matches("http://")
            .trim_end_matches('/')
            .to_string();
        assert!(server.addr.starts_with("127.0.0.1:"), "{line}");
        let t = Instant::now();
        while t.elapsed() < Duration::from_secs(20) {
            if let Ok(r) = try_request(&server.addr, "GET", "/api/presets", b"") {
                if r.status == 200 {
                    return server;
                }
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        panic!("the server did not answer within 20 s");
    }

    fn get(&self, path: &str) -> Resp {
        try_request(&self.addr, "GET", path, b"").unwrap_or_else(|e| panic!("GET {path}: {e}"))
    }

    fn post(&self, path: &str, body: &str) -> Resp {
        try_request(&self.addr, "POST", path, body.as_bytes())
            .unwrap_or_else(|e| panic!("POST {path} {body}: {e}"))
    }

    fn alive(&mut self) -> bool {
        matches!(self.child.try_wait(), Ok(None)) && self.get("/api/presets").status == 200
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

struct Resp {
    status: u16,
    headers: Vec<(String, String)>,
    body: Vec<u8>,
}

impl Resp {
    fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(k, _)| k.eq_ignore_ascii_case(name))
            .map(|(_, v)| v.as_str())
    }
    fn json(&self) -> serde_json::Value {
        serde_json::from_slice(&self.body).unwrap_or_else(|e| {
            panic!(
                "not JSON ({e}): {}",
                String::from_utf8_lossy(&self.body[..self.body.len().min(300)])
            )
        })
    }
}

/// A minimal HTTP/1.1 client (one request per connection).
fn try_request(addr: &str, method: &str, path: &str, body: &[u8]) -> std::io::Result<Resp> {
    let mut s = TcpStream::connect(addr)?;
    s.set_read_timeout(Some(Duration::from_secs(120)))?;
    let head = format!(
        "{method} {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
        body.len()
    );
    s.write_all(head.as_bytes())?;
    // The server may answer (and close) before reading a refused body: write on another thread.
    let mut w = s.try_clone()?;
    let owned = body.to_vec();
    let writer = std::thread::spawn(move || {
        let _ = w.write_all(&owned);
    });
    let mut raw = Vec::new();
    let read = s.read_to_end(&mut raw);
    let _ = writer.join();
    if raw.is_empty() {
        read?;
    }
    parse_response(&raw)
}

fn parse_response(raw: &[u8]) -> std::io::Result<Resp> {
    let bad = |m: &str| std::io::Error::new(std::io::ErrorKind::InvalidData, m.to_string());
    let end = raw
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .ok_or_else(|| bad("no end of headers"))?;
    let head = String::from_utf8_lossy(&raw[..end]).to_string();
    let mut lines = head.lines();
    let status: u16 = lines
        .next()
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|c| c.parse().ok())
        .ok_or_else(|| bad("no status"))?;
    let headers: Vec<(String, String)> = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_string(), v.trim().to_string()))
        .collect();
    let mut body = raw[end + 4..].to_vec();
    let chunked = headers.iter().any(|(k, v)| {
        k.eq_ignore_ascii_case("transfer-encoding") && v.eq_ignore_ascii_case("chunked")
    });
    if chunked {
        let mut out = Vec::new();
        let mut rest = &body[..];
        loop {
            let nl = rest
                .windows(2)
                .position(|w| w == b"\r\n")
                .ok_or_else(|| bad("chunk"))?;
            let size = usize::from_str_radix(String::from_utf8_lossy(&rest[..nl]).trim(), 16)
                .map_err(|_| bad("chunk size"))?;
            if size == 0 {
                break;
            }
            let start = nl + 2;
            out.extend_from_slice(&rest[start..start + size]);
            rest = &rest[start + size + 2..];
        }
        body = out;
    }
    Ok(Resp {
        status,
        headers,
        body,
    })
}

/// Width and height of a PNG from its header.
fn png_size(b: &[u8]) -> (u32, u32) {
    assert_eq!(&b[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    let w = u32::from_be_bytes(b[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(b[20..24].try_into().unwrap());
    (w, h)
}

/// A 4xx JSON error whose `error` names `field`.
fn assert_error(r: &Resp, field: &str) -> String {
    assert!(
        (400..500).contains(&r.status),
        "status {} for a bad request: {}",
        r.status,
        String::from_utf8_lossy(&r.body)
    );
    let j = r.json();
    let e = j["error"].as_str().expect("an error message").to_string();
    assert!(
        e.starts_with(&format!("{field}:")),
        "`{e}` does not name {field}"
    );
    assert_eq!(j["field"].as_str(), Some(field), "{e}");
    assert!(!e.contains('\n'), "{e}");
    e
}

#[test]
fn serve_api_answers_and_refuses_bad_requests() {
    let mut s = Server::start();
    // Presets, families with ranges, the page and its assets.
    let p = s.get("/api/presets").json();
    let names: Vec<&str> = p["presets"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x["name"].as_str().unwrap())
        .collect();
    assert!(names.contains(&"tolkowsky") && names.contains(&"princess"));
    let round = p["families"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["name"] == "round-brilliant")
        .unwrap();
    let pav = round["params"]
        .as_array()
        .unwrap()
        .iter()
        .find(|x| x["key"] == "pavilion_angle")
        .unwrap();
    assert!(pav["min"].as_f64().unwrap() < 40.9 && pav["max"].as_f64().unwrap() > 40.9);
    let page = s.get("/");
    assert_eq!(page.status, 200);
    assert!(String::from_utf8_lossy(&page.body).contains("facetlab"));
    assert_eq!(s.get("/page.js").status, 200);
    assert_eq!(s.get("/page.css").status, 200);
    assert_error(&s.get("/etc/passwd"), "path");

    // A render is a PNG of the requested size.
    let r = s.post(
        "/api/render",
        r#"{"cut": "tolkowsky", "set": {"pavilion_angle": 40.9}, "light": "aset", "size": 96, "tilt": 5}"#,
    );
    assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
    assert_eq!(r.header("content-type"), Some("image/png"));
    assert_eq!(png_size(&r.body), (96, 96));

    // Scores have the keys of `score --json`; quick says so.
    let j = s
        .post("/api/score", r#"{"cut": "tolkowsky", "quick": true}"#)
        .json();
    for k in [
        "cut",
        "overhead_light_return",
        "brilliance",
        "brilliance_iso",
        "brilliance_cos",
        "fire",
        "scintillation",
        "settings",
    ] {
        assert!(j.get(k).is_some(), "no {k} in {j}");
    }
    for k in ["blue", "red", "green", "leak"] {
        assert!(j["aset"][k].as_f64().is_some(), "no aset.{k}");
    }
    assert_eq!(j["quick"], true);
    let b = j["brilliance"].as_f64().unwrap();
    assert!((0.2..1.0).contains(&b), "{b}");

    // The cut's info and diagram; downloads in every format, read back by the API.
    let info = s
        .post(
            "/api/cut",
            r#"{"cut": "tolkowsky", "set": {"table": 0.55}}"#,
        )
        .json();
    assert_eq!(info["family"], "round-brilliant");
    assert!((info["proportions"]["table"].as_f64().unwrap() - 0.55).abs() < 1e-9);
    assert!(info["svg"].as_str().unwrap().contains("<svg"));
    for to in ["asc", "obj", "stl", "toml"] {
        let r = s.post(
            "/api/export",
            &format!(r#"{{"cut": "tolkowsky", "to": "{to}"}}"#),
        );
        assert_eq!(r.status, 200, "{to}");
        assert!(
            r.header("content-disposition")
                .unwrap()
                .to_ascii_lowercase()
                .contains(&format!("filename=\"tolkowsky.{to}\"")),
            "{to}"
        );
        let body = if to == "stl" {
            serde_json::json!({"cut": b64(&r.body), "format": to, "encoding": "base64", "name": "back.stl"})
        } else {
            serde_json::json!({"cut": String::from_utf8(r.body).unwrap(), "format": to, "name": format!("back.{to}")})
        };
        let back = s.post("/api/cut", &body.to_string());
        assert_eq!(
            back.status,
            200,
            "{to}: {}",
            String::from_utf8_lossy(&back.body)
        );
        assert_eq!(back.json()["facet_count"], 73, "{to}");
    }
    // The one-page report, self-contained.
    let r = s.post("/api/export", r#"{"cut": "tolkowsky", "to": "html"}"#);
    assert_eq!(r.status, 200);
    assert!(r.header("content-type").unwrap().starts_with("text/html"));
    let page = String::from_utf8(r.body).unwrap();
    assert_eq!(page.matches("data:image/png;base64,").count(), 3);
    assert!(page.contains("Grade estimate"));

    // Bad bodies and fields: 4xx JSON naming the field.
    assert_error(&s.post("/api/score", "not json"), "body");
    assert_error(&s.post("/api/score", "[1, 2]"), "body");
    assert_error(&s.post("/api/score", "{}"), "cut");
    assert_error(&s.post("/api/score", r#"{"cut": 3}"#), "cut");
    let e = assert_error(&s.post("/api/score", r#"{"cut": "nosuch"}"#), "cut");
    assert!(e.contains("tolkowsky"), "{e}");
    assert_error(
        &s.post(
            "/api/render",
            r#"{"cut": "tolkowsky", "set": {"crown_angle": 75}}"#,
        ),
        "set.crown_angle",
    );
    assert_error(
        &s.post(
            "/api/render",
            r#"{"cut": "tolkowsky", "set": {"crown_angle": "x"}}"#,
        ),
        "set.crown_angle",
    );
    assert_error(
        &s.post(
            "/api/render",
            r#"{"cut": "tolkowsky", "set": {"tabel": 0.5}}"#,
        ),
        "set.tabel",
    );
    assert_error(
        &s.post("/api/render", r#"{"cut": "tolkowsky", "size": 100000}"#),
        "size",
    );
    assert_error(
        &s.post("/api/render", r#"{"cut": "tolkowsky", "size": -4}"#),
        "size",
    );
    assert_error(
        &s.post("/api/render", r#"{"cut": "tolkowsky", "tilt": 80}"#),
        "tilt",
    );
    assert_error(
        &s.post("/api/render", r#"{"cut": "tolkowsky", "light": "disco"}"#),
        "light",
    );
    assert_error(
        &s.post("/api/render", r#"{"cut": "tolkowsky", "exposure": 0}"#),
        "exposure",
    );
    assert_error(
        &s.post("/api/render", r#"{"cut": "tolkowsky", "colour": 1}"#),
        "colour",
    );
    assert_error(
        &s.post("/api/export", r#"{"cut": "tolkowsky", "to": "../x"}"#),
        "to",
    );
    assert_error(
        &s.post("/api/cut", r#"{"cut": "tolkowsky", "format": "exe"}"#),
        "format",
    );
    let e = assert_error(
        &s.post(
            "/api/cut",
            r#"{"cut": "g 96 0\na x3 1 2\n", "format": "asc"}"#,
        ),
        "cut",
    );
    assert!(e.contains("line"), "{e}");
    assert_error(
        &s.post(
            "/api/cut",
            r#"{"cut": "v 0 0 0\nv 1 0 0\n", "format": "obj", "name": "../../etc/passwd"}"#,
        ),
        "cut",
    );

    // More than 5 MB is refused, and the server lives on.
    let big = format!(r#"{{"cut": "{}", "format": "asc"}}"#, "x".repeat(6 << 20));
    match try_request(&s.addr, "POST", "/api/cut", big.as_bytes()) {
        Ok(r) => {
            assert_eq!(r.status, 413);
            assert_error(&r, "body");
        }
        // The server may close the connection before the whole body is sent.
        Err(e) => eprintln!("a 6 MB body: connection closed ({e})"),
    }
    assert!(s.alive());
}

/// Standard base64 (for sending a binary STL).
/// An optimization from the page's API: the bundled configs are listed; a small config runs
/// to the end with its convergence curve and report; a second start while one runs is
/// refused (409); a long run stops when asked and still reports; bad configs name the field.
#[test]
fn serve_runs_an_optimization() {
    let s = Server::start();
    let list = s.get("/api/configs").json();
    let names: Vec<&str> = list["configs"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|c| c["name"].as_str())
        .collect();
    assert!(names.contains(&"round-brilliance"), "{names:?}");
    assert_error(&s.get("/api/optimize"), "run");
    assert_error(
        &s.post("/api/optimize", r#"{"config": "../etc/passwd"}"#),
        "config",
    );
    assert_error(
        &s.post("/api/optimize", r#"{"config_text": "[cut]\nfamily = 3"}"#),
        "config_text",
    );
    assert_error(&s.post("/api/optimize", r#"{"path": "x"}"#), "path");
    let small = |evals: u32| {
        let text = format!(
            "name = \"small\"\n[cut]\nfamily = \"round-brilliant\"\n[free]\ntable = [0.52, 0.6]\n\
             [method]\nname = \"nelder-mead\"\nstarts = 1\nmax_evaluations = {evals}\n\
             [verify]\nwinners = 1\nphotons = 2000\n"
        );
        serde_json::json!({ "config_text": text }).to_string()
    };
    let wait = |want: &[&str]| -> serde_json::Value {
        for _ in 0..600 {
            let st = s.get("/api/optimize").json();
            if want.contains(&st["state"].as_str().unwrap_or("")) {
                return st;
            }
            std::thread::sleep(std::time::Duration::from_millis(200));
        }
        panic!("the run did not end");
    };
    let r = s.post("/api/optimize", &small(6));
    assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
    let st = wait(&["done", "failed"]);
    assert_eq!(st["state"], "done", "{st}");
    assert!(st["evaluations"].as_u64().unwrap() >= 6);
    assert!(!st["curve"].as_array().unwrap().is_empty());
    assert!(st["best"]["free"]["table"].is_number(), "{st}");
    let page = s.get("/api/optimize/report");
    assert_eq!(page.status, 200);
    assert!(String::from_utf8_lossy(&page.body).contains("<h2>winner 1</h2>"));
    // A long run: a second start is refused while it goes; stop ends it.
    assert_eq!(s.post("/api/optimize", &small(100_000)).status, 200);
    assert_eq!(s.post("/api/optimize", &small(6)).status, 409);
    std::thread::sleep(std::time::Duration::from_millis(500));
    assert_eq!(s.post("/api/optimize/stop", "").status, 200);
    let st = wait(&["stopped", "done", "failed"]);
    assert_eq!(st["state"], "stopped", "{st}");
}

fn b64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for c in bytes.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for (i, shift) in [18, 12, 6, 0].into_iter().enumerate() {
            if i <= c.len() {
                out.push(A[(n >> shift & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

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

/// Wait until the page's `expr` (a JavaScript expression) is true; false after `secs`.
async fn wait_js(page: &chromiumoxide::Page, expr: &str, secs: u64) -> bool {
    let t = Instant::now();
    while t.elapsed() < Duration::from_secs(secs) {
        if let Ok(r) = page.evaluate(expr).await {
            if r.into_value::<bool>().unwrap_or(false) {
                return true;
            }
        }
        tokio::time::sleep(Duration::from_millis(25)).await;
    }
    eprintln!("waited {secs} s in vain for {expr}");
    false
}

async fn js<T: serde::de::DeserializeOwned>(page: &chromiumoxide::Page, expr: &str) -> T {
    page.evaluate(expr)
        .await
        .unwrap_or_else(|e| panic!("{expr}: {e}"))
        .into_value()
        .unwrap_or_else(|e| panic!("{expr}: {e}"))
}

#[test]
fn serve_page_works_in_a_browser() {
    let chromium = std::path::Path::new("/usr/bin/chromium");
    if !chromium.exists() {
        if std::env::var_os("CI").is_some() {
            panic!("CI is set but /usr/bin/chromium is missing (.ci/run installs it)");
        }
        eprintln!("SKIPPED serve_page_works_in_a_browser: /usr/bin/chromium is not installed (apt-get install -y chromium)");
        return;
    }
    let server = Server::start();
    let url = format!("http://{}/", server.addr);
    let shots = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/serve-screenshots");
    std::fs::create_dir_all(&shots).unwrap();
    // A small .asc fixture made by the binary itself.
    let dir = tempfile::tempdir().unwrap();
    let asc = dir.path().join("fixture-oval.asc");
    let out = Command::new(env!("CARGO_BIN_EXE_facetlab"))
        .args(["generate", "oval", "-o"])
        .arg(&asc)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    rt.block_on(browser_session(&url, &shots, &asc));
}

async fn browser_session(url: &str, shots: &std::path::Path, asc: &std::path::Path) {
    use chromiumoxide::browser::{Browser, BrowserConfig};
    use chromiumoxide::cdp::browser_protocol::dom::SetFileInputFilesParams;
    use chromiumoxide::cdp::js_protocol::runtime::{
        ConsoleApiCalledType, EventConsoleApiCalled, EventExceptionThrown,
    };
    use chromiumoxide::handler::viewport::Viewport;
    use chromiumoxide::page::ScreenshotParams;
    use futures::StreamExt;

    let profile = tempfile::tempdir().unwrap();
    let config = BrowserConfig::builder()
        .chrome_executable("/usr/bin/chromium")
        .no_sandbox()
        .user_data_dir(profile.path())
        .window_size(1500, 950)
        .viewport(Viewport {
            width: 1500,
            height: 950,
            ..Viewport::default()
        })
        .build()
        .unwrap();
    let (mut browser, mut handler) = Browser::launch(config).await.expect("chromium starts");
    let pump = tokio::spawn(async move { while handler.next().await.is_some() {} });
    let page = browser.new_page("about:blank").await.unwrap();
    let errors = std::sync::Arc::new(std::sync::Mutex::new(Vec::<String>::new()));
    let mut console = page
        .event_listener::<EventConsoleApiCalled>()
        .await
        .unwrap();
    let mut thrown = page.event_listener::<EventExceptionThrown>().await.unwrap();
    let e1 = errors.clone();
    tokio::spawn(async move {
        while let Some(ev) = console.next().await {
            if matches!(
                ev.r#type,
                ConsoleApiCalledType::Error | ConsoleApiCalledType::Assert
            ) {
                let args: Vec<String> = ev
                    .args
                    .iter()
                    .map(|a| {
                        a.value
                            .as_ref()
                            .map(|v| v.to_string())
                            .or_else(|| a.description.clone())
                            .unwrap_or_default()
                    })
                    .collect();
                e1.lock()
                    .unwrap()
                    .push(format!("console.error {}", args.join(" ")));
            }
        }
    });
    let e2 = errors.clone();
    tokio::spawn(async move {
        while let Some(ev) = thrown.next().await {
            let d = &ev.exception_details;
            e2.lock().unwrap().push(format!(
                "exception {} {:?}",
                d.text,
                d.exception.as_ref().and_then(|x| x.description.clone())
            ));
        }
    });
    // A collector in the page too (errors and unhandled rejections).
    page.evaluate_on_new_document(
        "window.__errs = []; window.addEventListener('error', e => window.__errs.push(String(e.message))); window.addEventListener('unhandledrejection', e => window.__errs.push('rejection: ' + String(e.reason)));",
    )
    .await
    .unwrap();
    page.goto(url).await.unwrap();
    assert!(
        wait_js(&page, "document.querySelector('#render-a').complete && document.querySelector('#render-a').naturalWidth === 512 && document.querySelector('#score-a-brilliance').textContent !== '—' && document.querySelectorAll('#params input[type=range]').length > 5", 30).await,
        "the page did not show tolkowsky's render, scores and sliders"
    );
    // Let the full scores arrive, then look at it.
    wait_js(
        &page,
        "document.querySelector('#scores').dataset.a === 'full'",
        30,
    )
    .await;
    let shot = |name: &str| shots.join(name);
    page.save_screenshot(ScreenshotParams::builder().build(), shot("1-tolkowsky.png"))
        .await
        .unwrap();

    // Move the pavilion slider by script: the picture and the scores change.
    let before_src: String = js(&page, "document.querySelector('#render-a').src").await;
    let before_b: String = js(
        &page,
        "document.querySelector('#score-a-brilliance').textContent",
    )
    .await;
    let t = Instant::now();
    let _: bool = js(
        &page,
        "(() => { const r = document.querySelector('#params input[type=range][data-key=pavilion_angle]'); r.value = '42.2'; r.dispatchEvent(new Event('input', {bubbles: true})); return true; })()",
    )
    .await;
    assert!(
        wait_js(
            &page,
            &format!("document.querySelector('#render-a').src !== {before_src:?} && document.querySelector('#render-a').complete && document.querySelector('#score-a-brilliance').textContent !== {before_b:?}"),
            30
        )
        .await,
        "moving the slider changed neither the picture nor the scores"
    );
    eprintln!(
        "slider → new picture and quick scores seen by the test after {} ms",
        t.elapsed().as_millis()
    );
    // A few more moves, one at a time: the page's own latency figures.
    let (mut pic, mut sco) = (Vec::new(), Vec::new());
    for v in ["41.0", "41.4", "40.6", "41.8", "42.2"] {
        let before_src: String = js(&page, "document.querySelector('#render-a').src").await;
        let before_b: String = js(
            &page,
            "document.querySelector('#score-a-brilliance').textContent",
        )
        .await;
        let _: bool = js(
            &page,
            &format!("(() => {{ const r = document.querySelector('#params input[type=range][data-key=pavilion_angle]'); r.value = '{v}'; r.dispatchEvent(new Event('input', {{bubbles: true}})); return true; }})()"),
        )
        .await;
        assert!(
            wait_js(
                &page,
                &format!("document.querySelector('#render-a').src !== {before_src:?} && document.querySelector('#render-a').complete && document.querySelector('#score-a-brilliance').textContent !== {before_b:?} && !document.querySelector('#score-a-brilliance').classList.contains('stale')"),
                30
            )
            .await,
            "pavilion {v}: no new picture and scores"
        );
        let p: String = js(
            &page,
            "document.querySelector('#render-a').dataset.ms || ''",
        )
        .await;
        let s: String = js(&page, "document.querySelector('#scores').dataset.ms || ''").await;
        pic.push(p.parse::<u64>().unwrap_or(0));
        sco.push(s.parse::<u64>().unwrap_or(0));
    }
    pic.sort();
    sco.sort();
    eprintln!(
        "slider → picture {pic:?} ms (median {}), → quick scores {sco:?} ms (median {})",
        pic[2], sco[2]
    );
    let num: String = js(&page, "document.querySelector('#num-pavilion_angle').value").await;
    assert_eq!(num, "42.20");

    // An out-of-range value typed in a number field: the server's message, inline.
    let _: bool = js(
        &page,
        "(() => { const n = document.querySelector('#num-crown_angle'); n.value = '75'; n.dispatchEvent(new Event('change', {bubbles: true})); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, "document.querySelector('.param[data-key=crown_angle] .err').textContent.includes('out of range')", 20).await,
        "no inline message for crown_angle 75"
    );
    page.save_screenshot(ScreenshotParams::builder().build(), shot("2-invalid.png"))
        .await
        .unwrap();
    let _: bool = js(
        &page,
        "(() => { const n = document.querySelector('#num-crown_angle'); n.value = '34.5'; n.dispatchEvent(new Event('change', {bubbles: true})); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, "document.querySelector('.param[data-key=crown_angle] .err').textContent === '' && !document.querySelector('#veil-a').classList.contains('on')", 20).await,
        "the inline message did not clear"
    );

    // Pin as B, change A's light to ASET: both pictures, the comparison columns.
    let _: bool = js(&page, "(document.querySelector('#compare').click(), true)").await;
    let _: bool = js(
        &page,
        "(() => { const l = document.querySelector('#light'); l.value = 'aset'; l.dispatchEvent(new Event('change')); return true; })()",
    )
    .await;
    let _: bool = js(
        &page,
        "(() => { const r = document.querySelector('#params input[type=range][data-key=table]'); r.value = '0.57'; r.dispatchEvent(new Event('input', {bubbles: true})); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, "!document.querySelector('#view-b').hidden && document.querySelector('#render-a').dataset.light === 'aset' && document.querySelector('#render-b').dataset.light === 'aset' && document.querySelector('#score-d-brilliance').textContent.trim().slice(1) !== '0.0000' && !document.querySelector('#render-a').parentElement.classList.contains('busy')", 30).await,
        "the comparison did not show"
    );
    wait_js(&page, "document.querySelector('#scores').dataset.a === 'full' && document.querySelector('#scores').dataset.b === 'full'", 30).await;
    page.save_screenshot(
        ScreenshotParams::builder().build(),
        shot("3-compare-aset.png"),
    )
    .await
    .unwrap();

    // Upload the .asc through the file input (DOM.setFileInputFiles).
    let input = page.find_element("#file").await.unwrap();
    page.execute(
        SetFileInputFilesParams::builder()
            .file(asc.display().to_string())
            .backend_node_id(input.backend_node_id)
            .build()
            .unwrap(),
    )
    .await
    .unwrap();
    assert!(
        wait_js(&page, "document.querySelector('#cut-name').textContent === 'fixture-oval' && document.querySelector('#preset').value === '__file' && document.querySelector('#params-note').textContent.includes('explicit')", 30).await,
        "the uploaded .asc did not load"
    );
    let _: bool = js(
        &page,
        "(() => { const l = document.querySelector('#light'); l.value = 'fire'; l.dispatchEvent(new Event('change')); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, "document.querySelector('#render-a').dataset.name === 'fixture-oval' && document.querySelector('#render-a').dataset.light === 'fire' && document.querySelector('#render-b').dataset.light === 'fire' && document.querySelector('#cap-a').textContent.includes('Fire')", 60).await,
        "the uploaded cut was not rendered and scored"
    );
    wait_js(
        &page,
        "document.querySelector('#scores').dataset.a === 'full'",
        30,
    )
    .await;
    page.save_screenshot(
        ScreenshotParams::builder().build(),
        shot("4-upload-fire.png"),
    )
    .await
    .unwrap();

    let page_errs: Vec<String> = js(&page, "window.__errs || []").await;
    let errs = errors.lock().unwrap().clone();
    assert!(
        errs.is_empty() && page_errs.is_empty(),
        "browser errors: {errs:?} {page_errs:?}"
    );
    let _ = browser.close().await;
    let _ = browser.wait().await;
    pump.abort();
}
