//! Where exit beams leave ([`ExitSink::exit_at`](crate::beam::ExitSink::exit_at)) and traces
//! of part of the cross-section ([`Stone::trace_window_into`]).

use super::{dirs, solids};
use crate::beam::{ExitBeam, ExitSink, Frame, Medium, Stone, TraceOptions};
use crate::optics::crystal::{Crystal, WaveMode};
use crate::optics::refract;
use crate::testkit::{boxed, tolkowsky};
use glam::{DVec2, DVec3, DVec4};

/// Keeps every exit with its footprint and place (narrow beams' as their polygons when
/// `polygons`).
#[derive(Default)]
struct Places {
    exits: Vec<(ExitBeam, Vec<DVec2>, Vec<DVec3>)>,
    polygons: bool,
}

impl ExitSink for Places {
    fn wants_footprints(&self) -> bool {
        true
    }
    fn wants_exit_places(&self) -> bool {
        true
    }
    fn wants_narrow_polygons(&self) -> bool {
        self.polygons
    }
    fn exit(&mut self, _: &ExitBeam, _: &[DVec2]) {
        unreachable!("the tracer hands exits out with their places");
    }
    fn exit_at(&mut self, e: &ExitBeam, fp: &[DVec2], place: &[DVec3]) {
        self.exits.push((*e, fp.to_vec(), place.to_vec()));
    }
}

/// Light straight through a box, tilted: each footprint vertex's ray, refracted at the top
/// by Snell's law (computed here) and run to the bottom, leaves at the place vertex handed
/// out with it.
#[test]
fn straight_through_places_follow_snell() {
    let solid = boxed(0.5, 0.5, 0.2);
    let stone = Stone::new(&solid);
    let frame = Frame::new(DVec3::new(0.3, -0.2, -1.0)).unwrap();
    let ri = 1.7;
    let mut sink = Places::default();
    let opts = TraceOptions::exact(1e-9);
    stone.trace_window_into(&frame, ri, &opts, &[], &mut sink, false);
    let t = refract(frame.dir, DVec3::Z, 1.0, ri).unwrap();
    let mut checked = 0;
    for (e, fp, place) in &sink.exits {
        // Entered the top (z = 0.2) and left the bottom (z = −0.2) at once.
        if e.external || e.reflections != 0 || stone.normal(e.exit_facet).z > -0.5 {
            continue;
        }
        assert_eq!(fp.len(), place.len());
        for (p, x) in fp.iter().zip(place) {
            // The entry point on the top plane whose image coordinates are p.
            let (u, v) = (frame.u, frame.v);
            let base = u * p.x + v * p.y;
            let top = base + frame.dir * ((0.2 - base.z) / frame.dir.z);
            let bottom = top + t * ((-0.2 - top.z) / t.z);
            assert!((bottom - *x).length() < 1e-12, "{bottom} {x}");
        }
        checked += 1;
    }
    assert!(checked > 0);
}

/// An internal exit of a narrow beam: the exit, its polygon, its exit facet's normal.
type NarrowExit = (ExitBeam, Vec<DVec3>, DVec3);

/// The tilted box of the narrow-polygon tests and the light through it, every beam narrow
/// (split threshold above the light), traced through `medium` twice: with one-point places
/// and with narrow beams' polygons ([`ExitSink::wants_narrow_polygons`]). Each internal exit
/// (the same in both traces) has its polygon on its exit facet's plane and its area centroid
/// at the one-point place (sliding a polygon along one direction between planes keeps its
/// centroid); returned with its polygon and its facet's normal.
fn narrow_box_exits(medium: Medium) -> (Frame, Vec<NarrowExit>) {
    let solid = boxed(0.5, 0.5, 0.2);
    let stone = Stone::new(&solid);
    let frame = Frame::new(DVec3::new(0.3, -0.2, -1.0)).unwrap();
    let opts = TraceOptions {
        split_threshold: 2.0,
        symmetry: false,
        ..TraceOptions::default()
    };
    let mut points = Places::default();
    stone.trace_medium_into(&frame, &medium, &opts, &mut points, false);
    let mut polys = Places {
        polygons: true,
        ..Places::default()
    };
    stone.trace_medium_into(&frame, &medium, &opts, &mut polys, false);
    assert_eq!(points.exits.len(), polys.exits.len());
    let mut out = Vec::new();
    for ((e, _, one), (f, _, poly)) in points.exits.iter().zip(&polys.exits) {
        assert_eq!((e.exit_facet, e.mode), (f.exit_facet, f.mode));
        if e.external {
            continue;
        }
        assert!(
            e.narrow && one.len() == 1 && poly.len() >= 3,
            "{e:?} {poly:?}"
        );
        let plane = solid.facets()[e.exit_facet].plane;
        for x in poly {
            assert!((plane.normal.dot(*x) - plane.offset).abs() < 1e-12);
        }
        let (c, _) = crate::beam::exact::area_centroid(poly, plane.normal);
        assert!((c - one[0]).length() < 1e-12, "{c} {}", one[0]);
        out.push((*e, poly.clone(), plane.normal));
    }
    (frame, out)
}

/// A narrow beam's polygon carried along its ray ([`ExitSink::wants_narrow_polygons`]):
/// through a tilted box with every beam narrow, the light straight through leaves the bottom
/// in the whole top face slid along the refracted ray (Snell's law computed here): its
/// vertices there and its area the top's (1); every narrow place, reflected ones too, lies on
/// its exit facet with its centroid at the one-point place ([`narrow_box_exits`]).
#[test]
fn narrow_polygons_are_carried_to_the_exit() {
    let ri = 1.7;
    let (frame, exits) = narrow_box_exits(Medium::Isotropic(ri));
    let t = refract(frame.dir, DVec3::Z, 1.0, ri).unwrap();
    let mut checked = 0;
    for (e, poly, n) in &exits {
        if e.reflections != 0 || n.z > -0.5 {
            continue;
        }
        let (_, area) = crate::beam::exact::area_centroid(poly, *n);
        assert!((area - 1.0).abs() < 1e-12, "{area}");
        for x in poly {
            let top = *x + t * ((0.2 - x.z) / t.z);
            assert!((top.x.abs() - 0.5).abs() < 1e-12 && (top.y.abs() - 0.5).abs() < 1e-12);
        }
        checked += 1;
    }
    assert_eq!(checked, 1);
}

/// A birefringent narrow beam's polygon is carried along each mode's own ray: through the
/// tilted box of a uniaxial crystal whose axis is tilted (walk-off), every beam narrow, each
/// exit's polygon lies on its exit facet with its centroid at the ray's one-point place
/// ([`narrow_box_exits`]), the light straight through leaves the bottom over the top face's
/// area (1), and both modes' rays carry polygons.
#[test]
fn birefringent_narrow_polygons_follow_each_mode() {
    let (_, exits) = narrow_box_exits(Medium::Uniaxial {
        crystal: Crystal::new(1.9254, 1.9841, DVec3::new(0.6, 0.3, 0.74).normalize()),
        alpha_o: 0.0,
        alpha_e: 0.0,
    });
    // Straight through (the narrow pair entering goes on as its stronger mode's ray), over
    // the top face's area; and both modes' rays, reflected ones, carry polygons.
    let straight: Vec<f64> = exits
        .iter()
        .filter(|(e, _, n)| e.reflections == 0 && n.z < -0.5)
        .map(|(_, poly, n)| crate::beam::exact::area_centroid(poly, *n).1)
        .collect();
    assert!(!straight.is_empty());
    for area in straight {
        assert!((area - 1.0).abs() < 1e-12, "{area}");
    }
    for mode in [WaveMode::Ordinary, WaveMode::Extraordinary] {
        assert!(exits.iter().any(|(e, _, _)| e.mode == Some(mode)));
    }
}

/// Every exit's place lies on its exit facet's plane; an exact beam's has its footprint's
/// vertex count, a narrow beam's is one point; symmetric copies' places are the traced ones
/// turned (their facets' planes hold them too).
#[test]
fn places_lie_on_the_exit_facets() {
    for (name, s) in solids() {
        let stone = Stone::new(&s);
        for frame in dirs() {
            let mut sink = Places::default();
            stone.trace_window_into(
                &frame,
                2.4173,
                &TraceOptions::default(),
                &[],
                &mut sink,
                false,
            );
            assert!(!sink.exits.is_empty());
            for (e, fp, place) in &sink.exits {
                if e.narrow {
                    assert_eq!(place.len(), 1, "{name}");
                } else {
                    assert_eq!(place.len(), fp.len(), "{name}");
                }
                let f = &s.facets()[e.exit_facet];
                for x in place {
                    let off = f.plane.normal.dot(*x) - f.plane.offset;
                    assert!(off.abs() < 1e-9, "{name}: {off}");
                }
            }
        }
    }
}

/// Four quadrant windows trace the whole cross-section between them: their incoming power
/// adds up to 1 and their exits' power to the whole trace's: to rounding for the light that
/// leaves after at most two internal reflections, within the light cut off upward and
/// downward (exact traces, split to 1e-10). For a singly refractive stone and for a
/// birefringent one whose optic axis is tilted (the photographs' perspective tiles of a
/// zircon): its beams split in two at every facet, so it is split to 1e-6 only, where its
/// early light has beams near the threshold too and agrees within the light cut off.
#[test]
fn windows_add_up_to_the_whole() {
    let axis = DVec3::new(0.5, 0.3, 0.8).normalize();
    let crystal = Medium::Uniaxial {
        crystal: Crystal::new(1.9254, 1.9841, axis),
        alpha_o: 0.0,
        alpha_e: 0.0,
    };
    windows_add_up(&Medium::Isotropic(2.4173), 1e-10, Some(1e-11));
    windows_add_up(&crystal, 1e-6, None);
}

/// `early_tol`: how close the early light must be (`None`: within the light cut off).
fn windows_add_up(medium: &Medium, split: f64, early_tol: Option<f64>) {
    let stone = Stone::new(&tolkowsky());
    let frame = Frame::new(DVec3::new(0.2, -0.35, -1.0)).unwrap();
    let opts = TraceOptions {
        symmetry: false,
        threshold: if early_tol.is_some() { split } else { 1e-10 },
        ..TraceOptions::exact(split)
    };
    let whole = stone.trace_medium(&frame, medium, 589.3, &opts);
    let (x0, y0) = (0.031, -0.047);
    let (u, v) = (frame.u, frame.v);
    let quadrants = [
        [(u, x0), (v, y0)],
        [(-u, -x0), (v, y0)],
        [(u, x0), (-v, -y0)],
        [(-u, -x0), (-v, -y0)],
    ];
    let (mut power_in, mut up, mut down, mut cut) = (0.0, 0.0, 0.0, 0.0);
    // Light that left after at most two internal reflections: no beam of it is anywhere
    // near the threshold, so it is the same light to rounding.
    let (mut early, mut whole_early) = (0.0, 0.0);
    for q in quadrants {
        let window: Vec<DVec4> = q.iter().map(|&(n, c)| n.extend(c)).collect();
        let mut sink = Places::default();
        let (st, _) =
            stone.trace_medium_window_into(&frame, medium, &opts, &window, &mut sink, false);
        power_in += st.power_in;
        cut += st.cut_off;
        for (e, fp, _) in &sink.exits {
            // Every footprint inside its window.
            for p in fp {
                let x = u * p.x + v * p.y;
                for h in &window {
                    assert!(h.truncate().dot(x) <= h.w + 1e-9);
                }
            }
            if e.direction.z > 0.0 {
                up += e.power;
            } else {
                down += e.power;
            }
            if e.reflections <= 2 {
                early += e.power;
            }
        }
    }
    for e in whole.exits.iter().filter(|e| e.reflections <= 2) {
        whole_early += e.power;
    }

    let (wu, wd): (f64, f64) = whole.exits.iter().fold((0.0, 0.0), |(a, b), e| {
        if e.direction.z > 0.0 {
            (a + e.power, b)
        } else {
            (a, b + e.power)
        }
    });
    assert!((power_in - 1.0).abs() < 1e-12, "{power_in}");
    // Smaller root beams are cut off a little differently below the threshold.
    let slack = cut + whole.stats.cut_off;
    assert!(slack < 1e-4, "{slack}");
    let early_tol = early_tol.unwrap_or(slack);
    assert!(
        (early - whole_early).abs() <= early_tol,
        "{early} {whole_early} (allowed {early_tol})"
    );
    assert!((up - wu).abs() <= slack, "{up} {wu}");
    assert!((down - wd).abs() <= slack, "{down} {wd}");
    assert!((up + down + cut - 1.0).abs() < 1e-12);
}
