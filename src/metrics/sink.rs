//! One backward trace from the viewer and what it measures: a [`Job`] (pose, index, the
//! images wanted), the [`PoseSink`] that sums each exit into light return, ASET bins and
//! spot-light images, and the [`PoseResult`] it hands back (with the ray floor's closure).

use super::config::ScoreConfig;
use super::fire::{FireLattice, Reach};
use super::symmetry::OrbitCoverage;
use crate::beam::{ExitBeam, ExitSink, Frame, Medium, Stone, TraceOptions, TraceStats};
use crate::geometry::{clip2d, Polyhedron};
use crate::render::lighting::{aset_shares_in, Cone, Lighting};
use crate::render::raster::{Coverage, Raster};
use crate::render::Tilt;
use crate::render::PORT_DEG;
use glam::{DMat3, DVec2};

/// One backward trace from the viewer at one pose and index, and what to measure on it.
#[derive(Clone, Debug)]
pub(super) struct Job {
    pub(super) tilt: Tilt,
    pub(super) ri: f64,
    /// What the trace goes through (the index `ri` alone, or a birefringent crystal whose
    /// absorption per mode is this job's body colour when it draws the colour).
    pub(super) medium: Medium,
    /// Spot-light images: indices into the lightings of [`score`] (fire's placements, then
    /// scintillation's turns), in the order of [`PoseResult::images`].
    ///
    /// [`score`]: super::score
    pub(super) images: Vec<usize>,
    /// Per image, the world map `G` (a symmetry of the stone about the z axis) taking this
    /// job's traced pose to the pose the image shows, when they differ (see
    /// [`symmetric_pose_map`]): each exit is seen along `G w` with its footprint mapped by `G`.
    ///
    /// [`symmetric_pose_map`]: super::symmetry::symmetric_pose_map
    pub(super) views: Vec<Option<DMat3>>,
    /// ISO and COS sums (brilliance).
    pub(super) brilliance: bool,
    /// Upward share and ASET bins (face-up).
    pub(super) face_up: bool,
    /// Split threshold of this trace.
    pub(super) split: f64,
    /// Body-colour absorption of this trace (per unit of the canonical solid; 0 = none) and
    /// whether it draws the coloured stone's face-up ISO picture ([`ColourImages`]). Every
    /// other measure of the job takes the exits' unabsorbed power, which is the colourless
    /// trace's bit for bit.
    pub(super) absorption: f64,
    pub(super) colour: bool,
}

/// A coloured stone's face-up ISO picture in one wavelength band on the colour grid
/// ([`COLOUR_GRID`](crate::render::COLOUR_GRID); radiance times covered share per pixel,
/// absorbed), the same for the light through the stone alone (its surface
/// reflection left out, for extinction), and the absorbed power seen and its part from below
/// the girdle plane (windowing).
#[derive(Clone, Debug)]
pub(super) struct ColourImages {
    pub(super) all: Raster,
    pub(super) through: Raster,
    pub(super) seen: f64,
    pub(super) below: f64,
}

/// What a [`Job`] measured.
#[derive(Clone, Debug, Default)]
pub(super) struct PoseResult {
    pub(super) power_in: f64,
    pub(super) traced: f64,
    pub(super) up: f64,
    pub(super) iso: f64,
    pub(super) cos: f64,
    pub(super) aset: [f64; 5],
    /// The same sums over the late exits of narrow beams' rays only ([`ExitBeam::late`];
    /// `traced` is their power), for the closure of the rays' stopped power.
    late: Sums,
    pub(super) images: Vec<Raster>,
    pub(super) colour: Option<ColourImages>,
}

/// Power-weighted sums over exits.
#[derive(Clone, Copy, Debug, Default)]
struct Sums {
    traced: f64,
    up: f64,
    iso: f64,
    cos: f64,
    aset: [f64; 5],
}

impl PoseResult {
    /// Hand the power of rays stopped by the ray floor (`closed`) back with the mean of the
    /// late narrow exits (of rays that had already lost half their power): the light a ray
    /// still carries after losing most of it leaves like that, and dimmer than the narrow
    /// exits as a whole (measured on 8 tilted poses of four presets, brilliance's radiance of
    /// the stopped light when followed to the end: 0.386–0.449; the late exits' mean is within
    /// 0.04 of it, all narrow exits' 0.02–0.12 above it). Pictures are not closed (the
    /// closed light is a few tenths of a percent, spread thin).
    fn close(&mut self, closed: f64) {
        let n = self.late;
        if !(closed > 0.0 && n.traced > 0.0) {
            return;
        }
        let k = closed / n.traced;
        self.traced += closed;
        self.up += k * n.up;
        self.iso += k * n.iso;
        self.cos += k * n.cos;
        for (a, b) in self.aset.iter_mut().zip(n.aset) {
            *a += k * b;
        }
    }
}

pub(super) struct PoseSink<'a> {
    rot: DMat3,
    light: &'a Lighting,
    /// Fire's placements, when this job's first images are theirs (all of them, in order).
    lattice: Option<&'a FireLattice<'a>>,
    spots: Vec<&'a Lighting>,
    /// Per image, its view's world map and that map's 2×2 part for footprints
    /// ([`Job::views`]).
    views: Vec<Option<(DMat3, [f64; 4])>>,
    /// A footprint mapped by a view, and its coverage.
    vfoot: Vec<DVec2>,
    vcov: Coverage,
    area: f64,
    face_up: bool,
    brilliance: bool,
    r: PoseResult,
    /// The current exit's footprint coverage (the same for every image).
    cov: Coverage,
    /// The copies of one traced exit (its orbit) under a symmetric trace's maps: per class
    /// of maps that differ by a symmetry of the pixel grid, the first copy's coverage; the
    /// other copies in its class move its pixels instead of clipping again.
    pub(super) orbit: OrbitCoverage,
    /// The same for the colour pictures, drawn on their own grid
    /// ([`COLOUR_GRID`](crate::render::COLOUR_GRID)), and the current exit's coverage there.
    corbit: OrbitCoverage,
    ccov: Coverage,
    /// Fire's placement lookup for the current orbit's elevation (shared by its copies).
    reach: Reach,
    /// The ASET bins' viewer port ([`PORT_DEG`]).
    port: Cone,
}

impl ExitSink for PoseSink<'_> {
    fn wants_footprints(&self) -> bool {
        !self.r.images.is_empty() || self.r.colour.is_some()
    }
    /// Fire's face-up traces measure nothing else: an exit (with its symmetric copies, which
    /// share its elevation) that no placement of the spots can reach is skipped whole.
    fn wants_orbit(&self, e: &ExitBeam) -> bool {
        let fire_only = self.lattice.map_or(0, |l| l.lightings.len());
        if self.face_up
            || self.brilliance
            || self.r.images.len() > fire_only
            || self.r.colour.is_some()
        {
            return true;
        }
        self.lattice
            .is_some_and(|l| l.reaches((self.rot * e.direction).z))
    }
    fn symmetries(&mut self, maps: &[(u16, [f64; 4])]) {
        self.orbit = OrbitCoverage::new(maps);
        self.corbit = OrbitCoverage::new(maps);
    }
    fn exit(&mut self, e: &ExitBeam, fp: &[DVec2]) {
        if e.sym == 0 {
            self.orbit.start();
            self.corbit.start();
        }
        let w = self.rot * e.direction;
        // Everything but the colour sees the colourless stone.
        let p = e.unabsorbed;
        let r = &mut self.r;
        if self.face_up {
            r.traced += p;
            let up = if w.z > 0.0 { p } else { 0.0 };
            r.up += up;
            let b = aset_shares_in(w, Some(&self.port));
            for (acc, x) in r.aset.iter_mut().zip(b) {
                *acc += p * x;
            }
            if e.late {
                r.late.up += up;
                for (acc, x) in r.late.aset.iter_mut().zip(b) {
                    *acc += p * x;
                }
            }
        }
        if self.brilliance {
            let (iso, cos) = (p * self.light.iso(w), p * self.light.cos(w));
            r.iso += iso;
            r.cos += cos;
            if e.late {
                r.late.iso += iso;
                r.late.cos += cos;
            }
        }
        if e.late {
            r.late.traced += p;
        }
        // The footprint's area and pixel coverage, computed on first use: every image has
        // the same size, so one coverage serves them all (a view's mapped footprint has its
        // own).
        let mut a = -1.0;
        let mut covered = false;
        let mut skip = 0;
        let cov = &mut self.cov;
        let orbit = &mut self.orbit;
        if let Some(lat) = self.lattice {
            skip = lat.lightings.len();
            let (images, scale) = (&mut r.images[..skip], p * self.area);
            if e.sym == 0 {
                lat.reach_into(w, &mut self.reach);
            }
            lat.for_each(w, orbit.azimuth(e.sym, w), &self.reach, |k, l| {
                if a < 0.0 {
                    a = clip2d::area(fp);
                }
                if l > 0.0 && a > 0.0 {
                    if !covered {
                        orbit.cover(&images[k], e.sym, fp, cov);
                        covered = true;
                    }
                    images[k].add_coverage(cov, l * scale / a);
                }
            });
        }
        if let Some(c) = r.colour.as_mut() {
            // The absorbed light under ISO (with the head shadow), as `render` draws a
            // coloured stone.
            c.seen += e.power;
            if w.z < 0.0 {
                c.below += e.power;
            }
            let l = self.light.iso(w);
            if a < 0.0 {
                a = clip2d::area(fp);
            }
            if l > 0.0 && a > 0.0 && e.power > 0.0 {
                // On the colour grid: its own coverage.
                let ccov = &mut self.ccov;
                self.corbit.cover(&c.all, e.sym, fp, ccov);
                let v = l * e.power * self.area / a;
                c.all.add_coverage(ccov, v);
                if !e.external {
                    c.through.add_coverage(ccov, v);
                }
            }
        }
        // Skipping on each slice iterator is O(1), unlike skipping the zipped pairs.
        for ((img, light), view) in r
            .images
            .iter_mut()
            .skip(skip)
            .zip(self.spots.iter().skip(skip))
            .zip(self.views.iter().skip(skip))
        {
            // Another pose, the traced one under a symmetry: its own direction and footprint
            // (of the same area).
            let wv = view.as_ref().map_or(w, |(g, _)| *g * w);
            if !light.near_spot(wv) {
                continue;
            }
            let l = light.spots(wv);
            if a < 0.0 {
                a = clip2d::area(fp);
            }
            if !(l > 0.0 && a > 0.0) {
                continue;
            }
            // Radiance through this beam: its power per unit of footprint, relative to the
            // incoming power per unit of cross-section.
            let v = l * p * self.area / a;
            match view {
                Some((_, m)) => {
                    self.vfoot.clear();
                    self.vfoot.extend(
                        fp.iter()
                            .map(|q| DVec2::new(m[0] * q.x + m[1] * q.y, m[2] * q.x + m[3] * q.y)),
                    );
                    img.coverage_into(&self.vfoot, &mut self.vcov);
                    img.add_coverage(&self.vcov, v);
                }
                None => {
                    if !covered {
                        orbit.cover(img, e.sym, fp, cov);
                        covered = true;
                    }
                    img.add_coverage(cov, v);
                }
            }
        }
    }
}

/// What every job of one score shares: the stone and its solid, the light and the spot
/// lightings, fire's lattice, the score's settings and the images' half-width.
#[derive(Clone, Copy)]
pub(super) struct JobContext<'a> {
    pub(super) stone: &'a Stone,
    pub(super) solid: &'a Polyhedron,
    pub(super) light: &'a Lighting,
    pub(super) lightings: &'a [Lighting],
    pub(super) lattice: &'a FireLattice<'a>,
    pub(super) cfg: &'a ScoreConfig,
    pub(super) half: f64,
}

impl<'a> JobContext<'a> {
    /// Trace `job` and measure it.
    pub(super) fn run(&self, job: &Job) -> PoseResult {
        let (frame, opts, mut sink) = self.sink(job);
        let (stats, _) = self
            .stone
            .trace_medium_into(&frame, &job.medium, &opts, &mut sink, false);
        sink.finish(stats)
    }

    /// A job's viewer frame, trace settings and sink (see [`JobContext::run`]).
    pub(super) fn sink(&self, job: &Job) -> (Frame, TraceOptions, PoseSink<'a>) {
        let JobContext {
            solid,
            light,
            lightings,
            lattice,
            cfg,
            half,
            ..
        } = *self;
        let rot = job.tilt.rotation();
        let frame = Frame::viewer(rot);
        let opts = TraceOptions {
            polarization: cfg.trace.polarization,
            footprints: !job.images.is_empty(),
            split_threshold: job.split,
            // The face-up figures are the cross-checked exact ones: no closure there.
            ray_floor: if job.face_up {
                0.0
            } else {
                cfg.trace.ray_floor
            },
            narrow_forks: cfg.trace.narrow_forks && !job.face_up,
            absorption: job.absorption,
            ..cfg.trace
        };
        let spots: Vec<&Lighting> = job
            .images
            .iter()
            .filter_map(|&i| lightings.get(i))
            .collect();
        let views = job
            .views
            .iter()
            .map(|g| g.map(|g| (g, [g.x_axis.x, g.y_axis.x, g.x_axis.y, g.y_axis.y])))
            .collect();
        let n = lattice.lightings.len();
        let has_fire = job.images.len() >= n && job.images[..n].iter().copied().eq(0..n);
        let sink = PoseSink {
            rot,
            light,
            lattice: has_fire.then_some(lattice),
            area: solid.projected_area(-frame.dir),
            face_up: job.face_up,
            brilliance: job.brilliance,
            r: PoseResult {
                images: spots
                    .iter()
                    .map(|_| Raster::new(cfg.resolution, half))
                    .collect(),
                colour: job.colour.then(|| ColourImages {
                    all: Raster::new(crate::render::COLOUR_GRID, half),
                    through: Raster::new(crate::render::COLOUR_GRID, half),
                    seen: 0.0,
                    below: 0.0,
                }),
                ..Default::default()
            },
            spots,
            views,
            vfoot: Vec::new(),
            vcov: Coverage::default(),
            cov: Coverage::default(),
            orbit: OrbitCoverage::default(),
            corbit: OrbitCoverage::default(),
            ccov: Coverage::default(),
            reach: Reach::default(),
            port: Cone::new(PORT_DEG),
        };
        (frame, opts, sink)
    }
}

impl PoseSink<'_> {
    /// What the job measured, once its trace (with `stats`) is done.
    pub(super) fn finish(mut self, stats: TraceStats) -> PoseResult {
        self.r.power_in = stats.power_in;
        self.r.close(stats.ray_closed);
        self.r
    }
}
