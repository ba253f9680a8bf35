use super::DrawResult;
use super::*;
use crate::photon::{rotation_sweep, trace_cut, Light, LightKind, TraceConfig};
use plotters::chart::SeriesLabelPosition;
use plotters::coord::Shift;
use plotters::prelude::*;

struct Cross;

impl Figure for Cross {
    fn size(&self) -> (u32, u32) {
        (120, 80)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let mut chart = ChartBuilder::on(root).build_cartesian_2d(0f64..1f64, 0f64..1f64)?;
        chart
            .draw_series(LineSeries::new([(0.0, 0.0), (1.0, 1.0)], TAB10[0]))?
            .label("key-a")
            .legend(line_key(TAB10[0].stroke_width(2), 20));
        legend(
            &mut chart,
            SeriesLabelPosition::UpperLeft,
            LegendStyle::Compact,
        )
    }
}

#[test]
fn save_writes_png_and_svg_and_no_temporary_files() {
    let dir = tempfile::tempdir().unwrap();
    save(&Cross, &dir.path().join("x.v2")).unwrap();
    let png = std::fs::read(dir.path().join("x.v2.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let svg = std::fs::read_to_string(dir.path().join("x.v2.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("key-a"), "{svg}");
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|f| f.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
    // A missing folder is a one-line error naming the file, not a panic.
    let bad = dir.path().join("no/such/x");
    let err = save(&Cross, &bad).unwrap_err().to_string();
    assert!(!err.contains('\n') && err.contains("x.png"), "{err}");
}

#[test]
fn every_figure_is_written_as_png_and_svg() {
    let dir = std::env::temp_dir().join(format!("facetlab-plot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cut = crate::io::load_cut("tolkowsky").unwrap();
    let cfg = TraceConfig {
        photons: 3_000,
        record_paths: 30,
        ..TraceConfig::thesis()
    };
    let t = trace_cut(&cut.solid, &cut.name, &Light::directed(0.0), &cfg, None).unwrap();
    let sweep = rotation_sweep(
        &cut.solid,
        &cut.name,
        LightKind::Directed,
        &TraceConfig {
            photons: 300,
            ..cfg.clone()
        },
        None,
    )
    .unwrap();
    let cam = Camera {
        azimuth_deg: 30.0,
        elevation_deg: 20.0,
    };
    face_categories(&[&t, &t], "test", &dir.join("bars")).unwrap();
    exit_angle_cdf(&[&t], "test", &dir.join("cdf")).unwrap();
    rotation(&[("tolkowsky", &sweep)], "directed", &dir.join("rot")).unwrap();
    facet_categories(&cut.solid, cam, "facets", &dir.join("facets")).unwrap();
    for color in [PathColor::Bounces, PathColor::Wavelength] {
        let style = PathStyle {
            camera: cam,
            color,
            first_segment: false,
            alpha: 0.3,
            max_paths: 30,
            title: "paths".into(),
        };
        photon_paths(&cut.solid, &t.paths, &style, &dir.join("paths")).unwrap();
    }
    for stem in ["bars", "cdf", "rot", "facets", "paths"] {
        let png = std::fs::read(dir.join(format!("{stem}.png"))).unwrap();
        assert_eq!(&png[1..4], b"PNG", "{stem}");
        let svg = std::fs::read_to_string(dir.join(format!("{stem}.svg"))).unwrap();
        assert!(svg.contains("<svg") && svg.len() > 1000, "{stem}");
    }
    // No temporary files are left behind.
    assert!(std::fs::read_dir(&dir).unwrap().all(|f| !f
        .unwrap()
        .file_name()
        .to_string_lossy()
        .starts_with('.')));
    // A missing folder is a one-line error, not a panic.
    let err = face_categories(&[&t], "x", &dir.join("no/such/dir/bars"))
        .unwrap_err()
        .to_string();
    assert!(!err.contains('\n'), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn one_palette() {
    assert!(SERIES.iter().all(|c| TAB10.contains(c)));
    assert!(CATEGORY_COLORS.iter().all(|c| TAB10.contains(c)));
    assert_eq!(every_30(&60.0), "60°");
    assert_eq!(every_30(&50.0), "");
}
