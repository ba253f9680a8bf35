//! Plans from a rough in the workbench's API: a distorted octahedron written as OBJ text here
//! runs to the end with plans inside it; bad roughs are refused before anything runs.

use super::*;

/// A distorted octahedron (convex, outward triangles) as OBJ text, in mm; `drop` leaves out
/// that many of its eight faces (an open mesh).
pub fn octahedron_obj(drop: usize) -> String {
    let v = [
        [3.2, 0.2, 0.1],
        [-2.8, -0.1, 0.3],
        [0.1, 3.0, -0.2],
        [-0.2, -3.1, 0.1],
        [0.3, 0.1, 2.5],
        [-0.1, 0.2, -3.4],
    ];
    let mut out = String::from("# a distorted octahedron\n");
    for p in v {
        out.push_str(&format!("v {} {} {}\n", p[0], p[1], p[2]));
    }
    let mut faces = Vec::new();
    for (x, sx) in [(1, 1.0), (2, -1.0)] {
        for (y, sy) in [(3, 1.0), (4, -1.0)] {
            for (z, sz) in [(5, 1.0), (6, -1.0)] {
                // Counter-clockwise seen from outside when the octant's signs multiply to +1.
                if sx * sy * sz > 0.0 {
                    faces.push(format!("f {x} {y} {z}\n"));
                } else {
                    faces.push(format!("f {x} {z} {y}\n"));
                }
            }
        }
    }
    for f in &faces[drop..] {
        out.push_str(f);
    }
    out
}

#[test]
fn serve_plans_a_rough() {
    let s = Server::start();
    let plan = |body: serde_json::Value| s.post("/api/plan", &body.to_string());
    assert_error(&s.get("/api/plan"), "run");
    // Bad roughs and choices: one line naming the field; no run starts.
    let bad = |body: serde_json::Value, field: &str, status: u16| {
        let r = plan(body.clone());
        assert_eq!(
            r.status,
            status,
            "{body}: {}",
            String::from_utf8_lossy(&r.body)
        );
        assert_error(&r, field)
    };
    let e = bad(
        serde_json::json!({"rough": octahedron_obj(1), "format": "obj"}),
        "rough",
        422,
    );
    assert!(e.contains("not closed"), "{e}");
    bad(
        serde_json::json!({"rough": "hello, not a mesh", "format": "obj"}),
        "rough",
        422,
    );
    bad(
        serde_json::json!({"rough": "solid x\nendsolid x\n", "format": "stl"}),
        "rough",
        422,
    );
    let many = "v 0 0 0\nv 1 0 0\nv 0 1 0\n".to_string() + &"f 1 2 3\n".repeat(20_001);
    let e = bad(
        serde_json::json!({"rough": many, "format": "obj"}),
        "rough",
        422,
    );
    assert!(e.contains("20000"), "{e}");
    bad(serde_json::json!({"crystal": "octahedron"}), "size_mm", 422);
    // The library's one range of a rough's size (the command line's and Python's too).
    let e = bad(
        serde_json::json!({"crystal": "cube", "size_mm": 600}),
        "size_mm",
        422,
    );
    assert_eq!(
        e,
        "size_mm: 600 is not allowed; give the rough's largest extent in (0, 500] mm"
    );
    bad(
        serde_json::json!({"crystal": "icosahedron", "size_mm": 6}),
        "crystal",
        422,
    );
    bad(
        serde_json::json!({"crystal": "cube", "size_mm": 6, "families": ["blob"]}),
        "families",
        422,
    );
    // A family named twice would write its plans over each other, as the CLI and Python say.
    let e = bad(
        serde_json::json!({"crystal": "cube", "size_mm": 6, "families": ["oval", "oval"]}),
        "families",
        422,
    );
    assert!(e.contains("`oval` is named twice"), "{e}");
    bad(
        serde_json::json!({"crystal": "cube", "size_mm": 6, "families": []}),
        "families",
        422,
    );
    bad(
        serde_json::json!({"crystal": "cube", "size_mm": 6, "top": 0}),
        "top",
        400,
    );
    bad(
        serde_json::json!({"crystal": "cube", "size_mm": 6, "material": "kryptonite"}),
        "material",
        422,
    );
    bad(
        serde_json::json!({"rough": octahedron_obj(0)}),
        "format",
        400,
    );
    bad(serde_json::json!({"path": "/etc/passwd"}), "path", 400);
    assert_error(&s.get("/api/plan"), "run");

    // The octahedron: planned to the end, plans inside it with their pictures and report.
    let r = plan(serde_json::json!({
        "rough": octahedron_obj(0), "format": "obj", "name": "../octa.obj",
        "families": ["round-brilliant", "oval"], "top": 2, "starts": 4,
    }));
    assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
    // A second start while it runs is refused (or it has already ended).
    let again = plan(serde_json::json!({"crystal": "cube", "size_mm": 6}));
    assert!(matches!(again.status, 200 | 409), "{}", again.status);
    // The plan run's status once it is no longer running.
    let wait = || {
        for _ in 0..600 {
            let st = s.get("/api/plan").json();
            if st["state"] != "running" {
                return st;
            }
            std::thread::sleep(Duration::from_millis(200));
        }
        panic!("the plan did not end");
    };
    let mut st = wait();
    if again.status == 200 {
        // The cube started after the octahedron ended: plan the octahedron again.
        assert_eq!(st["name"], "cube", "{st}");
        let r = plan(serde_json::json!({
            "rough": octahedron_obj(0), "format": "obj", "name": "octa",
            "families": ["round-brilliant", "oval"], "top": 2, "starts": 4,
        }));
        assert_eq!(r.status, 200);
        st = wait();
    }
    assert_eq!(st["state"], "done", "{st}");
    assert_eq!(st["name"], "octa");
    assert_eq!(st["starts_done"], st["starts"], "{st}");
    assert_eq!(st["starts"], 8);
    let rough_volume = st["rough"]["volume_mm3"].as_f64().unwrap();
    // The octahedron's volume: (1/6)·(x+ + x−)(y+ + y−)(z+ + z−) for vertices on the axes,
    // near it for these slightly moved ones.
    assert!(
        (rough_volume / (6.0 * 6.1 * 5.9 / 6.0) - 1.0).abs() < 0.1,
        "{rough_volume}"
    );
    let plans = st["plans"].as_array().unwrap();
    assert_eq!(plans.len(), 4, "{st}");
    for p in plans {
        let y = p["yield"].as_f64().unwrap();
        assert!(y > 0.0 && y < 1.0, "yield {y}");
        let v = p["volume_mm3"].as_f64().unwrap();
        assert!(
            (v / rough_volume - y).abs() < 1e-9,
            "{v} / {rough_volume} vs {y}"
        );
        assert!(p["carats"].as_f64().unwrap() > 0.0);
        assert!(p["scores"]["brilliance"].as_f64().unwrap() > 0.0);
        assert!(p["params"]["pavilion_angle"].as_f64().is_some() || p["family"] == "oval");
        let views = p["views"].as_str().unwrap();
        let png = s.get(views);
        assert_eq!(png.status, 200, "{views}");
        assert_eq!(png.header("content-type"), Some("image/png"));
        assert!(png_size(&png.body).0 > 100);
    }
    // Ranked by the objective (weight) within each family.
    assert!(plans[0]["carats"].as_f64() >= plans[1]["carats"].as_f64());
    let report = s.get("/api/plan/report");
    assert_eq!(report.status, 200);
    assert!(String::from_utf8_lossy(&report.body).contains("<html"));
    assert_eq!(s.get(st["overview"].as_str().unwrap()).status, 200);
    assert_error(&s.get("/api/plan/picture/..%2Fsummary.json"), "path");
    assert_error(&s.get("/api/plan/picture/nosuch.png"), "path");

    // A crystal with a size; stop ends it after the family being planned.
    let r = plan(serde_json::json!({
        "crystal": "octahedron", "size_mm": 6,
        "families": ["round-brilliant", "oval", "cushion", "princess", "emerald", "pear", "marquise"],
        "top": 1, "starts": 48,
    }));
    assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
    assert_eq!(s.post("/api/plan/stop", "").status, 200);
    st = wait();
    assert_eq!(st["state"], "stopped", "{st}");
    assert!(st["plans"].as_array().unwrap().len() < 7, "{st}");
}

/// A closed tetrahedron of size `r` at `c` (mm) as OBJ text (an inclusion).
fn speck_obj(c: [f64; 3], r: f64) -> String {
    let mut out = String::new();
    for p in [
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ] {
        out.push_str(&format!(
            "v {} {} {}\n",
            c[0] + r * p[0],
            c[1] + r * p[1],
            c[2] + r * p[2]
        ));
    }
    out + "f 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n"
}

#[test]
fn serve_plans_a_layout_of_several_stones() {
    let s = Server::start();
    let plan = |body: serde_json::Value| s.post("/api/plan", &body.to_string());
    let bad = |body: serde_json::Value, field: &str, status: u16| {
        let r = plan(body.clone());
        assert_eq!(
            r.status,
            status,
            "{body}: {}",
            String::from_utf8_lossy(&r.body)
        );
        assert_error(&r, field)
    };
    let octa = |extra: serde_json::Value| {
        let mut b = serde_json::json!({"crystal": "octahedron", "size_mm": 6});
        for (k, v) in extra.as_object().unwrap() {
            b[k] = v.clone();
        }
        b
    };
    bad(octa(serde_json::json!({"stones": 0})), "stones", 400);
    bad(octa(serde_json::json!({"stones": 9})), "stones", 400);
    bad(octa(serde_json::json!({"kerf_mm": -0.1})), "kerf_mm", 422);
    bad(
        octa(serde_json::json!({"allowance_mm": 11})),
        "allowance_mm",
        422,
    );
    bad(
        octa(serde_json::json!({"margin_mm": "wide"})),
        "margin_mm",
        400,
    );
    bad(octa(serde_json::json!({"cutter": "wire"})), "cutter", 422);
    bad(octa(serde_json::json!({"cutter": 2})), "cutter", 400);
    bad(
        octa(serde_json::json!({"inclusions": "not a list"})),
        "inclusions",
        400,
    );
    let open = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n";
    let e = bad(
        octa(serde_json::json!({"stones": 2, "inclusions": [open]})),
        "inclusions",
        422,
    );
    assert!(e.contains("not closed"), "{e}");
    bad(
        serde_json::json!({"crystal": "sphere", "size_mm": 6, "stones": 2}),
        "stones",
        422,
    );
    assert_error(&s.get("/api/plan"), "run");

    // Two stones kept off one inclusion, a short search.
    let (kerf, allowance, margin) = (0.25, 0.15, 0.2);
    let r = plan(octa(serde_json::json!({
        "families": ["round-brilliant"], "starts": 1, "stones": 2, "kerf_mm": kerf,
        "allowance_mm": allowance, "margin_mm": margin,
        "inclusions": [speck_obj([0.3, 0.2, 0.4], 0.15)],
    })));
    assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
    let mut st = s.get("/api/plan").json();
    for _ in 0..3000 {
        if st["state"] != "running" {
            break;
        }
        std::thread::sleep(Duration::from_millis(200));
        st = s.get("/api/plan").json();
    }
    assert_eq!(st["state"], "done", "{st}");
    let layout = &st["layout"];
    assert_eq!(layout["kerf_mm"], kerf);
    assert_eq!(layout["cutter"], "saw");
    assert_eq!(layout["pairs"].as_array().unwrap().len(), 1, "{layout}");
    assert_eq!(layout["allowance_mm"], allowance);
    assert_eq!(layout["inclusion_margin_mm"], margin);
    let stones = st["stones"].as_array().unwrap();
    assert_eq!(stones.len(), 2, "{st}");
    assert_eq!(layout["stones"], 2);
    assert_eq!(st["saw_plan"].as_array().unwrap().len(), 1, "{st}");
    let mut total = 0.0;
    for (k, stone) in stones.iter().enumerate() {
        assert_eq!(stone["family"], "round-brilliant");
        assert_eq!(stone["stem"], format!("stone-{}", k + 1));
        let ct = stone["carats"].as_f64().unwrap();
        // Weight ranks by carats: the value shown is the weight.
        assert_eq!(stone["objective"].as_f64().unwrap(), ct);
        total += ct;
        // The position lies inside the octahedron |x| + |y| + |z| <= 3 by the allowance.
        let c: Vec<f64> = (0..3)
            .map(|i| stone["centre_mm"][i].as_f64().unwrap())
            .collect();
        let l1 = c.iter().map(|x| x.abs()).sum::<f64>();
        assert!(l1 < 3.0 - allowance * 3f64.sqrt(), "{c:?}");
        // Each stone's plan is listed with its views.
        let p = st["plans"]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["stem"] == stone["stem"])
            .unwrap();
        assert_eq!(s.get(p["views"].as_str().unwrap()).status, 200);
    }
    assert!((layout["total_carats"].as_f64().unwrap() - total).abs() < 1e-9);
    let overview = s.get(st["overview"].as_str().unwrap());
    assert_eq!(overview.status, 200);
    assert!(png_size(&overview.body).0 > 100);
}
