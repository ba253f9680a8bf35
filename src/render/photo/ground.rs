//! The ground the stone rests on ([`Ground`]): a flat diffuse plane under the stone with its
//! shadow and caustics, from each direction of light the environment sends
//! ([`Environment::samples`](super::env::Environment::samples)).
//!
//! For one direction `ω` with horizontal irradiance `E`, the stone intercepts the power
//! `Φ = (E / ω_z) · A⊥` of a parallel beam over its cross-section `A⊥`. The beam tracer traces
//! it (light travelling along `−ω`); its exit beams leaving downward land on the plane as
//! exact polygons (each exit polygon slid along its direction), each adding its power over
//! its polygon's area (Watt 1990; Heckbert & Hanrahan 1984): the caustic, exact for a
//! directional light, per band. A narrow beam (below the split threshold, followed as one
//! ray) lands over its own cross-section: its polygon carried along the ray to the exit
//! facet, unclipped (`ExitSink::wants_narrow_polygons`), slid onto the plane along its
//! exit direction, its power spread over that area exactly; so a coarse split blurs the
//! caustic a little instead of speckling it. The shadow is the stone's outline projected along `ω` (the
//! convex hull of its vertices' projections), where the plane loses `E`. So on the plane
//!
//! `caustic power + light escaping upward + absorbed + cut off = Φ`,
//!
//! to rounding ([`GroundStats`]). Area lights are summed over their sampled directions.
//! Light the ground sends back to the stone is left out (it is seen, not traced twice): the
//! stone is lit by the environment alone, and sight lines leaving the stone downward see the
//! ground with its shadow and caustics.
//!
//! The irradiance is kept on a square raster around the stone (exact area coverage of every
//! polygon, [`Accumulator`]); beyond it the ground has its unshadowed irradiance. The
//! ground's radiance is `ρ / π · E` (a Lambertian plane of albedo `ρ`).

use super::env::{LightSample, Rgb};
use crate::beam::{ExitBeam, ExitSink, Frame, Medium, Stone, TraceOptions, TraceStats};
use crate::geometry::clip2d;
use crate::render::raster::Accumulator;
use glam::{DMat3, DVec2, DVec3};
use rayon::prelude::*;

/// What the stone stands on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum GroundKind {
    /// No ground: the environment all round.
    None,
    /// White paper or card (albedo 0.8).
    White,
    /// Black velvet (albedo 0.03).
    Black,
}

impl GroundKind {
    /// Every kind, in the order the command line lists them.
    pub const ALL: [GroundKind; 3] = [GroundKind::None, GroundKind::White, GroundKind::Black];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            GroundKind::None => "none",
            GroundKind::White => "white",
            GroundKind::Black => "black",
        }
    }

    /// The kind named `text` (any case); the error names `field` and the three names.
    pub fn parse(field: &str, text: &str) -> crate::error::Result<GroundKind> {
        let t = text.trim().to_ascii_lowercase();
        GroundKind::ALL
            .into_iter()
            .find(|k| k.name() == t)
            .ok_or_else(|| {
                crate::error::Error::invalid(
                    field,
                    format!("`{text}` is not allowed; use white, black or none"),
                )
            })
    }

    /// Albedo (linear sRGB).
    pub fn albedo(self) -> Rgb {
        match self {
            GroundKind::None => [0.0; 3],
            GroundKind::White => [0.8; 3],
            GroundKind::Black => [0.03; 3],
        }
    }
}

/// The ground: its kind and the gap under the stone's lowest point (girdle diameters; 0:
/// resting on it, culet-down or on whatever its pose puts lowest).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Ground {
    /// Its kind.
    pub kind: GroundKind,
    /// Height of the stone's lowest point above it.
    pub gap: f64,
}

impl Default for Ground {
    fn default() -> Self {
        Ground {
            kind: GroundKind::None,
            gap: 0.0,
        }
    }
}

/// The power bookkeeping of the light on the ground, summed over the directions traced; in
/// the units of irradiance × area (relative to the ISO sky's π on a white diffuser).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GroundStats {
    /// Directions of light traced.
    pub directions: usize,
    /// Power the stone intercepts (luminance Y).
    pub intercepted: f64,
    /// Of it, landing on the ground as caustics inside the raster.
    pub caustic: f64,
    /// Landing on the ground beyond the raster.
    pub caustic_outside: f64,
    /// Leaving the stone upward.
    pub escaped: f64,
    /// Absorbed by a body colour.
    pub absorbed: f64,
    /// Cut off by the tracer's thresholds.
    pub cut_off: f64,
    /// `intercepted − caustic − caustic_outside − escaped − absorbed − cut_off`: 0 to
    /// rounding.
    pub balance: f64,
    /// The shadows' area, each direction's weighted by its share of the irradiance.
    pub shadow_area: f64,
    /// Unshadowed irradiance of the ground (luminance).
    pub irradiance: f64,
}

/// How the light of one direction is traced: one or more traces, each standing for some
/// bands.
#[derive(Clone, Debug)]
pub struct Lit {
    /// The light's direction and irradiance.
    pub sample: LightSample,
    /// Its traces.
    pub traces: Vec<LitTrace>,
}

/// One trace of a light's direction: through `medium` with absorption `alpha` (per unit
/// length; a crystal medium carries its own per mode), standing for the bands `(band, irradiance, exponent)`: a band's light is the
/// trace's light before absorption times `T^exponent`, `T` being what the trace's
/// absorption left of it (exponent 1: the band traced itself; `α_b / alpha` for a band of
/// absorption `α_b` that shares the trace: exact for a beam of one path length).
#[derive(Clone, Debug)]
pub struct LitTrace {
    /// The stone's optics in this trace (one index, or a birefringent crystal).
    pub medium: Medium,
    /// Absorption per unit length.
    pub alpha: f64,
    /// `(band, horizontal irradiance, exponent)`.
    pub bands: Vec<(usize, f64, f64)>,
}

/// The ground's irradiance per band on a raster of `n × n` cells over `[−half, half]²`
/// (world x, y), with the plane at height `z`.
#[derive(Clone, Debug)]
pub struct GroundField {
    /// Height of the plane (world z).
    pub z: f64,
    /// Half the raster's side.
    pub half: f64,
    /// Cells per side.
    pub n: usize,
    /// Radiance per unit irradiance in each band: albedo / π.
    pub k: Vec<f64>,
    /// Unshadowed irradiance per band.
    pub e0: Vec<f64>,
    /// Irradiance the caustics bring, per band and cell (row-major, row 0 at y = −half).
    pub caustic: Vec<Vec<f64>>,
    /// Irradiance the shadows take, per band and cell.
    pub shadow: Vec<Vec<f64>>,
    /// The bookkeeping.
    pub stats: GroundStats,
}

/// A downward exit on the plane: its polygon (a range of its trace's points), its light
/// before absorption per unit area (per unit of the trace's share) and what absorption left
/// of it.
struct Landed {
    poly: (u32, u32),
    density: f64,
    kept: f64,
}

/// One trace's result: where its light landed, per band the power a unit share stands for
/// and the exponent of its absorption, its shares escaping upward (per band) and its stats.
struct Trace {
    landed: Vec<Landed>,
    points: Vec<DVec2>,
    bands: Vec<(usize, f64, f64)>,
    up: Vec<f64>,
    stats: TraceStats,
}

/// Collects the exits of a light's trace: downward ones as polygons on the plane.
struct CausticSink<'a> {
    rot: DMat3,
    z: f64,
    /// Side of the square an exit without an area lands on (a birefringent trace's narrow
    /// beam's ray, which carries no polygon, or a beam landing edge-on).
    dot: f64,
    /// The exponents of the bands the trace stands for.
    exponents: &'a [f64],
    landed: Vec<Landed>,
    points: Vec<DVec2>,
    up: Vec<f64>,
}

/// Where the ray from `x` along `w` (world, `w.z < 0`) meets the plane `z`.
#[inline]
pub fn land(x: DVec3, w: DVec3, z: f64) -> DVec2 {
    let t = (z - x.z) / w.z;
    DVec2::new(x.x + w.x * t, x.y + w.y * t)
}

/// `kept^k` (1 when nothing was absorbed; `kept` itself for k = 1).
#[inline]
fn kept_to(kept: f64, k: f64) -> f64 {
    if kept == 1.0 || k == 0.0 {
        1.0
    } else if k == 1.0 {
        kept
    } else {
        kept.powf(k)
    }
}

impl ExitSink for CausticSink<'_> {
    fn wants_exit_places(&self) -> bool {
        true
    }
    fn wants_narrow_polygons(&self) -> bool {
        true
    }
    fn exit(&mut self, e: &ExitBeam, fp: &[DVec2]) {
        self.exit_at(e, fp, &[]);
    }
    fn exit_at(&mut self, e: &ExitBeam, _: &[DVec2], place: &[DVec3]) {
        let w = self.rot * e.direction;
        let kept = if e.unabsorbed > 0.0 {
            (e.power / e.unabsorbed).clamp(0.0, 1.0)
        } else {
            1.0
        };
        if w.z >= 0.0 || place.is_empty() {
            for (u, &k) in self.up.iter_mut().zip(self.exponents) {
                *u += e.unabsorbed * kept_to(kept, k);
            }
            return;
        }
        let h = 0.5 * self.dot;
        let start = self.points.len();
        let square = |c: DVec2, pts: &mut Vec<DVec2>| {
            pts.extend([
                c + DVec2::new(-h, -h),
                c + DVec2::new(h, -h),
                c + DVec2::new(h, h),
                c + DVec2::new(-h, h),
            ])
        };
        if place.len() >= 3 {
            let (rot, z) = (self.rot, self.z);
            self.points
                .extend(place.iter().map(|&x| land(rot * x, w, z)));
        } else {
            square(land(self.rot * place[0], w, self.z), &mut self.points);
        }
        let mut a = clip2d::area(&self.points[start..]);
        if !(a > 0.0 && a.is_finite()) {
            // A beam landing edge-on (a sliver): its light on a dot.
            let c = self.points[start];
            self.points.truncate(start);
            square(c, &mut self.points);
            a = self.dot * self.dot;
        }
        self.landed.push(Landed {
            poly: (start as u32, self.points.len() as u32),
            density: e.unabsorbed / a,
            kept,
        });
    }
}

impl Trace {
    /// The polygon of a landed exit.
    #[inline]
    fn poly(&self, l: &Landed) -> &[DVec2] {
        &self.points[l.poly.0 as usize..l.poly.1 as usize]
    }
}

/// Rows of the ground's raster one thread fills at a time.
const GROUND_ROWS: usize = 32;

/// Where a ground lies and how it is sampled: its plane at height `z` (world), a raster of
/// `n` × `n` cells over ±`half`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroundPlane {
    /// Height of the plane.
    pub z: f64,
    /// Half-width of the raster.
    pub half: f64,
    /// Cells per side.
    pub n: usize,
}

impl GroundField {
    /// The ground under `stone` (posed by `rot`, stone → world) on `plane`, lit by `lights`
    /// (each traced as it says, with `opts`); `albedo` per band; `luminance` turns per-band
    /// values into luminance Y for the bookkeeping.
    pub fn new(
        stone: &Stone,
        rot: DMat3,
        plane: GroundPlane,
        albedo: &[f64],
        lights: &[Lit],
        luminance: &(dyn Fn(&[f64]) -> f64 + Sync),
        opts: &TraceOptions,
    ) -> GroundField {
        let GroundPlane { z, half, n } = plane;
        let bands = albedo.len();
        let n = n.max(1);
        let cell = 2.0 * half / n as f64;
        let t = rot.transpose();
        let verts: Vec<DVec3> = stone.vertices().iter().map(|&v| rot * v).collect();
        let mut e0 = vec![0.0; bands];
        for l in lights {
            for tr in &l.traces {
                for &(b, e, _) in &tr.bands {
                    e0[b] += e;
                }
            }
        }
        // Per light: its shadow (polygon, per-band irradiance taken) and its traces.
        type Shadow = (Vec<DVec2>, Vec<(usize, f64)>);
        let traced: Vec<(Shadow, Vec<Trace>)> = lights
            .par_iter()
            .map(|l| {
                let w = l.sample.dir;
                let shadow = clip2d::convex_hull(verts.iter().map(|&x| land(x, -w, z)).collect());
                let shade: Vec<(usize, f64)> = l
                    .traces
                    .iter()
                    .flat_map(|tr| tr.bands.iter().map(|&(b, e, _)| (b, e)))
                    .collect();
                let frame = Frame::new(t * -w).unwrap_or_else(Frame::overhead);
                let traces = l
                    .traces
                    .iter()
                    .map(|lt| {
                        let exponents: Vec<f64> = lt.bands.iter().map(|x| x.2).collect();
                        let mut sink = CausticSink {
                            rot,
                            z,
                            dot: 0.5 * cell,
                            exponents: &exponents,
                            landed: Vec::new(),
                            points: Vec::new(),
                            up: vec![0.0; exponents.len()],
                        };
                        let o = TraceOptions {
                            absorption: lt.alpha,
                            footprints: false,
                            ..*opts
                        };
                        let (ts, _) =
                            stone.trace_medium_into(&frame, &lt.medium, &o, &mut sink, false);
                        // Normal irradiance of the parallel beam times its cross-section.
                        let bands = lt
                            .bands
                            .iter()
                            .map(|&(b, e, k)| (b, e / w.z.max(1e-12) * ts.area, k))
                            .collect();
                        Trace {
                            landed: sink.landed,
                            points: sink.points,
                            bands,
                            up: sink.up,
                            stats: ts,
                        }
                    })
                    .collect();
                ((shadow, shade), traces)
            })
            .collect();
        // The rasters, up to eight bands at once (one walk along each polygon's edges adds
        // all of them), in bands of rows filled in parallel: each walks the polygons that
        // reach its rows into an accumulator its thread reuses (a whole raster's accumulator
        // of eight bands is 33 MB of fresh pages at 512 cells; the sums are the same).
        let rows: Vec<(usize, usize)> = (0..n)
            .step_by(GROUND_ROWS)
            .map(|j| (j, (j + GROUND_ROWS).min(n)))
            .collect();
        let fill = |shadows: bool| -> Vec<Vec<f64>> {
            let mut out = vec![vec![0.0; n * n]; bands];
            for b0 in (0..bands).step_by(8) {
                let b1 = (b0 + 8).min(bands);
                let m = b1 - b0;
                let mut outs: Vec<Vec<&mut [f64]>> = rows.iter().map(|_| Vec::new()).collect();
                for r in out[b0..b1].iter_mut() {
                    for (o, part) in outs.iter_mut().zip(r.chunks_mut(GROUND_ROWS * n)) {
                        o.push(part);
                    }
                }
                rows.par_iter().zip(outs).for_each_init(
                    || None::<Accumulator>,
                    |slot, (&(j0, j1), mut part)| {
                        let acc = match slot {
                            Some(acc) => {
                                acc.reset((j0, j1));
                                acc
                            }
                            None => slot.insert(Accumulator::new(n, half, (j0, j1), m)),
                        };
                        let (ylo, yhi) = (-half + j0 as f64 * cell, -half + j1 as f64 * cell);
                        let misses = |poly: &[DVec2]| {
                            poly.iter().all(|p| p.y < ylo) || poly.iter().all(|p| p.y > yhi)
                        };
                        let mut v = [0.0; 8];
                        for ((shadow, shade), traces) in &traced {
                            if shadows {
                                if misses(shadow) {
                                    continue;
                                }
                                v.fill(0.0);
                                for &(b, e) in shade {
                                    if (b0..b1).contains(&b) {
                                        v[b - b0] += e;
                                    }
                                }
                                acc.add_polygon(shadow, &v[..m]);
                                continue;
                            }
                            for tr in traces {
                                if !tr
                                    .bands
                                    .iter()
                                    .any(|x| (b0..b1).contains(&x.0) && x.1 != 0.0)
                                {
                                    continue;
                                }
                                for l in &tr.landed {
                                    let poly = tr.poly(l);
                                    if misses(poly) {
                                        continue;
                                    }
                                    v.fill(0.0);
                                    for &(b, phi, k) in &tr.bands {
                                        if (b0..b1).contains(&b) {
                                            v[b - b0] += l.density * kept_to(l.kept, k) * phi;
                                        }
                                    }
                                    acc.add_polygon(poly, &v[..m]);
                                }
                            }
                        }
                        acc.finish_into(&mut part);
                    },
                );
            }
            out
        };
        let caustic = fill(false);
        let shadow = fill(true);
        // Bookkeeping, per band then as luminance.
        let per = |f: &dyn Fn(&Trace, usize, f64, f64) -> f64| -> f64 {
            let mut v = vec![0.0; bands];
            for (_, traces) in &traced {
                for tr in traces {
                    for (i, &(b, phi, k)) in tr.bands.iter().enumerate() {
                        v[b] += f(tr, i, phi, k);
                    }
                }
            }
            luminance(&v)
        };
        let down_of = |tr: &Trace, k: f64| -> f64 {
            tr.landed
                .iter()
                .map(|l| clip2d::area(tr.poly(l)) * l.density * kept_to(l.kept, k))
                .sum()
        };
        let intercepted = per(&|tr, _, phi, _| phi * tr.stats.power_in);
        let down = per(&|tr, _, phi, k| phi * down_of(tr, k));
        let escaped = per(&|tr, i, phi, _| phi * tr.up[i]);
        let cut_off = per(&|tr, _, phi, _| phi * tr.stats.cut_off);
        let absorbed = per(&|tr, i, phi, k| {
            if k == 1.0 {
                phi * tr.stats.absorbed
            } else {
                // A band sharing another's trace: what its exponent took.
                phi * (tr.stats.power_in - tr.stats.cut_off - tr.up[i] - down_of(tr, k))
            }
        });
        let h2 = cell * cell;
        let inside = luminance(
            &caustic
                .iter()
                .map(|c| c.iter().sum::<f64>() * h2)
                .collect::<Vec<_>>(),
        );
        let mut st = GroundStats {
            directions: lights.len(),
            intercepted,
            caustic: inside,
            caustic_outside: down - inside,
            escaped,
            absorbed,
            cut_off,
            ..GroundStats::default()
        };
        for ((shadow, shade), _) in &traced {
            let mut v = vec![0.0; bands];
            for &(b, e) in shade {
                v[b] += e;
            }
            let e_y = luminance(&v);
            st.shadow_area += clip2d::area(shadow) * e_y;
            st.irradiance += e_y;
        }
        if st.irradiance > 0.0 {
            st.shadow_area /= st.irradiance;
        }
        st.balance = st.intercepted
            - st.caustic
            - st.caustic_outside
            - st.escaped
            - st.absorbed
            - st.cut_off;
        GroundField {
            z,
            half,
            n,
            k: albedo.iter().map(|a| a / std::f64::consts::PI).collect(),
            e0,
            caustic,
            shadow,
            stats: st,
        }
    }

    /// Side of a cell.
    pub fn cell(&self) -> f64 {
        2.0 * self.half / self.n as f64
    }

    /// Irradiance in band `b` of cell (i, j) (beyond the raster: the unshadowed one).
    #[inline]
    pub fn cell_irradiance(&self, b: usize, i: i64, j: i64) -> f64 {
        let n = self.n as i64;
        if i < 0 || j < 0 || i >= n || j >= n {
            return self.e0[b];
        }
        let k = (j * n + i) as usize;
        self.e0[b] - self.shadow[b][k] + self.caustic[b][k]
    }

    /// Radiance in band `b` at ground point `p` (bilinear between cell centres).
    #[inline]
    pub fn radiance(&self, b: usize, p: DVec2) -> f64 {
        let h = self.cell();
        let x = (p.x + self.half) / h - 0.5;
        let y = (p.y + self.half) / h - 0.5;
        let (i, j) = (x.floor(), y.floor());
        let (fx, fy) = (x - i, y - j);
        let (i, j) = (i as i64, j as i64);
        let e = (1.0 - fy)
            * ((1.0 - fx) * self.cell_irradiance(b, i, j) + fx * self.cell_irradiance(b, i + 1, j))
            + fy * ((1.0 - fx) * self.cell_irradiance(b, i, j + 1)
                + fx * self.cell_irradiance(b, i + 1, j + 1));
        (self.k[b] * e).max(0.0)
    }
}
