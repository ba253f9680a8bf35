//! The photograph's pipeline ([`photo`]): the camera's sight lines traced backwards by the
//! beam tracer (one orthographic trace, or perspective tiles), band by band; every exit
//! beam shaded by the environment in its direction or, leaving downward onto a ground, by
//! the ground's radiance over the exact polygon it lands on; the background seen past the
//! stone; all summed in CIE XYZ.

use super::camera::{Camera, Projection, Tile};
use super::env::{luminance, Environment, Rgb};
use super::ground::{land, GroundField, GroundKind, GroundPlane, Lit, LitTrace};
use super::options::PhotoOptions;
use super::{Photo, PhotoStats};
use crate::beam::{ExitBeam, ExitSink, Frame, Medium, Stone, TraceOptions};
use crate::geometry::canonical::{azimuth_turn, canonical};
use crate::geometry::{clip2d, outline_size, Polyhedron};
use crate::optics::color;
use crate::optics::upsample::{rgb_at, rgb_weights};
use crate::optics::Dispersion;
use crate::render::layer::{Layer, BAND_ROWS};
use crate::render::pose::picture_half;
use crate::render::raster::{Accumulator, Raster};
use glam::{DMat2, DMat3, DVec2, DVec3};
use rayon::prelude::*;

/// One band of the picture: its XYZ weight, its weights of linear sRGB's primaries
/// ([`rgb_weights`]), the stone's optics in it (a birefringent stone's two indices, optic
/// axis and absorption per mode) and its absorption per unit length (a birefringent stone's:
/// the mean of its two modes', standing for both where a trace serves several bands).
#[derive(Clone, Copy, Debug)]
pub(super) struct Band {
    pub xyz: DVec3,
    pub rgb: [f64; 3],
    pub medium: Medium,
    pub alpha: f64,
}

/// The bands of a picture of `opts`, and whether they are spectral. A stone whose index and
/// colour do not change with wavelength is traced once, in three pseudo-bands that carry
/// linear sRGB's red, green and blue (their XYZ weights being what the spectral bands would
/// give them, so the two ways give the same colours); any other in fire's bands (faint ones
/// merged into a neighbour, as fire pictures do). Under `grey` light (every radiance grey,
/// and every ground is) the three pseudo-bands are one.
pub(super) fn bands(
    opts: &PhotoOptions,
    axis: DVec3,
    mm_per_unit: f64,
    grey: bool,
) -> (Vec<Band>, bool) {
    let m = &opts.material;
    let body = m.colour.as_ref();
    // The medium of band `l`, and its absorption per unit length (per mode for a crystal,
    // which the medium carries; their mean stands for both in a shared trace's exponents).
    let optics = |l: f64| {
        let medium = Medium::of(m, l, axis, mm_per_unit, body.is_some());
        let alpha = match medium {
            Medium::Isotropic(_) => body.map_or(0.0, |c| c.alpha(l) * mm_per_unit),
            Medium::Uniaxial {
                alpha_o, alpha_e, ..
            } => 0.5 * (alpha_o + alpha_e),
        };
        (medium, alpha)
    };
    let spectral_bands = color::traced_bands(opts.bands.max(1), color::FAINT_BAND);
    let constant_e = m
        .uniaxial
        .as_ref()
        .is_none_or(|u| !m.birefringent() || matches!(u.extraordinary, Dispersion::Constant(_)));
    let constant = matches!(m.dispersion, Dispersion::Constant(_)) && constant_e && body.is_none();
    if constant {
        let mut cols = [DVec3::ZERO; 3];
        for (l, w) in &spectral_bands {
            let b = rgb_weights(*l);
            for c in 0..3 {
                cols[c] += *w * b[c];
            }
        }
        let medium = optics(589.3).0;
        if grey {
            // Grey light on a grey ground: one channel (red, equal to the others) with the
            // white's XYZ weight.
            let band = Band {
                xyz: cols[0] + cols[1] + cols[2],
                rgb: [1.0, 0.0, 0.0],
                medium,
                alpha: 0.0,
            };
            return (vec![band], false);
        }
        let unit = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let v = (0..3)
            .map(|c| Band {
                xyz: cols[c],
                rgb: unit[c],
                medium,
                alpha: 0.0,
            })
            .collect();
        (v, false)
    } else {
        let v = spectral_bands
            .iter()
            .map(|&(l, w)| {
                let (medium, alpha) = optics(l);
                Band {
                    xyz: w,
                    rgb: rgb_weights(l),
                    medium,
                    alpha,
                }
            })
            .collect();
        (v, true)
    }
}

/// The sink of one trace of the picture (one band group, one tile): every exit's footprint
/// (in image coordinates) with its radiance, into a layer of one value per band traced.
struct PhotoSink<'a> {
    layer: Layer,
    rot: DMat3,
    env: &'a Environment,
    /// The bands this trace draws (indices into `bands`).
    which: &'a [usize],
    bands: &'a [Band],
    ground: Option<&'a GroundField>,
    tile: Option<&'a Tile>,
    /// Side of the picture's pixel in image coordinates.
    pixel: f64,
    fp: Vec<DVec2>,
    values: Vec<f64>,
    /// The ground seen through the stone.
    seen: Seen<'a>,
}

impl PhotoSink<'_> {
    /// Values of the environment seen along `w` in the bands drawn.
    fn env_values(&mut self, w: DVec3) {
        let c = self.env.radiance(w);
        self.values.clear();
        for &b in self.which {
            self.values.push(rgb_at(c, self.bands[b].rgb));
        }
    }

    /// Values of the ground in the bands drawn at ground point `p`.
    fn ground_values(&mut self, g: &GroundField, p: DVec2) {
        self.values.clear();
        for &b in self.which {
            self.values.push(g.radiance(b, p));
        }
    }

    /// A sight-line beam of footprint `fp` (image coordinates) that lands on the ground over
    /// `landed`, of radiance `k` per unit of ground radiance: its exact coverage of each
    /// pixel times the ground's radiance seen there, kept in `seen` (see [`Seen`]).
    fn ground_exit(&mut self, g: &GroundField, landed: &[DVec2], fp: &[DVec2], k: f64) {
        let mut cov = std::mem::take(&mut self.seen.cov);
        self.seen.proto.coverage_into(fp, &mut cov);
        let h = self.pixel;
        let nc = self.which.len();
        // The image → ground map of the beam (affine: one exit facet, one direction).
        let map = if landed.len() == fp.len() && landed.len() >= 3 && cov.cells.len() > 1 {
            affine(fp, landed)
        } else {
            None
        };
        match map {
            None => {
                // A beam within a pixel (or degenerate): the ground at its landed centroid.
                let c = clip2d::centroid(landed).unwrap_or(landed[0]);
                self.ground_values(g, c);
                for &(px, a) in &cov.cells {
                    self.seen.pixels.push(px as u32);
                    let s = k * a / (h * h);
                    self.seen.values.extend(self.values.iter().map(|v| v * s));
                }
            }
            Some((m, t)) => {
                // Samples per side of a pixel: enough that each spans at most about a
                // ground cell (a pixel that sees much of the ground averages it), 4 at most.
                let ext = h * m.x_axis.length().max(m.y_axis.length());
                let s = ((ext / g.cell()).ceil() as usize).clamp(1, 4);
                let (mut lo, mut hi) =
                    (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
                for p in fp {
                    lo = lo.min(*p);
                    hi = hi.max(*p);
                }
                let n = self.seen.proto.n;
                let half = self.seen.proto.half;
                let mut sum = [0.0; 3];
                for &(px, a) in &cov.cells {
                    let (i, j) = (px % n, px / n);
                    let p0 = DVec2::new(-half + i as f64 * h, -half + j as f64 * h);
                    // The part of the pixel within the footprint's box, sampled on an
                    // s × s grid (its centre when s = 1).
                    let (b0, b1) = (p0.max(lo), (p0 + DVec2::splat(h)).min(hi));
                    let d = (b1 - b0).max(DVec2::ZERO) / s as f64;
                    sum[..nc].fill(0.0);
                    for u in 0..s {
                        for v in 0..s {
                            let q = b0 + DVec2::new((u as f64 + 0.5) * d.x, (v as f64 + 0.5) * d.y);
                            let at = m * q + t;
                            for (c, &b) in self.which.iter().enumerate() {
                                sum[c] += g.radiance(b, at);
                            }
                        }
                    }
                    self.seen.pixels.push(px as u32);
                    let w = k * a / (h * h * (s * s) as f64);
                    self.seen.values.extend(sum[..nc].iter().map(|v| v * w));
                }
            }
        }
        self.seen.cov = cov;
    }
}

/// The ground seen through the stone by one trace: per pixel a beam covers, its values (one
/// per band drawn, before the trace's cross-section scales them, as a [`Layer`]'s are), in
/// the order the beams came; added to the filled picture after its layers. Each beam's
/// coverage of the pixels is exact ([`Raster::coverage_into`]); the ground's (bilinear)
/// radiance is sampled at the part of each pixel within the beam's box: at its centre, or on
/// a grid of up to 4 × 4 where a pixel sees more than a ground cell.
struct Seen<'a> {
    /// An image of the picture's size (for its geometry only).
    proto: &'a Raster,
    cov: crate::render::raster::Coverage,
    pixels: Vec<u32>,
    values: Vec<f64>,
}

impl ExitSink for PhotoSink<'_> {
    fn wants_footprints(&self) -> bool {
        true
    }
    fn symmetries(&mut self, maps: &[(u16, [f64; 4])]) {
        self.layer.set_symmetries(maps);
    }
    fn wants_exit_places(&self) -> bool {
        self.ground.is_some()
    }
    fn exit(&mut self, e: &ExitBeam, fp: &[DVec2]) {
        self.exit_at(e, fp, &[]);
    }
    fn exit_at(&mut self, e: &ExitBeam, fp: &[DVec2], place: &[DVec3]) {
        let w = self.rot * e.direction;
        // The beam's radiance per unit of the light it started with: its power per unit of
        // its footprint (in the traced frame's coordinates), before the layer's scaling by
        // the cross-section.
        let a_src = clip2d::area(fp);
        if a_src.is_nan() || e.power.is_nan() || a_src <= 0.0 || e.power <= 0.0 {
            self.layer.exits += 1;
            return;
        }
        let k = e.power / a_src;
        // Orthographic with the environment all round: the layer keeps a symmetric trace's
        // copies as maps of the traced footprint.
        if self.tile.is_none() && self.ground.is_none() {
            self.env_values(w);
            let v = std::mem::take(&mut self.values);
            self.layer.record(e, fp, &v);
            self.values = v;
            return;
        }
        self.fp.clear();
        match self.tile {
            Some(t) => self.fp.extend(fp.iter().map(|&p| t.image(p))),
            None => self.fp.extend_from_slice(fp),
        }
        let fp = std::mem::take(&mut self.fp);
        self.layer.exits += 1;
        match self.ground {
            Some(g) if w.z < 0.0 && !place.is_empty() => {
                let landed: Vec<DVec2> =
                    place.iter().map(|&x| land(self.rot * x, w, g.z)).collect();
                self.ground_exit(g, &landed, &fp, k);
            }
            _ => {
                self.env_values(w);
                let v: Vec<f64> = self.values.iter().map(|x| x * k).collect();
                self.layer.add_polygon(&fp, &v);
            }
        }
        self.fp = fp;
    }
}

/// The affine map `p ↦ m p + t` taking polygon `from`'s vertices to `to`'s (from its first
/// vertex and the two that span the largest triangle with it); `None` when degenerate.
fn affine(from: &[DVec2], to: &[DVec2]) -> Option<(DMat2, DVec2)> {
    let n = from.len();
    let (mut best, mut bi, mut bj) = (0.0, 1, 2);
    for i in 1..n {
        for j in i + 1..n {
            let a = clip2d::cross(from[i] - from[0], from[j] - from[0]).abs();
            if a > best {
                (best, bi, bj) = (a, i, j);
            }
        }
    }
    let g = DMat2::from_cols(from[bi] - from[0], from[bj] - from[0]);
    let det = g.determinant();
    let scale = (from[bi] - from[0]).length_squared() + (from[bj] - from[0]).length_squared();
    if !(det.abs() > 1e-12 * scale && det.is_finite()) {
        return None;
    }
    let f = DMat2::from_cols(to[bi] - to[0], to[bj] - to[0]);
    let m = f * g.inverse();
    let t = to[0] - m * from[0];
    Some((m, t))
}

/// The outline's coverage of each pixel: facets facing the sight lines, each tile's through
/// its window.
fn coverage(solid: &Polyhedron, cam: &Camera, tiles: &[Tile]) -> Raster {
    if tiles.is_empty() {
        return crate::render::outline_coverage(solid, &cam.frame(), cam.size, cam.half);
    }
    let n = cam.size;
    let mut cov = Raster::new(n, cam.half);
    let mut acc = Accumulator::new(n, cam.half, (0, n), 1);
    for t in tiles {
        for f in 0..solid.facets().len() {
            if solid.facets()[f].plane.normal.dot(t.frame.dir) >= 0.0 {
                continue;
            }
            let poly: Vec<DVec2> = solid
                .facet_polygon(f)
                .iter()
                .map(|p| DVec2::new(p.dot(t.frame.u), p.dot(t.frame.v)))
                .collect();
            let inside = clip2d::clip_convex(&poly, &t.quad);
            if inside.len() >= 3 {
                let img: Vec<DVec2> = inside.iter().map(|&p| t.image(p)).collect();
                acc.add_polygon(&img, &[1.0]);
            }
        }
    }
    cov.data = acc.finish().swap_remove(0);
    cov
}

/// Take `opts` as a photograph of `solid`. The solid is first put in its canonical placement
/// (centred, unit size, turned to its canonical azimuth and posed turned back, so that a
/// moved or rescaled copy gives the same photograph and the stone faces the camera as its
/// file draws it), then posed by `opts.tilt` and set on the ground (its
/// lowest point `opts.ground.gap` above it). Options should have passed
/// [`PhotoOptions::validate`]; out-of-range values never panic.
pub fn photo(solid: &Polyhedron, opts: &PhotoOptions) -> Photo {
    // A birefringent stone's optic axis, carried into the canonical placement with it.
    let axis = crate::render::pose::canonical_optic_axis(solid, &opts.material);
    // The canonical solid is the stone turned by `turn` about z (its canonical azimuth):
    // posing it turned back first photographs the stone as its file and its diagram draw it,
    // as `render` does (and its optic axis with it).
    let turn = azimuth_turn(solid);
    let solid = canonical(solid);
    let stone = Stone::new(&solid);
    let rot = opts.tilt.rotation() * DMat3::from_rotation_z(-turn);
    let size = opts.size.max(1);
    let half = picture_half(&solid) * opts.margin;
    let width = outline_size(solid.vertices()).1;
    let mm_per_unit = opts.width_mm / width.max(1e-300);
    // The turntable turns the stone under the camera and lights: the same as turning the
    // camera and lights the other way round the stone.
    let mut view = opts.view;
    view.azimuth_deg -= opts.turn_deg;
    let (dir, right, up) = view.axes();
    let projection = match opts.distance_mm {
        Some(d) => Projection::Perspective {
            distance: d / mm_per_unit,
            tile: opts.tile,
        },
        None => Projection::Orthographic,
    };
    let cam = Camera {
        dir,
        right,
        up,
        rot,
        half,
        size,
        projection,
    };
    let env = opts
        .light
        .environment(
            dir,
            view.world_azimuth_deg(),
            opts.light_rotation_deg - opts.turn_deg,
        )
        .with_aperture(opts.aperture_deg());
    let (bands, spectral) = bands(opts, axis, mm_per_unit, env.is_grey());
    let nb = bands.len();
    let luminance_of = |v: &[f64]| -> f64 { v.iter().zip(&bands).map(|(x, b)| x * b.xyz.y).sum() };

    // The ground: its plane under the posed stone's lowest point, its light.
    let ground = (opts.ground.kind != GroundKind::None).then(|| {
        let lowest = stone
            .vertices()
            .iter()
            .map(|&v| (rot * v).z)
            .fold(f64::INFINITY, f64::min);
        let z = lowest - opts.ground.gap;
        let albedo: Vec<f64> = bands
            .iter()
            .map(|b| rgb_at(opts.ground.kind.albedo(), b.rgb))
            .collect();
        let samples = env.samples(opts.ground_cells);
        // Round lights are traced in every band (their caustics show fire); a cell of the
        // diffuse light once, at the middle band's index, standing for every band (its
        // caustic is too spread to show fire; a coloured stone's bands share its absorption
        // by their exponents).
        let alpha_max = bands.iter().map(|b| b.alpha).fold(0.0, f64::max);
        let mid = &bands[nb / 2];
        // The shared trace absorbs as the most absorbing band does, each band scaled from it
        // by its exponent: a crystal's per-mode absorption taken from that band too (exact
        // when its two modes' absorptions keep their ratio across the bands).
        let mid_medium = match (
            mid.medium,
            bands.iter().max_by(|a, b| a.alpha.total_cmp(&b.alpha)),
        ) {
            (
                Medium::Uniaxial { crystal, .. },
                Some(Band {
                    medium:
                        Medium::Uniaxial {
                            alpha_o, alpha_e, ..
                        },
                    ..
                }),
            ) => Medium::Uniaxial {
                crystal,
                alpha_o: *alpha_o,
                alpha_e: *alpha_e,
            },
            (m, _) => m,
        };
        let lights: Vec<Lit> = samples
            .iter()
            .map(|s| {
                let e = |b: &Band| rgb_at(s.irradiance, b.rgb);
                let traces = if spectral && s.point {
                    bands
                        .iter()
                        .enumerate()
                        .map(|(i, b)| LitTrace {
                            medium: b.medium,
                            alpha: b.alpha,
                            bands: vec![(i, e(b), 1.0)],
                        })
                        .collect()
                } else {
                    vec![LitTrace {
                        medium: mid_medium,
                        alpha: alpha_max,
                        bands: bands
                            .iter()
                            .enumerate()
                            .map(|(i, b)| {
                                let k = if alpha_max > 0.0 {
                                    b.alpha / alpha_max
                                } else {
                                    0.0
                                };
                                (i, e(b), k)
                            })
                            .collect(),
                    }]
                };
                Lit { sample: *s, traces }
            })
            .collect();
        // The raster: around the stone, out to where a camera above sees, cells about two
        // of the picture's pixels.
        let reach = (half / view.elevation_deg.to_radians().sin().abs().max(0.4)).max(2.0 * half);
        let n = ((0.5 * size as f64 * reach / half) as usize).clamp(64, 512);
        let gt = TraceOptions {
            polarization: opts.polarization,
            ..opts.ground_trace
        };
        GroundField::new(
            &stone,
            rot,
            GroundPlane { z, half: reach, n },
            &albedo,
            &lights,
            &luminance_of,
            &gt,
        )
    });

    // The picture's traces: per band group (spectral: one band each; otherwise one trace of
    // three channels), per tile.
    let tiles = cam.tiles();
    let groups: Vec<Vec<usize>> = if spectral {
        (0..nb).map(|b| vec![b]).collect()
    } else {
        vec![(0..nb).collect()]
    };
    let trace_opts = opts.trace_options();
    let frame0 = cam.frame();
    // Each group traced (its tiles in parallel) and filled at once, its layers dropped
    // before the next ones are made: a layer keeps every exit's footprint.
    let proto = Raster::new(size, half);
    let trace_unit = |which: &[usize], tile: Option<&Tile>| -> (Layer, Vec<u32>, Vec<f64>) {
        let b0 = &bands[which[0]];
        let mut sink = PhotoSink {
            layer: Layer::new(which.len()),
            rot,
            env: &env,
            which,
            bands: &bands,
            ground: ground.as_ref(),
            tile,
            pixel: 2.0 * half / size as f64,
            fp: Vec::new(),
            values: Vec::new(),
            seen: Seen {
                proto: &proto,
                cov: Default::default(),
                pixels: Vec::new(),
                values: Vec::new(),
            },
        };
        let o = TraceOptions {
            absorption: b0.alpha,
            ..trace_opts
        };
        let frame: Frame = tile.map_or(frame0, |t| t.frame);
        let window = tile.map_or(&[][..], |t| &t.window[..]);
        let (st, _) =
            stone.trace_medium_window_into(&frame, &b0.medium, &o, window, &mut sink, false);
        let mut layer = sink.layer;
        let Seen {
            pixels, mut values, ..
        } = sink.seen;
        values.iter_mut().for_each(|v| *v *= st.area);
        layer.finish(st);
        (layer, pixels, values)
    };
    let filled: Vec<(Vec<Raster>, f64, usize, usize)> = groups
        .par_iter()
        .map(|which| {
            let units: Vec<(Layer, Vec<u32>, Vec<f64>)> = if tiles.is_empty() {
                vec![trace_unit(which, None)]
            } else {
                tiles
                    .par_iter()
                    .map(|t| trace_unit(which, Some(t)))
                    .collect()
            };
            let cut: f64 = units.iter().map(|l| l.0.stats.cut_off).sum();
            let exits: usize = units.iter().map(|l| l.0.exits).sum();
            let refs: Vec<&Layer> = units.iter().map(|u| &u.0).collect();
            let mut r = Layer::fill(&refs, which.len(), size, half, false);
            // The ground seen through the stone, unit by unit in order.
            let nc = which.len();
            for (_, pixels, values) in &units {
                for (&px, v) in pixels.iter().zip(values.chunks_exact(nc)) {
                    for (raster, x) in r.iter_mut().zip(v) {
                        raster.data[px as usize] += x;
                    }
                }
            }
            (r, cut, exits, units.len())
        })
        .collect();
    let mut stats = PhotoStats {
        size,
        light: env.name.clone(),
        ..PhotoStats::default()
    };
    let mut band_rasters: Vec<Raster> = Vec::with_capacity(nb);
    for (r, cut, exits, traces) in filled {
        stats.cut_off = stats.cut_off.max(cut);
        stats.exits += exits;
        stats.traces += traces;
        band_rasters.extend(r);
    }
    let cov = coverage(&solid, &cam, &tiles);
    // The stone's light in XYZ, then the background through the rest of each pixel.
    let h = 2.0 * half / size as f64;
    let mut xyz: Vec<Raster> = (0..3).map(|_| Raster::new(size, half)).collect();
    let mut stone_y = Raster::new(size, half);
    let uniform_bg: Option<Rgb> = match (&ground, cam.projection) {
        (None, Projection::Orthographic) => Some(env.radiance(cam.dir)),
        _ => None,
    };
    let rows: Vec<(Vec<DVec3>, Vec<f64>)> = (0..size)
        .into_par_iter()
        .map(|j| {
            let mut row = vec![DVec3::ZERO; size];
            let mut ys = vec![0.0; size];
            let y = -half + (j as f64 + 0.5) * h;
            for i in 0..size {
                let k = j * size + i;
                let mut s = DVec3::ZERO;
                for (b, band) in bands.iter().enumerate() {
                    s += band.xyz * band_rasters[b].data[k];
                }
                ys[i] = s.y;
                let c = cov.data[k].clamp(0.0, 1.0);
                if c < 1.0 {
                    let x = -half + (i as f64 + 0.5) * h;
                    let bg = background(
                        &cam,
                        &env,
                        ground.as_ref(),
                        &bands,
                        uniform_bg,
                        DVec2::new(x, y),
                    );
                    s += bg * (1.0 - c);
                }
                row[i] = s;
            }
            (row, ys)
        })
        .collect();
    for (j, (row, ys)) in rows.into_iter().enumerate() {
        for (i, (v, y)) in row.into_iter().zip(ys).enumerate() {
            let k = j * size + i;
            xyz[0].data[k] = v.x;
            xyz[1].data[k] = v.y;
            xyz[2].data[k] = v.z;
            stone_y.data[k] = y;
        }
    }
    let outline = cov.integral();
    stats.mean = if outline > 0.0 {
        stone_y.integral() / outline
    } else {
        0.0
    };
    stats.spectral = spectral;
    stats.bands = if spectral { nb } else { 0 };
    stats.ground = ground.as_ref().map(|g| g.stats);
    let _ = (luminance, BAND_ROWS);
    let [x, y, z]: [Raster; 3] = xyz
        .try_into()
        .unwrap_or_else(|_| unreachable!("three channels"));
    Photo {
        xyz: [x, y, z],
        stone: stone_y,
        coverage: cov,
        stats,
    }
}

/// XYZ of what the sight line through image point `p` sees past the stone: the ground, or
/// the environment.
fn background(
    cam: &Camera,
    env: &Environment,
    ground: Option<&GroundField>,
    bands: &[Band],
    uniform: Option<Rgb>,
    p: DVec2,
) -> DVec3 {
    let (o, d) = cam.ray(p);
    if let Some(g) = ground {
        if d.z < -1e-9 {
            let at = land(o, d, g.z);
            let mut s = DVec3::ZERO;
            for (b, band) in bands.iter().enumerate() {
                s += band.xyz * g.radiance(b, at);
            }
            return s;
        }
    }
    let c = uniform.unwrap_or_else(|| env.radiance(d));
    let mut s = DVec3::ZERO;
    for band in bands {
        s += band.xyz * rgb_at(c, band.rgb);
    }
    s
}
