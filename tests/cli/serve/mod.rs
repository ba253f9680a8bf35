//! `facetlab serve`: the API as a client sees it (the built binary on a free port), a fuzz loop
//! that must not kill the server, and the page in a real browser (Chromium, with the cargo
//! feature `browser-tests`, which `.ci/run` turns on).
//! This file holds the harness (the server as a child process, a bare HTTP/1.1 client); the
//! tests are in [`api`], [`fuzz`] and [`browser`].

mod api;
#[cfg(feature = "browser-tests")]
mod browser;
mod colour;
mod crystal;
mod first;
mod fuzz;
mod paths;
mod plan;
mod recipe;
mod scores;
#[cfg(feature = "browser-tests")]
mod tier_editor;

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
        Server::start_at(None)
    }

    /// The same, with `dir` its working folder.
    fn start_in(dir: &std::path::Path) -> Server {
        Server::start_at(Some(dir))
    }

    fn start_at(dir: Option<&std::path::Path>) -> Server {
        // FACETLAB_SERVE_BIN runs another build (a release build, to measure latency).
        let bin = std::env::var("FACETLAB_SERVE_BIN")
            .unwrap_or_else(|_| env!("CARGO_BIN_EXE_facetlab").to_string());
        let mut cmd = Command::new(bin);
        if let Some(d) = dir {
            cmd.current_dir(d);
        }
        let mut child = cmd
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

/// `POST /api/score` with a bad `body`: answered `status`, one line naming `field`; the line.
fn score_refused(s: &Server, body: &str, field: &str, status: u16) -> String {
    let r = s.post("/api/score", body);
    assert_eq!(
        r.status,
        status,
        "{body}: {}",
        String::from_utf8_lossy(&r.body)
    );
    assert_error(&r, field)
}

/// Standard base64 of `bytes` (as the page's `btoa` sends uploads).
fn b64(bytes: &[u8]) -> String {
    use base64::Engine;
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

/// The mean colour of a PNG's pixels that differ from its corner's (the stone, not the
/// ground), as 0–255 RGB, and how many there are.
fn stone_mean_rgb(b: &[u8]) -> ([f64; 3], usize) {
    let mut reader = png::Decoder::new(std::io::Cursor::new(b))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb, "an RGB picture");
    let px: Vec<&[u8]> = buf[..info.buffer_size()].chunks(3).collect();
    let ground = px[0];
    let mut sum = [0.0; 3];
    let mut n = 0;
    for p in px.iter().filter(|p| *p != &ground) {
        for k in 0..3 {
            sum[k] += p[k] as f64;
        }
        n += 1;
    }
    (sum.map(|s| s / n.max(1) as f64), n)
}

/// The hue of an RGB colour, degrees in [0, 360), and its chroma (max − min), 0–255.
fn hue(c: [f64; 3]) -> (f64, f64) {
    let [r, g, b] = c;
    let (hi, lo) = (r.max(g).max(b), r.min(g).min(b));
    let d = hi - lo;
    if d <= 0.0 {
        return (0.0, 0.0);
    }
    let h = if hi == r {
        60.0 * ((g - b) / d).rem_euclid(6.0)
    } else if hi == g {
        60.0 * ((b - r) / d + 2.0)
    } else {
        60.0 * ((r - g) / d + 4.0)
    };
    (h, d)
}

/// Whether this run is CI's: `CI` set to anything but empty, `false` or `0` (`.ci/run` and CI
/// services set `CI=true`). A test that cannot run there fails instead of passing.
fn in_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "false" && v != "0")
}

/// Without the feature `browser-tests` the browser test is not built: a skip anywhere else, a
/// failure under CI (`.ci/run` builds it with `cargo test --features browser-tests`).
#[cfg(not(feature = "browser-tests"))]
#[test]
fn the_browser_test_is_not_skipped_in_ci() {
    assert!(
        !in_ci(),
        "CI is set but the browser test of `facetlab serve` was not built: run `cargo test --features browser-tests`"
    );
    eprintln!(
        "SKIPPED the browser test of `facetlab serve`: `cargo test --features browser-tests` runs it (needs /usr/bin/chromium)"
    );
}

/// Without the feature `browser-tests`, `cargo test` lists the browser test as ignored with
/// the reason, where a user sees it (run with `--ignored`, it fails saying how to build it).
#[cfg(not(feature = "browser-tests"))]
#[test]
#[ignore = "the browser test of `facetlab serve` runs with `cargo test --features browser-tests` (needs /usr/bin/chromium)"]
fn serve_page_works_in_a_browser() {
    panic!("built without the feature `browser-tests`: run `cargo test --features browser-tests`");
}
