//! No request makes the server open a file a client names (issue 36): paths to files beside
//! the server (absolute, relative, with `..`, through a symlink, URL-encoded, as `file://`) in
//! every field that takes text, of every endpoint, are answered without their content, the
//! same whether the file exists or not (no oracle), and without opening them (a FIFO among
//! them would hang the request). A config sent to the server may name a preset or the design
//! sent with it; a path in its `[cut] file` is a 422 that repeats nothing of it.

use super::*;
use serde_json::json;
use std::path::Path;

/// The text inside every file the server must not read.
const MARK: &str = "zz-secret-36";

/// An octahedron as GemCad writes it (its tiers `crown`, `table`, `pav`).
const OCTA: &str = "g 96 0.0\nI 2.42\na 41.0 0.5 0 24 48 72 n crown\na 0 0.3 0 n table\na -41.0 0.5 0 24 48 72 n pav\n";

/// Percent-encode every byte but letters and digits.
fn url_encoded(s: &str) -> String {
    s.bytes()
        .map(|b| {
            if b.is_ascii_alphanumeric() {
                (b as char).to_string()
            } else {
                format!("%{b:02X}")
            }
        })
        .collect()
}

/// Every spelling of a file `name` in `work` (the server's folder, inside `root`).
fn spellings(root: &Path, name: &str) -> Vec<String> {
    let abs = root.join("work").join(name).display().to_string();
    vec![
        abs.clone(),
        name.to_string(),
        format!("./{name}"),
        format!("../work/{name}"),
        format!("work/../../work/{name}"),
        format!("{}/work/../work/{name}", root.display()),
        url_encoded(&abs),
        format!("file://{abs}"),
        format!("file://{}", url_encoded(&abs)),
    ]
}

/// Every request that puts `p` in a field that takes text: (method, path, body).
fn requests(p: &str) -> Vec<(&'static str, String, String)> {
    let mut out = Vec::new();
    let post = |path: &str, body: serde_json::Value| ("POST", path.to_string(), body.to_string());
    // The cut endpoints: every text field, the rest a cheap valid request.
    let base = [
        ("/api/cut", json!({"cut": "princess"})),
        ("/api/score", json!({"cut": "princess", "quick": true})),
        ("/api/render", json!({"cut": "princess", "size": 16})),
        ("/api/export", json!({"cut": "princess", "to": "asc"})),
    ];
    for (path, body) in &base {
        let fields: &[&str] = match *path {
            "/api/cut" => &[
                "cut", "format", "encoding", "name", "material", "colour", "size_mm",
            ],
            "/api/score" => &["cut", "light", "material", "colour"],
            "/api/render" => &["cut", "light", "material", "colour", "size_mm"],
            _ => &["cut", "to"],
        };
        for f in fields {
            let mut b = body.clone();
            b[*f] = json!(p);
            out.push(post(path, b));
        }
        // An upload named by the path (a name is a label, never a file).
        let mut b = body.clone();
        b["cut"] = json!(OCTA);
        b["format"] = json!("asc");
        b["name"] = json!(p);
        out.push(post(path, b));
    }
    // Plans: every text field.
    let plan = json!({"crystal": "octahedron", "size_mm": 5, "families": ["princess"], "starts": 1, "top": 1});
    for f in ["rough", "format", "encoding", "name", "crystal", "material"] {
        let mut b = plan.clone();
        b[f] = json!(p);
        if f == "format" || f == "encoding" || f == "name" {
            b["rough"] = json!("v 0 0 0\n");
            b.as_object_mut().unwrap().remove("crystal");
            b.as_object_mut().unwrap().remove("size_mm");
        }
        if f == "rough" {
            b.as_object_mut().unwrap().remove("crystal");
            b["format"] = json!("obj");
        }
        // A plan that would start is made to fail before it starts: no valid family.
        if f == "name" {
            b["families"] = json!(["no-such-family"]);
        }
        out.push(post("/api/plan", b));
    }
    let mut b = plan.clone();
    b["families"] = json!([p]);
    out.push(post("/api/plan", b));
    // Optimization: the config's name, its text's `[cut] file`, `name`, material, and the
    // design fields.
    out.push(post("/api/optimize", json!({ "config": p })));
    let cut_file = format!("[cut]\nfile = {}\n[free]\ncrown = [35, 45]\n", json!(p));
    out.push(post("/api/optimize", json!({ "config_text": cut_file })));
    let named = format!("name = {}\n[cut]\nfamily = \"round-brilliant\"\n", json!(p));
    out.push(post("/api/optimize", json!({ "config_text": named })));
    let material = format!(
        "[cut]\nfamily = \"round-brilliant\"\n[free]\ntable = [0.52, 0.6]\n[score]\nmaterial = {}\n",
        json!(p)
    );
    out.push(post("/api/optimize", json!({ "config_text": material })));
    out.push(post(
        "/api/optimize",
        json!({ "config_text": cut_file, "design": p, "design_name": "other.asc" }),
    ));
    out.push(post(
        "/api/optimize",
        json!({ "config_text": cut_file, "design_name": p }),
    ));
    // And in the URL.
    let e = url_encoded(p);
    for path in [
        format!("/api/plan/picture/{e}"),
        format!("/{e}"),
        format!("/{p}"),
        format!("/api/optimize/report?file={e}"),
        format!("/page.js/../{e}"),
    ] {
        if !path.contains(' ') {
            out.push(("GET", path, String::new()));
        }
    }
    out
}

fn send(s: &Server, (method, path, body): &(&str, String, String)) -> Resp {
    let t = Instant::now();
    let r = try_request(&s.addr, method, path, body.as_bytes())
        .unwrap_or_else(|e| panic!("{method} {path} {body}: {e}"));
    assert!(
        t.elapsed() < Duration::from_secs(60),
        "{method} {path} {body} took {:?}: did the server open a FIFO?",
        t.elapsed()
    );
    r
}

/// A response with the two names' differing digit blotted out (`7` and `8` both `#`).
fn blotted(r: &Resp) -> (u16, String) {
    let text = String::from_utf8_lossy(&r.body).replace(['7', '8'], "#");
    (r.status, text)
}

#[test]
fn serve_never_opens_a_path_a_client_names() {
    let root = tempfile::tempdir().unwrap();
    let work = root.path().join("work");
    std::fs::create_dir(&work).unwrap();
    // Files the server must not read: a design, a mesh, a TOML, plain text, a symlink to the
    // design and (where mkfifo exists) a FIFO, whose opening would block the request.
    let design = format!("H {MARK}\n{OCTA}F {MARK}\n");
    std::fs::write(work.join("secret7.asc"), &design).unwrap();
    std::fs::write(
        work.join("secret7.obj"),
        format!(
            "# {MARK}\nv 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\nf 1 3 5\nf 2 4 6\n"
        ),
    )
    .unwrap();
    std::fs::write(
        work.join("secret7.toml"),
        format!("name = \"{MARK}\"\nfamily = \"round-brilliant\"\n"),
    )
    .unwrap();
    std::fs::write(work.join("secret7"), format!("{MARK}\n")).unwrap();
    std::os::unix::fs::symlink(work.join("secret7.asc"), work.join("link7.asc")).unwrap();
    let fifo = Command::new("mkfifo")
        .arg(work.join("trap7.asc"))
        .status()
        .is_ok_and(|s| s.success());
    let mut s = Server::start_in(&work);

    let mut names = vec![
        "secret7.asc",
        "secret7.obj",
        "secret7.toml",
        "secret7",
        "link7.asc",
    ];
    if fifo {
        names.push("trap7.asc");
    }
    let mut tried = 0;
    for name in names {
        let missing = name.replace('7', "8");
        for (p, q) in spellings(root.path(), name)
            .iter()
            .zip(spellings(root.path(), &missing))
        {
            for (there, absent) in requests(p).iter().zip(requests(&q)) {
                let (a, b) = (send(&s, there), send(&s, &absent));
                let body = String::from_utf8_lossy(&a.body);
                assert!(
                    !body.contains(MARK),
                    "{} {} {}: the answer holds the file's content: {body}",
                    there.0,
                    there.1,
                    there.2
                );
                assert!(a.status < 500, "{} {}: {}", there.1, there.2, a.status);
                assert_eq!(
                    blotted(&a),
                    blotted(&b),
                    "{} {} {}: the answer tells whether the file exists",
                    there.0,
                    there.1,
                    there.2
                );
                tried += 1;
            }
            // A path in a config's `[cut] file` is refused with a 422 that repeats nothing.
            let text = format!("[cut]\nfile = {}\n[free]\ncrown = [35, 45]\n", json!(p));
            let r = s.post("/api/optimize", &json!({ "config_text": text }).to_string());
            assert_eq!(r.status, 422, "{}", String::from_utf8_lossy(&r.body));
            let e = assert_error(&r, "config_text");
            assert!(!e.contains("secret") && !e.contains("work"), "{e}");
        }
    }
    assert!(tried > 1000, "{tried} requests");
    assert!(s.alive());

    // What a config may name: a preset, or the design sent with it (read in memory).
    let wait = || -> serde_json::Value {
        for _ in 0..600 {
            let st = s.get("/api/optimize").json();
            if ["done", "failed", "stopped"].contains(&st["state"].as_str().unwrap_or("")) {
                return st;
            }
            std::thread::sleep(Duration::from_millis(200));
        }
        panic!("the run did not end");
    };
    let small = "[method]\nname = \"nelder-mead\"\nstarts = 1\nmax_evaluations = 4\n[verify]\nwinners = 1\nphotons = 2000\n";
    let preset =
        format!("[cut]\nfile = \"tolkowsky\"\n[free]\npavilion-main = [40, 41.4]\n{small}");
    let r = s.post(
        "/api/optimize",
        &json!({ "config_text": preset }).to_string(),
    );
    assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
    let st = wait();
    assert_eq!(st["state"], "done", "{st}");
    let uploaded = format!(
        "[cut]\nfile = \"mine.asc\"\nfacet_changes = \"skip\"\n[free]\ncrown = [38, 44]\n{small}"
    );
    let r = s.post(
        "/api/optimize",
        &json!({ "config_text": uploaded, "design": OCTA, "design_name": "mine.asc" }).to_string(),
    );
    assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
    let st = wait();
    assert_eq!(st["state"], "done", "{st}");
    assert!(st["best"]["free"]["crown"].is_number(), "{st}");
    // The same name without the upload is a path, refused.
    let r = s.post(
        "/api/optimize",
        &json!({ "config_text": uploaded }).to_string(),
    );
    assert_eq!(r.status, 422);
}

/// Item 10: The API traces an uploaded design in its own material (its `I` index) unless told
/// otherwise, as every command does; `material` still chooses.
#[test]
fn serve_scores_a_design_in_its_own_material() {
    let s = Server::start();
    let quartz = OCTA.replace("I 2.42", "I 1.544");
    let material = |extra: serde_json::Value| {
        let mut b = json!({"cut": quartz, "format": "asc", "name": "q.asc", "quick": true});
        if let (Some(m), serde_json::Value::Object(e)) = (b.as_object_mut(), extra) {
            m.extend(e);
        }
        let r = s.post("/api/score", &b.to_string());
        assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
        r.json()["settings"]["material"]
            .as_str()
            .unwrap()
            .to_string()
    };
    assert_eq!(material(json!({})), "quartz");
    assert_eq!(material(json!({"material": "diamond"})), "diamond");
    // A preset has no index of its own: diamond.
    let r = s
        .post("/api/score", r#"{"cut": "tolkowsky", "quick": true}"#)
        .json();
    assert_eq!(r["settings"]["material"], "diamond");
}
