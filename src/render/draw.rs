//! The footprint → pixel path: trace the viewer backwards, weight each exit beam by the light
//! it sees, and add its footprint's exact coverage to the pixels ([`render`]).

use super::image::{
    fire_from_sum, pixel_xyz, saturated_y, AsetShares, ColourStats, Image, Stats, COLOUR_GRID,
};
use super::layer::{Layer, BAND_ROWS};
use super::light::Light;
use super::lighting::Lighting;
use super::options::RenderOptions;
use super::pose::{picture_half, view_rotation};
use super::raster::{Accumulator, Raster};
use crate::beam::{ExitBeam, Frame, Medium, Stone, TraceOptions};
use crate::geometry::canonical::{azimuth_turn, canonical};
use crate::geometry::{outline_size, Polyhedron};
use crate::optics::{color, Dispersion};
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// Whether the picture of `solid` (canonical: centred on the picture) seen along `frame`
/// under `light` is its own mirror image across both image axes: a light that depends on the
/// elevation alone (every light but fire's spots) and a solid that each axis' mirror maps onto
/// itself (every facet plane onto a facet plane, to 1e-9), and a birefringent stone's optic
/// axis `axis` (stone coordinates; `None` for a singly refractive stone) along or across each
/// mirror (else the mirror image is another crystal). Such a picture's exits come in
/// mirrored pairs, footprints and values both.
fn mirrored(solid: &Polyhedron, frame: &Frame, light: Light, axis: Option<DVec3>) -> bool {
    if light == Light::Fire {
        return false;
    }
    let planes = solid.facet_planes();
    [frame.u, frame.v].iter().all(|&a| {
        let kept = axis.is_none_or(|c| {
            let d = c.normalize().dot(a).abs();
            !(1e-9..=1.0 - 1e-9).contains(&d)
        });
        kept && {
            planes.iter().all(|p| {
                let n = p.plane.normal;
                let m = n - 2.0 * n.dot(a) * a;
                planes.iter().any(|q| {
                    q.plane.normal.distance_squared(m) < 1e-18
                        && (q.plane.offset - p.plane.offset).abs() < 1e-9
                })
            })
        }
    })
}

/// Draw `solid` as `opts` says. The solid is traced in its canonical placement
/// ([`canonical`]: centred, unit size, turned about its axis to the canonical azimuth, the
/// very solid the scores trace), and seen turned back by that azimuth: a moved or rescaled
/// copy gives the same picture, and the picture shows the stone as its file and its diagram
/// draw it (a design's long axis where the design puts it, not where the canonical azimuth
/// would), the lights and the viewer where the options put them. The picture spans
/// [`picture_half`] around the centroid. Options should have passed
/// [`RenderOptions::validate`]; out-of-range values never panic.
pub fn render(solid: &Polyhedron, opts: &RenderOptions) -> Image {
    // A birefringent stone's optic axis, carried into the canonical placement with it.
    let axis = crate::render::pose::canonical_optic_axis(solid, &opts.material);
    let turn = azimuth_turn(solid);
    let solid = canonical(solid);
    let stone = Stone::new(&solid);
    // The canonical solid is the stone turned by `turn` about z: posing it turned back first
    // puts the stone itself in the pose the options ask for.
    let rot = view_rotation(opts.light, opts.tilt) * glam::DMat3::from_rotation_z(-turn);
    let frame = Frame::viewer(rot);
    let size = opts.size.max(1);
    let half = picture_half(&solid);
    let trace_opts = opts.trace_options();
    let quadrant = mirrored(
        &solid,
        &frame,
        opts.light,
        opts.material.birefringent().then_some(axis),
    );
    let lighting = Lighting::new(opts.head_shadow(), &opts.spots);
    // Absorption per girdle-diameter unit of the canonical solid: α per mm times the mm one
    // unit of its width stands for.
    let mm_per_unit = opts.width_mm / outline_size(solid.vertices()).1.max(1e-300);
    let mut stats = Stats {
        size,
        ..Stats::default()
    };
    // A coloured stone under a grey light is drawn in its colour, band by band like fire;
    // the false-colour lights keep their colours.
    let coloured_grey = opts.light.channels() == 1 && opts.material.colour.is_some();
    // A coloured picture's XYZ pixels and its windowing, for its colour statistics.
    let mut colour_input: Option<(Vec<DVec3>, Vec<DVec3>, f64)> = None;
    let channels = if opts.light == Light::Fire || coloured_grey {
        let fire = opts.light == Light::Fire;
        let body = opts.material.colour.as_ref();
        let absorption = |l: f64| body.map_or(0.0, |c| c.alpha(l) * mm_per_unit);
        // Faint bands (far out in the red) take a neighbour's trace, as in the scores.
        let bands = color::traced_bands(opts.bands.max(1), color::FAINT_BAND);
        let centres: Vec<f64> = bands.iter().map(|b| b.0).collect();
        let weights: Vec<DVec3> = bands.iter().map(|b| b.1).collect();
        let constant =
            matches!(opts.material.dispersion, Dispersion::Constant(_)) && body.is_none();
        let ri0 = opts.material.ri(opts.wavelength_nm);
        // One trace per band (one for all when neither index nor colour changes with
        // wavelength): each band's radiance image, and for a coloured stone a second channel,
        // the light that went through it (the surface reflection left out, for its
        // extinction), and the absorbed power seen and seen from below the girdle plane.
        let n = if body.is_some() { 2 } else { 1 };
        let traces: Vec<(Medium, f64)> = if constant {
            vec![(Medium::Isotropic(ri0), 0.0)]
        } else {
            centres
                .iter()
                .map(|&l| {
                    let m = crate::beam::Medium::of(
                        &opts.material,
                        l,
                        axis,
                        mm_per_unit,
                        body.is_some(),
                    );
                    (m, absorption(l))
                })
                .collect()
        };
        let traced: Vec<(Layer, f64, f64)> = traces
            .par_iter()
            .map(|&(medium, alpha)| {
                // A coloured stone's bands as the scores trace fire's.
                let o = TraceOptions {
                    absorption: alpha,
                    ..if body.is_some() {
                        opts.colour_trace_options()
                    } else {
                        trace_opts
                    }
                };
                let (mut seen, mut under) = (0.0, 0.0);
                // A colourless fire picture sums nothing else: an exit whose elevation no
                // spot reaches (its copies share it) is skipped with its copies.
                let fire_only = fire && body.is_none();
                let reach =
                    |e: &ExitBeam| !fire_only || lighting.spots_reach_z((rot * e.direction).z);
                let value = |e: &ExitBeam| {
                    let w = rot * e.direction;
                    seen += e.power;
                    if w.z < 0.0 {
                        under += e.power;
                    }
                    let v = if fire {
                        lighting.spots(w)
                    } else {
                        opts.light.shade(&lighting, w).1
                    };
                    [v, if e.external { 0.0 } else { v }, 0.0, 0.0, 0.0]
                };
                let layer = Layer::trace(&stone, &frame, &medium, &o, n, value, reach);
                (layer, seen, under)
            })
            .collect();
        let below: Vec<f64> = traced
            .iter()
            .map(|&(_, seen, under)| if seen > 0.0 { under / seen } else { 0.0 })
            .collect();
        let band_layers: Vec<Layer> = traced.into_iter().map(|t| t.0).collect();
        let band_rasters: Vec<Vec<Raster>> = band_layers
            .par_iter()
            .map(|l| Layer::fill(&[l], l.channels, size, half, quadrant))
            .collect();
        let images: Vec<&Raster> = (0..bands.len())
            .map(|b| &band_rasters[if constant { 0 } else { b }][0])
            .collect();
        for l in &band_layers {
            stats.cut_off = stats.cut_off.max(l.stats.cut_off);
            stats.exits += l.exits;
        }
        let outline = band_layers[0].stats.area;
        let white: DVec3 = weights.iter().copied().sum();
        let mut rgb: Vec<Raster> = (0..3).map(|_| Raster::new(size, half)).collect();
        // Rows in parallel; their luminance sums (and fire's, [`fire_of`] from the same XYZ)
        // added in row order (the same on any number of threads).
        let [r, g, b] = &mut rgb[..] else {
            unreachable!("three channels")
        };
        let rows: Vec<(f64, f64)> = r
            .data
            .par_chunks_mut(size)
            .zip(g.data.par_chunks_mut(size))
            .zip(b.data.par_chunks_mut(size))
            .enumerate()
            .map(|(j, ((r, g), b))| {
                let (mut y, mut yc) = (0.0, 0.0);
                for i in 0..size {
                    let p = j * size + i;
                    let xyz = pixel_xyz(&images, &weights, p);
                    y += xyz.y;
                    if fire {
                        yc += saturated_y(&images, p, || xyz, white);
                    }
                    let c = color::xyz_to_linear_srgb(xyz).max(DVec3::ZERO);
                    (r[i], g[i], b[i]) = (c.x, c.y, c.z);
                }
                (y, yc)
            })
            .collect();
        let y_sum: f64 = rows.iter().map(|r| r.0).sum();
        let h = rgb[0].pixel();
        if fire {
            let yc: f64 = rows.iter().map(|r| r.1).sum();
            stats.fire = Some(fire_from_sum(yc, h, outline));
        }
        stats.mean = if outline > 0.0 {
            y_sum * h * h / outline
        } else {
            0.0
        };
        if body.is_some() {
            // The light seen that comes from below the girdle plane, weighted by luminance.
            let (mut num, mut den) = (0.0, 0.0);
            for (b, w) in weights.iter().enumerate() {
                num += w.y * below[if constant { 0 } else { b }];
                den += w.y;
            }
            let window = if den > 0.0 { num / den } else { 0.0 };
            // The colour statistics on their own grid, whatever the picture's size.
            let grid = COLOUR_GRID;
            let regrid: Vec<Vec<Raster>>;
            let on_grid = if size == grid {
                &band_rasters
            } else {
                regrid = band_layers
                    .par_iter()
                    .map(|l| Layer::fill(&[l], l.channels, grid, half, quadrant))
                    .collect();
                &regrid
            };
            let xyz_of = |channel: usize| -> Vec<DVec3> {
                (0..grid * grid)
                    .map(|p| {
                        (0..bands.len())
                            .zip(&weights)
                            .map(|(b, w)| {
                                *w * on_grid[if constant { 0 } else { b }][channel].data[p]
                            })
                            .sum()
                    })
                    .collect()
            };
            colour_input = Some((xyz_of(0), xyz_of(1), window));
        }
        rgb
    } else {
        let n = opts.light.channels();
        let (mut mean, mut bins) = (0.0, [0.0; 5]);
        let medium =
            crate::beam::Medium::of(&opts.material, opts.wavelength_nm, axis, mm_per_unit, false);
        let layer = Layer::trace(
            &stone,
            &frame,
            &medium,
            &trace_opts,
            n,
            |e| {
                let (c, y) = opts.light.shade(&lighting, rot * e.direction);
                mean += e.power * y;
                for (b, x) in bins.iter_mut().zip(c) {
                    *b += e.power * x;
                }
                c
            },
            |_| true,
        );
        let power_in = layer.stats.power_in;
        stats.mean = if power_in > 0.0 { mean / power_in } else { 0.0 };
        if opts.light == Light::Aset {
            let t: f64 = bins.iter().sum();
            let t = if t > 0.0 { t } else { 1.0 };
            stats.aset = Some(AsetShares {
                blue: bins[0] / t,
                red: bins[1] / t,
                green: bins[2] / t,
                leak: bins[3] / t,
                port: bins[4] / t,
            });
        }
        stats.cut_off = layer.stats.cut_off;
        stats.exits = layer.exits;
        Layer::fill(&[&layer], n, size, half, quadrant)
    };
    let coverage = outline_coverage(&solid, &frame, size, half);
    if let Some((xyz, through, window)) = colour_input {
        let grid = if size == COLOUR_GRID {
            coverage.clone()
        } else {
            outline_coverage(&solid, &frame, COLOUR_GRID, half)
        };
        // The scores' view: face-up under ISO light (their colour is this picture's).
        let scores = opts.light == Light::Iso && opts.tilt.tilt_deg == 0.0;
        stats.colour = Some(ColourStats::of(&xyz, &through, &grid, window).seen(scores));
    }
    Image {
        light: opts.light,
        channels,
        coverage,
        stats,
    }
}

/// Share of each pixel of a `size`-pixel picture spanning ±`half` that the outline of
/// `solid` seen along `frame` covers: the facets facing the viewer tile it.
pub(crate) fn outline_coverage(
    solid: &Polyhedron,
    frame: &Frame,
    size: usize,
    half: f64,
) -> Raster {
    let polys: Vec<Vec<DVec2>> = (0..solid.facets().len())
        .filter(|&f| solid.facets()[f].plane.normal.dot(frame.dir) < 0.0)
        .map(|f| {
            solid
                .facet_polygon(f)
                .iter()
                .map(|p| DVec2::new(p.dot(frame.u), p.dot(frame.v)))
                .collect()
        })
        .collect();
    // Band by band with one accumulator: a whole picture's would be fresh memory, slower to
    // touch the first time than to clear.
    let mut coverage = Raster::new(size, half);
    let mut outline = Accumulator::new(size, half, (0, BAND_ROWS.min(size)), 1);
    for (k, rows) in coverage.data.chunks_mut(BAND_ROWS * size).enumerate() {
        let j0 = k * BAND_ROWS;
        outline.reset((j0, j0 + rows.len() / size));
        for poly in &polys {
            outline.add_polygon(poly, &[1.0]);
        }
        outline.finish_into(&mut [rows]);
    }
    coverage
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::Tilt;

    /// Drawing a quadrant and mirroring it gives the full fill's pixels (to rounding) for
    /// every mirror-symmetric picture, and the check refuses the pictures that are not: fire's
    /// spots, a pose tilted out of a mirror plane, a solid without the mirrors.
    #[test]
    fn a_mirrored_quadrant_is_the_whole_picture() {
        let round = canonical(&crate::testkit::tolkowsky());
        let cases = [
            (Light::Iso, Tilt::FACE_UP, 96, true),
            (Light::Aset, Tilt::FACE_UP, 95, true),
            (Light::Hearts, Tilt::FACE_UP, 64, true),
            (Light::Fire, Tilt::FACE_UP, 64, false),
            (
                Light::Iso,
                Tilt {
                    tilt_deg: 10.0,
                    azimuth_deg: 0.0,
                },
                64,
                false,
            ),
            (
                Light::Iso,
                Tilt {
                    tilt_deg: 10.0,
                    azimuth_deg: 33.0,
                },
                64,
                false,
            ),
        ];
        for (light, tilt, size, symmetric) in cases {
            let frame = Frame::viewer(view_rotation(light, tilt));
            assert_eq!(
                mirrored(&round, &frame, light, None),
                symmetric,
                "{light:?} {tilt:?}"
            );
            if !symmetric {
                continue;
            }
            let stone = Stone::new(&round);
            let opts = RenderOptions::new(light);
            let lighting = Lighting::new(opts.head_shadow(), &[]);
            let rot = view_rotation(light, tilt);
            let n = light.channels();
            let value = |e: &ExitBeam| light.shade(&lighting, rot * e.direction).0;
            let layer = Layer::trace(
                &stone,
                &frame,
                &Medium::Isotropic(2.417),
                &opts.trace_options(),
                n,
                value,
                |_| true,
            );
            let half = picture_half(&round);
            let full = Layer::fill(&[&layer], n, size, half, false);
            let quad = Layer::fill(&[&layer], n, size, half, true);
            for (a, b) in full.iter().zip(&quad) {
                let worst = a.max_difference(b);
                assert!(worst < 1e-12, "{light:?} {size}: {worst}");
            }
        }
        // A solid without the mirrors: one pavilion facet turned.
        let mut planes = round.facet_planes();
        let k = planes.iter().position(|p| p.plane.normal.z < -0.5).unwrap();
        planes[k].plane.normal =
            (planes[k].plane.normal + glam::DVec3::new(0.01, 0.02, 0.0)).normalize();
        let skew = Polyhedron::from_planes(&planes).unwrap();
        let frame = Frame::viewer(view_rotation(Light::Iso, Tilt::FACE_UP));
        assert!(!mirrored(&skew, &frame, Light::Iso, None));
        // A birefringent stone's optic axis: up, or in a mirror's plane along an image axis,
        // keeps the mirrors; tilted toward any other azimuth it breaks them.
        let frame = Frame::viewer(view_rotation(Light::Iso, Tilt::FACE_UP));
        assert!(mirrored(&round, &frame, Light::Iso, Some(DVec3::Z)));
        assert!(mirrored(&round, &frame, Light::Iso, Some(frame.u)));
        let tilted = (DVec3::Z + 0.5 * frame.u + 0.2 * frame.v).normalize();
        assert!(!mirrored(&round, &frame, Light::Iso, Some(tilted)));
    }
}
