//! The API of `facetlab serve`: every endpoint's answers and refusals, and an optimization
//! run started, watched and stopped from the API.

use super::*;

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
    // The lights the page's menu is built from: the library's one table, and the two name
    // lists it makes.
    let table = serde_json::to_value(facetlab::render::lights::table()).unwrap();
    assert_eq!(p["light_table"], table);
    let names = |photo: bool| -> Vec<serde_json::Value> {
        let t = table.as_array().unwrap().iter();
        t.filter(|e| e["photo"] == photo)
            .map(|e| e["name"].clone())
            .collect()
    };
    assert_eq!(p["lights"].as_array().unwrap(), &names(false));
    assert_eq!(p["photo_lights"].as_array().unwrap(), &names(true));
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
    for to in ["asc", "gem", "obj", "stl", "toml"] {
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
        let body = if to == "stl" || to == "gem" {
            serde_json::json!({"cut": b64(&r.body), "format": to, "encoding": "base64", "name": format!("back.{to}")})
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
    // A photograph's settings with a laboratory light (given or the default) are refused, not
    // ignored, as the command line's --view and --ground are.
    for (body, field) in [
        (
            r#"{"cut": "tolkowsky", "light": "iso", "view": 40}"#,
            "view",
        ),
        (r#"{"cut": "tolkowsky", "view_az": 10}"#, "view_az"),
        (
            r#"{"cut": "tolkowsky", "light": "fire", "ground": "white"}"#,
            "ground",
        ),
        (
            r#"{"cut": "tolkowsky", "light": "aset", "light_rotation": 5}"#,
            "light_rotation",
        ),
    ] {
        let e = assert_error(&s.post("/api/render", body), field);
        assert!(
            e.contains("is for photographs") && e.contains("tent"),
            "{e}"
        );
    }
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

/// A design without a family (an uploaded `.asc`): its tiers are the parameters, with their
/// own angles as defaults; setting one re-solves the depths and keeps the facets; an angle
/// that would open a meet is a 422 naming the tier and the meet.
#[test]
fn serve_design_tiers_are_sliders() {
    use facetlab::io;
    let s = Server::start();
    let preset = io::presets::load("tolkowsky").unwrap().unwrap();
    let text = io::asc::write(&preset, io::asc::DEFAULT_GEAR);
    let upload = |set: serde_json::Value| {
        serde_json::json!({"cut": text, "format": "asc", "name": "tolk.asc", "set": set})
            .to_string()
    };
    let info = s.post("/api/cut", &upload(serde_json::json!({})));
    assert_eq!(info.status, 200, "{}", String::from_utf8_lossy(&info.body));
    let info = info.json();
    assert!(info["family"].is_null(), "an .asc has no family");
    let tiers = info["design_space"]["tiers"]
        .as_array()
        .expect("the design's tiers as sliders");
    let tier = |key: &str| {
        tiers
            .iter()
            .find(|t| t["key"] == key)
            .unwrap_or_else(|| panic!("no tier {key} in {tiers:?}"))
            .clone()
    };
    // The defaults are the design's angles: the preset's pavilion and crown angles.
    let mains = tier("pavilion-main");
    let (pav, crown) = (
        preset.params["pavilion_angle"],
        preset.params["crown_angle"],
    );
    assert!(
        (mains["default"].as_f64().unwrap() - pav).abs() < 1e-9,
        "{mains}"
    );
    assert!((tier("bezel")["default"].as_f64().unwrap() - crown).abs() < 1e-9);
    assert_eq!(mains["step"], 0.01);
    let (lo, hi) = (
        mains["min"].as_f64().unwrap(),
        mains["max"].as_f64().unwrap(),
    );
    assert!(lo < pav && pav < hi && hi - lo <= 10.0 + 1e-9, "{mains}");

    // pavilion-main turned: the solid's pavilion angle follows, the facets stay, the score moves.
    let turned = s
        .post(
            "/api/cut",
            &upload(serde_json::json!({"pavilion-main": 41.0})),
        )
        .json();
    let got = turned["proportions"]["pavilion_angle"].as_f64().unwrap();
    assert!((got - 41.0).abs() < 1e-6, "pavilion angle {got}");
    assert_eq!(turned["facet_count"], info["facet_count"]);
    let score = |set: serde_json::Value| {
        let mut b: serde_json::Value = serde_json::from_str(&upload(set)).unwrap();
        b["quick"] = true.into();
        let r = s.post("/api/score", &b.to_string());
        assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
        r.json()["brilliance"].as_f64().unwrap()
    };
    let (b0, b1) = (
        score(serde_json::json!({})),
        score(serde_json::json!({"pavilion-main": 41.0})),
    );
    assert!((b0 - b1).abs() > 1e-6, "brilliance {b0} at both angles");
    let r = s.post(
        "/api/render",
        &upload(serde_json::json!({"pavilion-main": 40.5, "lower-half": 42.0})),
    );
    assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
    // Tiers tied: turned by one change of angle, or set to one angle.
    let tied = s
        .post(
            "/api/cut",
            &upload(serde_json::json!({"pavilion-main+lower-half": 0.25})),
        )
        .json();
    let got = tied["proportions"]["pavilion_angle"].as_f64().unwrap();
    assert!((got - pav - 0.25).abs() < 1e-6, "pavilion angle {got}");
    assert_error(
        &s.post("/api/cut", &upload(serde_json::json!({"nosuch": 40.0}))),
        "set.nosuch",
    );

    // A square design whose crown tiers A and B meet at an apex: A alone opens it.
    let pyramid = "GemCad 5.0\ng 96 0.0\ny 4 n\nI 1.54\nH meets test\n\
                   a -90.000000 0.50000000 96 24 48 72 n G\n\
                   a 40.000000 0.35969603 96 48 n A\n\
                   a 40.000000 0.35969603 24 72 n B\n\
                   a 0.000000 -0.30000000 96 n U\n";
    let body = |set: serde_json::Value| {
        serde_json::json!({"cut": pyramid, "format": "asc", "name": "pyramid.asc", "set": set})
            .to_string()
    };
    let p = s.post("/api/cut", &body(serde_json::json!({}))).json();
    let keys: Vec<&str> = p["design_space"]["tiers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["key"].as_str().unwrap())
        .collect();
    assert_eq!(keys, ["A", "B"]);
    let e = assert_error(
        &s.post("/api/render", &body(serde_json::json!({"A": 42.0}))),
        "set.A",
    );
    assert!(e.contains("meet A·B"), "{e}");
    assert_eq!(
        s.post("/api/render", &body(serde_json::json!({"A": 42.0})))
            .status,
        422
    );
    let both = s.post("/api/cut", &body(serde_json::json!({"A": 42.0, "B": 42.0})));
    assert_eq!(both.status, 200, "{}", String::from_utf8_lossy(&both.body));
    assert_eq!(both.json()["facet_count"], p["facet_count"]);
    // The background probe says which meet each tier opens alone.
    let mut probed = serde_json::Value::Null;
    for _ in 0..200 {
        probed = s.post("/api/cut", &body(serde_json::json!({}))).json()["design_space"].clone();
        if probed["probed"] == true {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    assert_eq!(probed["probed"], true, "{probed}");
    for t in probed["tiers"].as_array().unwrap() {
        assert_eq!(t["alone_opens"], serde_json::json!(["A·B"]), "{t}");
    }
}

/// Issue 51 item 10: SIGTERM stops the server at once; a request under way (a large
/// photograph) is answered or its connection closed, never left hanging, and the process
/// ends by itself with exit code 0. (How soon is measured by hand, not here.)
#[test]
fn sigterm_stops_the_server_with_a_request_under_way() {
    let mut s = Server::start();
    let addr = s.addr.clone();
    let slow = std::thread::spawn(move || {
        try_request(
            &addr,
            "POST",
            "/api/render",
            br#"{"cut": "tolkowsky", "light": "tent", "size": 1024}"#,
        )
    });
    // Once the request is in, the signal.
    std::thread::sleep(std::time::Duration::from_millis(300));
    let pid = s.child.id().to_string();
    assert!(std::process::Command::new("kill")
        .args(["-TERM", &pid])
        .status()
        .unwrap()
        .success());
    let t = std::time::Instant::now();
    let status = loop {
        if let Some(st) = s.child.try_wait().unwrap() {
            break st;
        }
        assert!(
            t.elapsed() < std::time::Duration::from_secs(30),
            "still running 30 s after SIGTERM"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    assert_eq!(status.code(), Some(0));
    // Answered in full, or cut: the client is not left waiting.
    match slow.join().unwrap() {
        Ok(r) => assert!(r.status == 200 || r.status >= 500, "{}", r.status),
        Err(e) => assert!(
            !matches!(
                e.kind(),
                std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
            ),
            "{e}"
        ),
    }
}
