//! One traced picture layer ([`Layer`]): the beam tracer's exits kept as the picture needs
//! them, and their footprints filled into rasters ([`Layer::fill`]).
//!
//! A face-up stone's trace hands out every exit once per symmetry of the stone (16 copies
//! for a round brilliant). The layer keeps each traced exit's footprint once and, per copy
//! that adds light, only its symmetry, its values and its footprint's box: the copy's
//! footprint is the traced one under the symmetry's 2×2 map, made again when it is drawn
//! (as the trace made it). Copies that add nothing (fire's spots reach few exits) are not
//! kept at all. A 512² fire picture's process peaks at 41 MB this way, 152 MB when it kept the
//! whole [`BeamTree`](crate::beam::BeamTree).

use super::raster::{Accumulator, Raster};
use crate::beam::{ExitBeam, ExitSink, Frame, Medium, Stone, TraceOptions, TraceStats};
use crate::geometry::clip2d;
use glam::DVec2;
use rayon::prelude::*;

/// Rows per band of the parallel fill.
pub(super) const BAND_ROWS: usize = 64;

/// A copy of a traced exit that adds light to the picture.
#[derive(Clone, Copy, Debug)]
struct Drawn {
    /// The traced exit (index into `Layer::ranges`).
    exit: u32,
    /// Its symmetry (index into `Layer::maps`; 0 = the traced exit itself).
    sym: u16,
    /// Smallest and largest y and smallest x of its footprint.
    y_lo: f64,
    y_hi: f64,
    x_lo: f64,
}

/// One traced picture layer: the copies that add light, each with its values per unit of
/// footprint (one per channel), and the trace's statistics.
pub(super) struct Layer {
    /// Channels of the values.
    pub(super) channels: usize,
    /// The trace's power accounting.
    pub(super) stats: TraceStats,
    /// Every exit the trace handed out (all copies).
    pub(super) exits: usize,
    /// Footprints of the traced exits, concatenated, and each one's range.
    foot: Vec<DVec2>,
    ranges: Vec<(u32, u32)>,
    /// The 2×2 footprint map of each symmetry index (identity at 0).
    maps: Vec<[f64; 4]>,
    drawn: Vec<Drawn>,
    /// `channels` values per drawn copy.
    values: Vec<f64>,
}

/// The sink a [`Layer`] is traced into.
struct LayerSink<F: FnMut(&ExitBeam) -> [f64; 5], G: Fn(&ExitBeam) -> bool> {
    value: F,
    orbit: G,
    /// Copies the trace hands out per traced exit.
    copies: usize,
    /// Copies of orbits skipped whole (counted among the exits): a trace asks
    /// `ExitSink::wants_orbit` before handing out each traced exit with its copies.
    skipped: std::cell::Cell<usize>,
    layer: Layer,
}

impl<F: FnMut(&ExitBeam) -> [f64; 5], G: Fn(&ExitBeam) -> bool> ExitSink for LayerSink<F, G> {
    fn wants_footprints(&self) -> bool {
        true
    }
    fn wants_orbit(&self, e: &ExitBeam) -> bool {
        let wanted = (self.orbit)(e);
        if !wanted {
            self.skipped.set(self.skipped.get() + self.copies);
        }
        wanted
    }
    fn symmetries(&mut self, maps: &[(u16, [f64; 4])]) {
        self.copies = maps.len();
        self.layer.set_symmetries(maps);
    }
    fn exit(&mut self, e: &ExitBeam, fp: &[DVec2]) {
        let c = (self.value)(e);
        self.layer.record(e, fp, &c);
    }
}

impl Layer {
    /// An empty layer of `channels` values per footprint, for a sink of its own that
    /// [`Layer::record`]s exits and [`Layer::add_polygon`]s, then [`Layer::finish`]es.
    pub(super) fn new(channels: usize) -> Layer {
        Layer {
            channels: channels.clamp(1, 5),
            stats: TraceStats::default(),
            exits: 0,
            foot: Vec::new(),
            ranges: Vec::new(),
            maps: vec![[1.0, 0.0, 0.0, 1.0]],
            drawn: Vec::new(),
            values: Vec::new(),
        }
    }

    /// The symmetries' footprint maps a trace hands its copies out under
    /// ([`ExitSink::symmetries`]), for [`Layer::record`] to draw copies from their traced
    /// footprint.
    pub(super) fn set_symmetries(&mut self, maps: &[(u16, [f64; 4])]) {
        let n = maps.iter().map(|&(i, _)| i as usize + 1).max().unwrap_or(1);
        let mut m = vec![[1.0, 0.0, 0.0, 1.0]; n];
        for &(i, map) in maps {
            m[i as usize] = map;
        }
        self.maps = m;
    }

    /// Keep exit `e` with its footprint `fp` and its values per unit of its power `c` (the
    /// first `channels` are used). A copy (`e.sym` ≠ 0) needs the symmetries' maps
    /// ([`ExitSink::symmetries`] of the layer's own sink).
    pub(super) fn record(&mut self, e: &ExitBeam, fp: &[DVec2], c: &[f64]) {
        self.exits += 1;
        if e.sym == 0 {
            let a = self.foot.len() as u32;
            self.foot.extend_from_slice(fp);
            self.ranges.push((a, self.foot.len() as u32));
        }
        let c = &c[..self.channels.min(c.len())];
        // (Written so that a NaN power or area draws nothing.)
        let drawable = e.power > 0.0 && c.iter().any(|&x| x != 0.0);
        if !drawable {
            return;
        }
        let a = clip2d::area(fp);
        if a.is_nan() || a <= 0.0 {
            return;
        }
        // Radiance through this beam: its power per unit of footprint (relative to the
        // incoming power per unit of cross-section once multiplied by the cross-section,
        // which the trace gives at its end).
        self.push(e.sym, fp, e.power / a, c);
    }

    /// Add the polygon `poly` (image coordinates) with `values` per unit area as they stand
    /// before [`Layer::finish`] multiplies them by the cross-section (a beam's power per unit
    /// of its footprint times the radiance it carries).
    pub(super) fn add_polygon(&mut self, poly: &[DVec2], values: &[f64]) {
        if poly.len() < 3 || !values.iter().any(|&v| v != 0.0 && v.is_finite()) {
            return;
        }
        let a = self.foot.len() as u32;
        self.foot.extend_from_slice(poly);
        self.ranges.push((a, self.foot.len() as u32));
        let c = &values[..self.channels.min(values.len())];
        self.push(0, poly, 1.0, c);
    }

    /// The drawn copy of the last footprint kept (under symmetry `sym`), values `c · k`.
    fn push(&mut self, sym: u16, fp: &[DVec2], k: f64, c: &[f64]) {
        let (mut y_lo, mut y_hi, mut x_lo) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
        for p in fp {
            y_lo = y_lo.min(p.y);
            y_hi = y_hi.max(p.y);
            x_lo = x_lo.min(p.x);
        }
        self.drawn.push(Drawn {
            exit: self.ranges.len() as u32 - 1,
            sym,
            y_lo,
            y_hi,
            x_lo,
        });
        let n = self.channels;
        self.values
            .extend((0..n).map(|i| c.get(i).copied().unwrap_or(0.0) * k));
    }

    /// Scale the kept values by the trace's cross-section and keep its statistics: the layer
    /// is then ready to [`Layer::fill`].
    pub(super) fn finish(&mut self, stats: TraceStats) {
        let area = stats.area;
        self.values.iter_mut().for_each(|v| *v *= area);
        self.stats = stats;
    }

    /// Trace `stone` along `frame` through `medium` and keep, for each exit (every copy),
    /// `value(exit)`'s first `channels` values: the radiance the exit carries per unit of
    /// its power. `value` sees every exit for which `orbit` holds, so it may also sum what
    /// the caller measures; `orbit(exit)` false says that neither the exit nor its symmetric
    /// copies add anything (decided from what the copies share: power, and the direction's
    /// component along the viewer's axis), so they are skipped whole.
    pub(super) fn trace(
        stone: &Stone,
        frame: &Frame,
        medium: &Medium,
        opts: &TraceOptions,
        channels: usize,
        value: impl FnMut(&ExitBeam) -> [f64; 5],
        orbit: impl Fn(&ExitBeam) -> bool,
    ) -> Layer {
        let mut sink = LayerSink {
            value,
            orbit,
            copies: 1,
            skipped: std::cell::Cell::new(0),
            layer: Layer::new(channels),
        };
        let opts = TraceOptions {
            footprints: true,
            ..*opts
        };
        let (stats, _) = stone.trace_medium_into(frame, medium, &opts, &mut sink, false);
        let mut layer = sink.layer;
        layer.exits += sink.skipped.get();
        layer.finish(stats);
        layer
    }

    /// Fill `channels` images of `size` pixels over `[−half, half]²` from the layers (each
    /// layer's values added to the same images), in bands of rows in parallel; each pixel
    /// receives its footprints in the layers' order, so the result does not depend on the
    /// number of threads.
    ///
    /// With `quadrant` (a picture that is its own mirror image across both image axes, see
    /// `mirrored` in the drawing) only the bottom-left quadrant's pixels are drawn, from the
    /// footprints that reach it (a pixel's running sums take only edges to its left), and the
    /// rest mirrored.
    pub(super) fn fill(
        layers: &[&Layer],
        channels: usize,
        size: usize,
        half: f64,
        quadrant: bool,
    ) -> Vec<Raster> {
        let proto = Raster::new(size, half);
        let h = proto.pixel();
        // Rows and columns drawn: all, or the first half (with the middle one when odd).
        let m = if quadrant { size.div_ceil(2) } else { size };
        let x_m = -half + m as f64 * h;
        let bands: Vec<(usize, usize)> = (0..m)
            .step_by(BAND_ROWS)
            .map(|j| (j, (j + BAND_ROWS).min(m)))
            .collect();
        let mut rasters: Vec<Raster> = (0..channels).map(|_| Raster::new(size, half)).collect();
        // Per row band, its rows of every channel's picture: each band is drawn straight
        // into them, with an accumulator reused from band to band on a thread.
        let mut outs: Vec<Vec<&mut [f64]>> = bands.iter().map(|_| Vec::new()).collect();
        for r in rasters.iter_mut() {
            for (o, rows) in outs.iter_mut().zip(r.data.chunks_mut(BAND_ROWS * size)) {
                o.push(rows);
            }
        }
        bands.par_iter().zip(outs).for_each_init(
            || None::<Accumulator>,
            |slot, (&(j0, j1), mut out)| {
                let (ylo, yhi) = (-half + j0 as f64 * h, -half + j1 as f64 * h);
                let acc = match slot {
                    Some(acc) => {
                        acc.reset((j0, j1));
                        acc
                    }
                    None => slot.insert(Accumulator::new(size, half, (j0, j1), channels)),
                };
                let mut fp = Vec::new();
                for layer in layers {
                    let c = layer.channels;
                    for (d, v) in layer.drawn.iter().zip(layer.values.chunks_exact(c)) {
                        if d.y_hi < ylo || d.y_lo > yhi || (quadrant && d.x_lo >= x_m) {
                            continue;
                        }
                        let (a, b) = layer.ranges[d.exit as usize];
                        let traced = &layer.foot[a as usize..b as usize];
                        if d.sym == 0 {
                            acc.add_polygon(traced, &v[..c.min(channels)]);
                        } else {
                            let m2 = layer.maps[d.sym as usize];
                            fp.clear();
                            fp.extend(traced.iter().map(|p| {
                                DVec2::new(m2[0] * p.x + m2[1] * p.y, m2[2] * p.x + m2[3] * p.y)
                            }));
                            acc.add_polygon(&fp, &v[..c.min(channels)]);
                        }
                    }
                }
                acc.finish_into(&mut out);
            },
        );
        rasters
            .into_iter()
            .map(|mut r| {
                if quadrant {
                    for j in 0..m {
                        let row = &mut r.data[j * size..(j + 1) * size];
                        for i in m..size {
                            row[i] = row[size - 1 - i];
                        }
                    }
                    for j in m..size {
                        r.data
                            .copy_within((size - 1 - j) * size..(size - j) * size, j * size);
                    }
                }
                r
            })
            .collect()
    }
}
