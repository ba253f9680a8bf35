//! The stone's symmetries, used to trace once what they repeat: the representative of a pose
//! ([`symmetric_pose`]) and the map taking it to the pose ([`symmetric_pose_map`]), and the
//! coverages of the symmetric copies of one traced exit ([`OrbitCoverage`]).

use crate::beam::mirror_matrix;
use crate::render::raster::{Coverage, GridMap, Raster};
use crate::render::Tilt;
use glam::{DMat3, DVec2, DVec3};

/// Coverages of the copies of one traced exit that a symmetric trace hands out
/// ([`ExitSink::symmetries`]). Their footprint maps fall into classes `G · R` (`R` the class's
/// first map, `G` a symmetry of the pixel grid, [`GridMap`]); within a class, coverages are
/// each other's with the pixels moved. A face-up round brilliant's 16 maps make two classes
/// (the quarter turns and the mirrors through the axes and diagonals, times 1 or a 45° turn),
/// so two clips serve all 16 copies.
///
/// [`ExitSink::symmetries`]: crate::beam::ExitSink::symmetries
#[derive(Debug, Default)]
pub(super) struct OrbitCoverage {
    /// Per symmetry index: its class and its map's grid part `G`.
    class: Vec<Option<(usize, GridMap)>>,
    /// Per class: the first coverage computed for the current orbit, and that copy's `G`.
    pub(super) first: Vec<(Option<GridMap>, Coverage)>,
    /// Per symmetry index: how it moves an azimuth, `a ↦ sign · a + turn` (degrees).
    turns: Vec<(f64, f64)>,
    /// The azimuth of the current orbit's identity copy, degrees.
    azimuth: f64,
}

impl OrbitCoverage {
    /// Sort the maps `(index, [a, b, c, d])` (orthogonal) into classes.
    pub(super) fn new(maps: &[(u16, [f64; 4])]) -> OrbitCoverage {
        let mut o = OrbitCoverage::default();
        let mut reps: Vec<[f64; 4]> = Vec::new();
        for &(i, m) in maps {
            let i = usize::from(i);
            // m · rᵀ for each class's first map r.
            let found = reps.iter().enumerate().find_map(|(c, r)| {
                let mt = [
                    m[0] * r[0] + m[1] * r[1],
                    m[0] * r[2] + m[1] * r[3],
                    m[2] * r[0] + m[3] * r[1],
                    m[2] * r[2] + m[3] * r[3],
                ];
                GridMap::of(mt).map(|g| (c, g))
            });
            let entry = found.unwrap_or_else(|| {
                reps.push(m);
                o.first.push((None, Coverage::default()));
                (reps.len() - 1, GridMap::IDENTITY)
            });
            if o.class.len() <= i {
                o.class.resize(i + 1, None);
                o.turns.resize(i + 1, (f64::NAN, f64::NAN));
            }
            o.class[i] = Some(entry);
            // A turn by θ is [cos θ, −sin θ, sin θ, cos θ]; a mirror through the line at β is
            // [cos 2β, sin 2β, sin 2β, −cos 2β]: either way the angle is atan2(c, a).
            let sign = (m[0] * m[3] - m[1] * m[2]).signum();
            o.turns[i] = (sign, m[2].atan2(m[0]).to_degrees());
        }
        o
    }

    /// The azimuth (degrees, up to whole turns) of the copy with symmetry index `sym` and
    /// world direction `w`, from its orbit's identity copy's (one arc-tangent per orbit: ask
    /// for every copy, the identity first), when the trace is symmetric; `None` otherwise.
    /// The maps act on world directions as on footprints: the frames' symmetries keep the
    /// viewer's axis.
    pub(super) fn azimuth(&mut self, sym: u16, w: DVec3) -> Option<f64> {
        let &(sign, turn) = self.turns.get(usize::from(sym))?;
        if sym == 0 {
            self.azimuth = w.y.atan2(w.x).to_degrees();
        }
        Some(sign * self.azimuth + turn)
    }

    /// A new orbit begins (its identity copy arrives).
    pub(super) fn start(&mut self) {
        for f in &mut self.first {
            f.0 = None;
        }
    }

    /// The coverage of the copy with symmetry index `sym` and footprint `fp` on images like
    /// `img`, into `cov`: moved from its class's first coverage of this orbit, or clipped
    /// (and kept as the first).
    pub(super) fn cover(&mut self, img: &Raster, sym: u16, fp: &[DVec2], cov: &mut Coverage) {
        let Some(&Some((c, g))) = self.class.get(usize::from(sym)) else {
            img.coverage_into(fp, cov);
            return;
        };
        let (g0, first) = &mut self.first[c];
        match *g0 {
            Some(g0) => img.map_coverage(first, g.after_inverse_of(g0), cov),
            None => {
                img.coverage_into(fp, first);
                *g0 = Some(g);
                cov.cells.clear();
                cov.cells.extend_from_slice(&first.cells);
            }
        }
    }
}

/// The representative of `tilt` under a stone's symmetry `(order, mirror azimuth)` (see
/// [`Stone::symmetry`]): the stone turned by 360°/order, or mirrored through a mirror line at
/// azimuth β, meets the viewer tilted toward azimuth `a` as the unturned stone meets one tilted
/// toward `a − 360°/order`, or toward `2β − a`. Light returned under an azimuthally symmetric
/// lighting (ISO, COS, the head shadow) is the same for all of them, so brilliance traces
/// one. The representative's azimuth is the smallest in `[0°, 360°/order)` over the group,
/// rounded to 1e-9° so that equal poses are found equal.
///
/// [`Stone::symmetry`]: crate::beam::Stone::symmetry
pub fn symmetric_pose(tilt: Tilt, (order, mirror): (usize, Option<f64>)) -> Tilt {
    if tilt.tilt_deg == 0.0 || order == 0 {
        return tilt;
    }
    let period = 360.0 / order as f64;
    let snap = |a: f64| {
        let a = (a.rem_euclid(period) * 1e9).round() / 1e9;
        if a >= period {
            0.0
        } else {
            a
        }
    };
    let mut a = snap(tilt.azimuth_deg);
    if let Some(beta) = mirror {
        a = a.min(snap(2.0 * beta.to_degrees() - a));
    }
    Tilt {
        tilt_deg: tilt.tilt_deg,
        azimuth_deg: a,
    }
}

/// [`symmetric_pose`] with the symmetry taking it to `tilt`: the representative pose and,
/// unless it is `tilt` itself, the world map `G` (a rotation about the z axis or a mirror
/// through it, a symmetry of the stone) with `tilt.rotation() = G · rep.rotation() · Gᵀ`. The
/// stone at `tilt` is then the stone at the representative moved by `G` (the viewer on the z
/// axis stays put): its exits leave along `G w` with footprints mapped by `G`.
pub(super) fn symmetric_pose_map(
    tilt: Tilt,
    symmetry: (usize, Option<f64>),
) -> (Tilt, Option<DMat3>) {
    let rep = symmetric_pose(tilt, symmetry);
    let (order, mirror) = symmetry;
    if tilt.tilt_deg == 0.0 || order == 0 {
        return (rep, None);
    }
    let period = 360.0 / order as f64;
    // Azimuths equal modulo 360° (the representative is rounded to 1e-9°).
    let same = |a: f64, b: f64| {
        let d = (a - b).rem_euclid(360.0);
        d.min(360.0 - d) < 1e-6
    };
    if same(rep.azimuth_deg, tilt.azimuth_deg) {
        return (rep, None);
    }
    for k in 0..order {
        let turn = k as f64 * period;
        if same(rep.azimuth_deg + turn, tilt.azimuth_deg) {
            return (rep, Some(DMat3::from_rotation_z(turn.to_radians())));
        }
        if let Some(beta) = mirror {
            // The mirror through azimuth γ takes a tilt toward a to one toward 2γ − a.
            let gamma = beta.to_degrees() + 0.5 * turn;
            if same(2.0 * gamma - rep.azimuth_deg, tilt.azimuth_deg) {
                return (rep, Some(mirror_matrix(gamma.to_radians())));
            }
        }
    }
    // Not reached for a representative of `tilt`; tracing `tilt` itself is always right.
    (tilt, None)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::{ExitBeam, ExitSink, Stone, TraceOptions};
    use crate::geometry::{canonical, Polyhedron};
    use crate::metrics::fire::{fire_placements, turned, FireLattice};
    use crate::metrics::scintillation::scintillation_turns;
    use crate::metrics::sink::{Job, JobContext, PoseSink};
    use crate::metrics::ScoreConfig;
    use crate::render::lighting::Lighting;
    use crate::testkit::{princess, tolkowsky};

    /// The jobs' context of `solid` (traced as `stone`) under `cfg`, its pictures as wide as
    /// the score's.
    fn context<'a>(
        stone: &'a Stone,
        solid: &'a Polyhedron,
        light: &'a Lighting,
        lightings: &'a [Lighting],
        lattice: &'a FireLattice<'a>,
        cfg: &'a ScoreConfig,
    ) -> JobContext<'a> {
        JobContext {
            stone,
            solid,
            light,
            lightings,
            lattice,
            cfg,
            half: crate::render::picture_half(solid),
        }
    }

    /// The poses a stone's symmetry maps onto each other return the same light: pictures of a
    /// round brilliant and a princess tilted 10° toward several azimuths have the means of their
    /// representatives' pictures ([`symmetric_pose`]) within the narrow-beam approximation, while
    /// the azimuths that are not equivalent differ by far more.
    #[test]
    fn symmetric_poses_return_the_same_light() {
        use crate::render::{render, Light, RenderOptions};
        let mean = |solid: &Polyhedron, t: Tilt| {
            let mut o = RenderOptions::new(Light::Iso);
            o.size = 32;
            o.tilt = t;
            o.trace.split_threshold = 1e-5;
            render(solid, &o).stats.mean
        };
        for (solid, order) in [(tolkowsky(), 8), (princess(), 4)] {
            let symmetry = Stone::new(&crate::geometry::canonical::canonical(&solid)).symmetry();
            assert_eq!(symmetry.0, order);
            assert!(symmetry.1.is_some());
            let (mut worst, mut spread) = (0.0f64, (f64::INFINITY, f64::NEG_INFINITY));
            for az in [72.0, 144.0, 216.0, 288.0, 100.0] {
                let t = Tilt {
                    tilt_deg: 10.0,
                    azimuth_deg: az,
                };
                let r = symmetric_pose(t, symmetry);
                assert!(r.azimuth_deg >= 0.0 && r.azimuth_deg <= 180.0 / order as f64 + 1e-9);
                let (a, b) = (mean(&solid, t), mean(&solid, r));
                worst = worst.max((a - b).abs());
                spread = (spread.0.min(b), spread.1.max(b));
            }
            eprintln!(
                "order {order}: worst {worst:.2e}, spread {:.2e}",
                spread.1 - spread.0
            );
            assert!(worst < 3e-4, "order {order}: {worst}");
            assert!(spread.1 - spread.0 > 10.0 * worst, "{spread:?} vs {worst}");
        }
    }

    /// [`symmetric_pose_map`]: the pose is its representative moved by the symmetry `G`
    /// (`R(tilt) = G R(rep) Gᵀ`, G orthogonal), for rotation groups with and without mirrors;
    /// and the spot-lit image of a tilted pose, traced itself, is the image its representative's
    /// trace gives seen through `G` (every pixel, to rounding), for a round brilliant and a
    /// princess, rotations and mirrors both (to 1e-8 of the brightest pixel: the
    /// representative's azimuth is rounded to 1e-9°; measured 2.7e-9).
    #[test]
    fn symmetric_pose_views_give_the_pose_s_own_image() {
        for symmetry in [
            (8, Some(0.0)),
            (4, Some(0.3)),
            (3, None),
            (5, Some(0.1)),
            (1, None),
        ] {
            for k in 0..36 {
                let t = Tilt {
                    tilt_deg: 7.0,
                    azimuth_deg: 10.0 * k as f64 + 1.3,
                };
                let (rep, g) = symmetric_pose_map(t, symmetry);
                assert_eq!(rep, symmetric_pose(t, symmetry));
                let g = g.unwrap_or(DMat3::IDENTITY);
                let dist = |a: DMat3, b: DMat3| {
                    (a - b)
                        .to_cols_array()
                        .map(f64::abs)
                        .iter()
                        .fold(0.0, |m: f64, &x| m.max(x))
                };
                assert!(dist(g * g.transpose(), DMat3::IDENTITY) < 1e-12);
                let err = dist(g * rep.rotation() * g.transpose(), t.rotation());
                assert!(err < 1e-9, "{symmetry:?} {t:?} -> {rep:?}: {err}");
            }
        }
        let cfg = ScoreConfig {
            resolution: 32,
            trace: TraceOptions {
                split_threshold: 1e-3,
                ..Default::default()
            },
            ..ScoreConfig::default()
        };
        let mut views = 0;
        for solid in [tolkowsky(), princess()] {
            let solid = canonical::canonical(&solid);
            let stone = Stone::new(&solid);
            let light = Lighting::new(0.0, &cfg.spots);
            let lattice = FireLattice::new(&[], &[]);
            for az in [72.0, 144.0, 216.0, 288.0, 100.0] {
                let t = Tilt {
                    tilt_deg: 3.0,
                    azimuth_deg: az,
                };
                let lightings = [Lighting::new(0.0, &turned(&cfg.spots, az, 0.0))];
                let job = |tilt: Tilt, view: Option<DMat3>| Job {
                    tilt,
                    ri: 2.417,
                    medium: crate::beam::Medium::Isotropic(2.417),
                    images: vec![0],
                    views: vec![view],
                    brilliance: false,
                    face_up: false,
                    split: cfg.trace.split_threshold,
                    absorption: 0.0,
                    colour: false,
                };
                let ctx = context(&stone, &solid, &light, &lightings, &lattice, &cfg);
                let run = |j: &Job| ctx.run(j);
                let (rep, view) = symmetric_pose_map(t, stone.symmetry());
                views += usize::from(view.is_some());
                let own = run(&job(t, None));
                let seen = run(&job(rep, view));
                let (a, b) = (&own.images[0].data, &seen.images[0].data);
                let top = a.iter().fold(0.0f64, |m, &x| m.max(x));
                assert!(top > 0.0);
                let worst = a
                    .iter()
                    .zip(b)
                    .map(|(x, y)| (x - y).abs())
                    .fold(0.0, f64::max);
                // (The representative's azimuth is rounded to 1e-9°.)
                assert!(worst < 1e-8 * top, "{t:?} via {rep:?}: {worst} of {top}");
            }
        }
        // Most of those poses were seen through a symmetry (not traced themselves).
        assert!(views >= 8, "{views}");
    }

    /// The copies of a face-up exit that differ by a symmetry of the pixel grid (quarter turns,
    /// mirrors through the axes and diagonals) take their coverage from one clip: the images of a
    /// face-up trace with fire's placements and scintillation's turns agree, pixel by pixel, with
    /// those of the same trace whose sink clips every copy itself and finds every copy's azimuth
    /// and reach for fire's placements on its own (tolkowsky: two classes of 8; princess: one
    /// of 8; a 3-fold stone: three classes, the identity with a mirror).
    #[test]
    fn orbit_coverage_gives_every_copy_its_own_clip() {
        /// Forwards everything but the symmetries, each copy as if it began an orbit, so every
        /// copy is clipped (and its azimuth and fire's reach found) on its own.
        struct Clipped<'a, 'b>(&'a mut PoseSink<'b>);
        impl ExitSink for Clipped<'_, '_> {
            fn wants_footprints(&self) -> bool {
                self.0.wants_footprints()
            }
            fn wants_orbit(&self, e: &ExitBeam) -> bool {
                self.0.wants_orbit(e)
            }
            fn exit(&mut self, e: &ExitBeam, fp: &[DVec2]) {
                self.0.exit(&ExitBeam { sym: 0, ..*e }, fp)
            }
        }
        let cfg = ScoreConfig {
            resolution: 40,
            fire_placements: 5,
            trace: TraceOptions {
                split_threshold: 1e-3,
                ..Default::default()
            },
            ..ScoreConfig::default()
        };
        // A triangular bipyramid: three-fold with mirrors, three classes.
        let bipyramid = {
            let planes: Vec<crate::geometry::FacetPlane> = (0..6)
                .map(|k| {
                    let a = (120.0 * (k % 3) as f64 + 60.0 * (k / 3) as f64).to_radians();
                    let z = if k < 3 { 0.8 } else { -1.1 };
                    crate::geometry::FacetPlane::new(
                        DVec3::new(a.cos(), a.sin(), z),
                        1.0,
                        format!("b{k}"),
                        "b",
                    )
                })
                .collect();
            Polyhedron::from_planes(&planes).expect("a bipyramid")
        };
        let solids = [(tolkowsky(), 2), (princess(), 1), (bipyramid, 3)];
        for (solid, want_classes) in solids {
            let solid = canonical::canonical(&solid);
            let stone = Stone::new(&solid);
            let light = Lighting::new(0.0, &cfg.spots);
            let placements = fire_placements(&cfg);
            let mut lightings: Vec<Lighting> = placements
                .iter()
                .map(|p| Lighting::new(0.0, &p.spots))
                .collect();
            let n = lightings.len();
            lightings.extend(
                scintillation_turns(&cfg)
                    .iter()
                    .map(|&t| Lighting::new(0.0, &turned(&cfg.spots, t, 0.0))),
            );
            let lattice = FireLattice::new(&placements, &lightings[..n]);
            let job = Job {
                tilt: Tilt::FACE_UP,
                ri: 2.417,
                medium: crate::beam::Medium::Isotropic(2.417),
                images: (0..lightings.len()).collect(),
                views: vec![None; lightings.len()],
                brilliance: true,
                face_up: true,
                split: 1e-4,
                absorption: 0.0,
                colour: false,
            };
            let run = |clip_all: bool| {
                let (frame, opts, mut sink) =
                    context(&stone, &solid, &light, &lightings, &lattice, &cfg).sink(&job);
                let (stats, _) = if clip_all {
                    stone.trace_medium_into(
                        &frame,
                        &job.medium,
                        &opts,
                        &mut Clipped(&mut sink),
                        false,
                    )
                } else {
                    stone.trace_medium_into(&frame, &job.medium, &opts, &mut sink, false)
                };
                let classes = sink.orbit.first.len();
                (sink.finish(stats), classes)
            };
            let ((moved, classes), (clipped, _)) = (run(false), run(true));
            assert_eq!(classes, want_classes, "{:?}", stone.symmetry());
            for (a, b) in moved.images.iter().zip(&clipped.images) {
                let top = b.data.iter().fold(0.0f64, |m, &x| m.max(x));
                let worst = a.max_difference(b);
                // (A stone's mirror found to ~1e-11 counts as the grid's.)
                assert!(worst <= 1e-9 * top, "{worst} of {top}");
            }
            assert!(moved.images.iter().any(|i| i.data.iter().any(|&x| x > 0.0)));
            assert_eq!(moved.iso, clipped.iso);
        }
    }
}
