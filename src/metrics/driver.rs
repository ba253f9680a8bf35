//! The score driver: [`score`] gathers the distinct traces every score needs (one per pose and
//! index, shared), runs them on the rayon pool longest first ([`par_in_order`]) and combines
//! the results in a fixed order into [`Scores`].

use super::config::ScoreConfig;
use super::fire::{fire_placements, turned, FireLattice};
use super::scintillation::{scintillation_of, scintillation_turns};
use super::scores::{Aset, PoseScore, Scores};
use super::sink::{ColourImages, Job, JobContext, PoseResult};
use super::symmetry::{symmetric_pose, symmetric_pose_map};
use crate::beam::{Frame, Stone, TraceOptions};
use crate::geometry::{canonical, Polyhedron};
use crate::optics::{color, Dispersion};
use crate::render::lighting::Lighting;
use crate::render::raster::Raster;
use crate::render::{fire_of, Tilt};
use glam::{DMat3, DVec3};
use rayon::prelude::*;

/// Score `solid` (see the [module documentation](super)). The configuration should have
/// passed [`ScoreConfig::validate`]; out-of-range values are not checked here but never panic.
/// Poses and wavelengths are traced in parallel with rayon and combined in a fixed order, so
/// the result does not depend on the number of threads.
pub fn score(solid: &Polyhedron, cfg: &ScoreConfig) -> Scores {
    score_with_faint(solid, cfg, color::FAINT_BAND)
}

/// [`score`], with fire's bands whose colour weight is below `faint` of the white's merged
/// into a neighbour ([`color::traced_bands`]; 0 traces every band).
pub(super) fn score_with_faint(solid: &Polyhedron, cfg: &ScoreConfig, faint: f64) -> Scores {
    // A birefringent stone's optic axis, carried into the canonical placement with it.
    let axis = cfg.material.uniaxial.as_ref().map_or(DVec3::Z, |u| {
        canonical::canonical_axis(solid, u.axis.vector())
    });
    // The stone as given: its colour is drawn as `render` draws it ([`colour_of`]).
    let given = solid;
    let solid = &canonical::canonical(solid);
    let stone = Stone::new(solid);
    let light = Lighting::new(cfg.head_shadow_deg, &cfg.spots);
    let placements = fire_placements(cfg);
    let turns = scintillation_turns(cfg);
    let mut lightings: Vec<Lighting> = placements
        .iter()
        .map(|p| Lighting::new(cfg.head_shadow_deg, &p.spots))
        .collect();
    let first_turn = lightings.len();
    lightings.extend(
        turns
            .iter()
            .map(|&t| Lighting::new(cfg.head_shadow_deg, &turned(&cfg.spots, t, 0.0))),
    );
    let half = crate::render::picture_half(solid);
    let ri0 = cfg.material.ri(cfg.wavelength_nm);
    // Absorption per unit of the canonical solid is α per mm times this.
    let mm_per_unit = {
        let (width_mm, width) = stone_width(solid, cfg);
        width_mm / width.max(1e-300)
    };
    let medium_at = |l: f64, absorbing: bool| {
        crate::beam::Medium::of(&cfg.material, l, axis, mm_per_unit, absorbing)
    };
    // Fire's bands: the faint ones (far out in the red) take a neighbour's trace.
    let bands = color::traced_bands(cfg.bands.max(1), faint);
    // Distinct traces, each shared by every score that needs it (same pose, same index).
    let mut jobs: Vec<Job> = Vec::new();
    #[derive(Clone, Copy)]
    enum Use {
        FaceUp,
        Brilliance,
        /// An image under lighting `l`, of the pose the job traces or, mapped by a symmetry
        /// of the stone, of another ([`Job::views`]).
        Image(usize, Option<DMat3>),
    }
    // A job is named by its pose, its index (which names the wavelength: a stone's ordinary
    // index is one-to-one with it) and its split; a birefringent stone's medium follows from
    // the wavelength `l`.
    let index =
        |tilt: Tilt, ri: f64, l: f64, what: Use, split: f64, jobs: &mut Vec<Job>| -> usize {
            // Every face-up pose is the same trace, whatever azimuth it names.
            let tilt = if tilt.tilt_deg == 0.0 {
                Tilt::FACE_UP
            } else {
                tilt
            };
            let split = if tilt != Tilt::FACE_UP {
                split
            } else if ri.to_bits() == ri0.to_bits() {
                split
                    .min(cfg.fire_split_threshold)
                    .min(cfg.face_up_split_threshold)
            } else {
                split.min(cfg.fire_split_threshold)
            };
            let same =
                |j: &Job| j.tilt == tilt && j.ri.to_bits() == ri.to_bits() && j.split == split;
            let k = match jobs.iter().position(same) {
                Some(k) => k,
                None => {
                    jobs.push(Job {
                        tilt,
                        ri,
                        medium: if cfg.material.birefringent() {
                            medium_at(l, false)
                        } else {
                            crate::beam::Medium::Isotropic(ri)
                        },
                        images: Vec::new(),
                        views: Vec::new(),
                        brilliance: false,
                        face_up: false,
                        split,
                        absorption: 0.0,
                        colour: false,
                    });
                    jobs.len() - 1
                }
            };
            match what {
                Use::FaceUp => jobs[k].face_up = true,
                Use::Brilliance => jobs[k].brilliance = true,
                Use::Image(l, view) => {
                    if !jobs[k].images.contains(&l) {
                        jobs[k].images.push(l);
                        jobs[k].views.push(view);
                    }
                }
            }
            k
        };
    let split = cfg.tilted_split();
    // The face-up figures (overhead light return, ASET) are the cross-checked ones: the
    // face-up trace at the reference wavelength splits down to `face_up_split_threshold`
    // (cheap: a face-up stone traces one symmetry wedge), the other face-up traces (fire's
    // bands) to `fire_split_threshold`.
    let l0 = cfg.wavelength_nm;
    let face_up = index(
        Tilt::FACE_UP,
        ri0,
        l0,
        Use::FaceUp,
        cfg.fire_split_threshold,
        &mut jobs,
    );
    // Brilliance sees no spot light: a pose and its image under one of the stone's
    // symmetries return the same light, so they share one trace.
    // A birefringent stone's poses are mapped only by the symmetries that keep its optic
    // axis: another one would trace the crystal turned.
    let symmetry = if cfg.material.birefringent() {
        stone.symmetry_keeping(axis)
    } else {
        stone.symmetry()
    };
    let brill: Vec<usize> = cfg
        .tilts
        .iter()
        .map(|t| {
            let t = symmetric_pose(*t, symmetry);
            index(t, ri0, l0, Use::Brilliance, split, &mut jobs)
        })
        .collect();
    let constant = matches!(cfg.material.dispersion, Dispersion::Constant(_));
    let fire: Vec<usize> = bands
        .iter()
        .filter(|_| cfg.parts.fire)
        .map(|&(l, _)| {
            let (ri, l) = if constant {
                (ri0, l0)
            } else {
                (cfg.material.ri(l), l)
            };
            let mut k = 0;
            for p in 0..placements.len() {
                k = index(
                    Tilt::FACE_UP,
                    ri,
                    l,
                    Use::Image(p, None),
                    cfg.fire_split_threshold,
                    &mut jobs,
                );
            }
            k
        })
        .collect();
    // A coloured stone's face-up colour rides on fire's band traces when each band has its
    // own (the exits' unabsorbed power keeps fire and the rest colourless); otherwise
    // `colour_of` draws it apart.
    let shared_colour = shared_colour(solid, cfg, &bands, &fire, constant);
    if let Some(alphas) = &shared_colour {
        for ((&k, &alpha), band) in fire.iter().zip(alphas).zip(&bands) {
            jobs[k].absorption = alpha;
            jobs[k].colour = true;
            if cfg.material.birefringent() {
                // The crystal's own absorption per mode (pleochroism).
                jobs[k].medium = medium_at(band.0, true);
            }
        }
    }
    // Scintillation: per turn, the rocking sequence toward the turn's azimuth, under the spot
    // lights turned with it. A pose that a symmetry of the stone maps onto another is that
    // pose's trace seen through the symmetry (one trace for both).
    let scint: Vec<Vec<(usize, usize)>> = turns
        .iter()
        .enumerate()
        .filter(|_| cfg.parts.scintillation)
        .map(|(j, &turn)| {
            cfg.scintillation_tilts
                .iter()
                .map(|&t| {
                    let tilt = Tilt {
                        tilt_deg: t,
                        azimuth_deg: turn,
                    };
                    let l = first_turn + j;
                    let (rep, view) = symmetric_pose_map(tilt, symmetry);
                    (
                        index(rep, ri0, l0, Use::Image(l, view), split, &mut jobs),
                        l,
                    )
                })
                .collect()
        })
        .collect();
    let lattice = FireLattice::new(&placements, &lightings[..first_turn]);
    // The costliest traces first, so that the short ones fill in at the end: face-up ones
    // (the finest splits), then the poses whose trace uses the fewest symmetries.
    let copies: Vec<usize> = jobs
        .iter()
        .map(|j| stone.frame_symmetries(&Frame::viewer(j.tilt.rotation())))
        .collect();
    let mut order: Vec<usize> = (0..jobs.len()).collect();
    order.sort_by(|&a, &b| {
        let (x, y) = (&jobs[a], &jobs[b]);
        (x.tilt != Tilt::FACE_UP)
            .cmp(&(y.tilt != Tilt::FACE_UP))
            .then(x.split.total_cmp(&y.split))
            .then(copies[a].cmp(&copies[b]))
            .then(y.images.len().cmp(&x.images.len()))
    });
    let ctx = JobContext {
        stone: &stone,
        solid,
        light: &light,
        lightings: &lightings,
        lattice: &lattice,
        cfg,
        half,
    };
    let results: Vec<PoseResult> = par_in_order(&order, |k| ctx.run(&jobs[k]));
    let image = |k: usize, l: usize| -> Option<&Raster> {
        let pos = jobs[k].images.iter().position(|&x| x == l)?;
        results[k].images.get(pos)
    };

    let norm = |r: &PoseResult, x: f64| {
        if r.power_in > 0.0 {
            x / r.power_in
        } else {
            0.0
        }
    };
    let fu = &results[face_up];
    let n = brill.len().max(1) as f64;
    let poses: Vec<PoseScore> = brill
        .iter()
        .zip(&cfg.tilts)
        .map(|(&k, t)| PoseScore {
            tilt_deg: t.tilt_deg,
            azimuth_deg: t.azimuth_deg,
            iso: norm(&results[k], results[k].iso),
            cos: norm(&results[k], results[k].cos),
        })
        .collect();
    let brilliance_iso = poses.iter().map(|p| p.iso).sum::<f64>() / n;
    let brilliance_cos = poses.iter().map(|p| p.cos).sum::<f64>() / n;
    let a = fu.aset;
    let at: f64 = a.iter().sum();
    let aset = if at > 0.0 {
        Aset {
            blue: a[0] / at,
            red: a[1] / at,
            green: a[2] / at,
            leak: a[3] / at,
            port: a[4] / at,
        }
    } else {
        Aset::default()
    };
    let weights: Vec<DVec3> = bands.iter().map(|b| b.1).collect();
    let outline = solid.projected_area(DVec3::Z);
    // Each placement's fire in parallel, summed in placement order.
    let per_placement: Vec<f64> = placements
        .par_iter()
        .enumerate()
        .map(|(p, placement)| {
            let images: Vec<&Raster> = fire.iter().filter_map(|&k| image(k, p)).collect();
            placement.weight * fire_of(&images, &weights, outline)
        })
        .collect();
    let fire_sum: f64 = per_placement.iter().sum();
    let fire_w: f64 = placements.iter().map(|p| p.weight).sum();
    let fire_value = if !cfg.parts.fire {
        f64::NAN
    } else if fire_w > 0.0 {
        fire_sum / fire_w
    } else {
        0.0
    };
    let sequences: Vec<Vec<&Raster>> = scint
        .iter()
        .map(|seq| seq.iter().filter_map(|&(k, l)| image(k, l)).collect())
        .collect();
    let sequences: Vec<&[&Raster]> = sequences.iter().map(|s| s.as_slice()).collect();
    Scores {
        overhead_light_return: norm(fu, fu.up),
        brilliance: 0.5 * (brilliance_iso + brilliance_cos),
        brilliance_iso,
        brilliance_cos,
        fire: fire_value,
        scintillation: if cfg.parts.scintillation {
            scintillation_of(&sequences)
        } else {
            f64::NAN
        },
        aset,
        poses,
        colour: match shared_colour {
            Some(_) => {
                let images: Vec<&ColourImages> = fire
                    .iter()
                    .filter_map(|&k| results[k].colour.as_ref())
                    .collect();
                Some(colour_from_bands(solid, &images, &weights, half))
            }
            None => colour_of(given, cfg),
        },
    }
}

/// Per fire band, the body colour's absorption per unit of the canonical `solid`, when the
/// colour can be drawn on fire's band traces: a coloured material whose index changes with
/// the wavelength (so that every band has its own trace) and fire scored (fire's band traces
/// are then traced as [`colour_of`]'s picture). The colour is drawn on its own grid
/// ([`COLOUR_GRID`](crate::render::COLOUR_GRID)) either way.
fn shared_colour(
    solid: &Polyhedron,
    cfg: &ScoreConfig,
    bands: &[(f64, DVec3)],
    fire: &[usize],
    constant: bool,
) -> Option<Vec<f64>> {
    let body = cfg.material.colour.as_ref()?;
    let distinct = fire.iter().enumerate().all(|(i, k)| !fire[..i].contains(k));
    if constant || !cfg.parts.fire || !distinct || fire.is_empty() {
        return None;
    }
    // Fire's band traces trace as the colour's picture does (checked: a coloured picture's
    // untilted bands are traced with fire's split and ray floor).
    let picture = colour_options(solid, cfg).colour_trace_options();
    let fires = TraceOptions {
        polarization: cfg.trace.polarization,
        footprints: true,
        split_threshold: cfg.fire_split_threshold,
        ..cfg.trace
    };
    if fires != picture {
        return None;
    }
    let (width_mm, width) = stone_width(solid, cfg);
    let per_unit = width_mm / width.max(1e-300);
    Some(
        bands
            .iter()
            .map(|&(l, _)| body.alpha(l) * per_unit)
            .collect(),
    )
}

/// The width in mm a coloured stone's size gives `solid` (its length turned into a width by
/// the outline's L/W when the size names a length), and the outline's width in the solid's
/// own units.
fn stone_width(solid: &Polyhedron, cfg: &ScoreConfig) -> (f64, f64) {
    let (l, w) = crate::geometry::outline_size(solid.vertices());
    let l_w = l / w.max(1e-300);
    let mm = cfg
        .size
        .width_mm(l_w, "score.size_mm")
        .unwrap_or(crate::optics::StoneSize::DEFAULT_WIDTH_MM);
    (mm, w)
}

/// The face-up colour from fire's band traces' ISO pictures ([`ColourImages`]): XYZ per pixel
/// by the bands' colour weights, over the outline, as `render` draws a coloured stone.
fn colour_from_bands(
    solid: &Polyhedron,
    images: &[&ColourImages],
    weights: &[DVec3],
    half: f64,
) -> crate::render::ColourStats {
    let grid = crate::render::COLOUR_GRID;
    let n = grid * grid;
    let xyz_of = |through: bool| -> Vec<DVec3> {
        (0..n)
            .map(|p| {
                images
                    .iter()
                    .zip(weights)
                    .map(|(c, w)| {
                        *w * if through {
                            c.through.data[p]
                        } else {
                            c.all.data[p]
                        }
                    })
                    .sum()
            })
            .collect()
    };
    // The light seen that comes from below the girdle plane, weighted by luminance.
    let (mut num, mut den) = (0.0, 0.0);
    for (c, w) in images.iter().zip(weights) {
        if c.seen > 0.0 {
            num += w.y * c.below / c.seen;
        }
        den += w.y;
    }
    let window = if den > 0.0 { num / den } else { 0.0 };
    let coverage = crate::render::outline_coverage(
        solid,
        &Frame::viewer(Tilt::FACE_UP.rotation()),
        grid,
        half,
    );
    crate::render::ColourStats::of(&xyz_of(false), &xyz_of(true), &coverage, window)
}

/// The face-up colour of a coloured stone: its ISO picture drawn in colour, exactly as
/// `render --light iso` draws it (fire's bands, each with its exact absorption, traced as
/// fire's: fire's split threshold and the scores' ray floor), its statistics on the colour
/// grid ([`COLOUR_GRID`](crate::render::COLOUR_GRID), whatever the scores'
/// resolution); `None` when the material is colourless. With the default settings this is
/// `render --light iso`'s `colour` for the same stone, material, size, head shadow and bands,
/// bit for bit: one extinction wherever it is shown.
pub fn colour_of(solid: &Polyhedron, cfg: &ScoreConfig) -> Option<crate::render::ColourStats> {
    cfg.material.colour.as_ref()?;
    crate::render::render(solid, &colour_options(solid, cfg))
        .stats
        .colour
}

/// The options of the coloured ISO picture the face-up colour is measured on
/// ([`colour_of`]).
fn colour_options(solid: &Polyhedron, cfg: &ScoreConfig) -> crate::render::RenderOptions {
    crate::render::RenderOptions {
        size: crate::render::COLOUR_GRID,
        head_shadow_deg: Some(cfg.head_shadow_deg),
        material: cfg.material.clone(),
        bands: cfg.bands,
        trace: cfg.trace,
        // Traced as fire's bands are: the colour rides on their traces when fire is scored.
        colour_split_threshold: cfg.fire_split_threshold,
        colour_ray_floor: cfg.trace.ray_floor,
        width_mm: stone_width(solid, cfg).0,
        ..crate::render::RenderOptions::new(crate::render::Light::Iso)
    }
}

/// `f(k)` for every `k` of `order` (a permutation of `0..n`), started in that order on the
/// rayon pool: each worker takes the next one when it is free (greedy list scheduling, so
/// that long jobs given first finish together). The results come back by index,
/// `[f(0), f(1), …]`, whatever the number of threads.
pub(super) fn par_in_order<T: Send + Sync>(
    order: &[usize],
    f: impl Fn(usize) -> T + Sync,
) -> Vec<T> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::OnceLock;
    let next = AtomicUsize::new(0);
    let slots: Vec<OnceLock<T>> = order.iter().map(|_| OnceLock::new()).collect();
    let workers = rayon::current_num_threads().clamp(1, order.len().max(1));
    (0..workers).into_par_iter().for_each(|_| loop {
        let i = next.fetch_add(1, Ordering::Relaxed);
        let Some(&k) = order.get(i) else { break };
        if let Some(slot) = slots.get(k) {
            let _ = slot.set(f(k));
        }
    });
    slots
        .into_iter()
        .map(|s| s.into_inner().expect("every index of `order` was run"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Jobs started in any order on pools of one to three threads come back by index, each run
    /// exactly once.
    #[test]
    fn par_in_order_returns_results_by_index() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        for threads in 1..=3 {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a pool");
            for order in [
                vec![],
                vec![0],
                vec![3, 1, 4, 0, 2],
                (0..40).rev().collect(),
            ] {
                let runs = AtomicUsize::new(0);
                let got = pool.install(|| {
                    par_in_order(&order, |k| {
                        runs.fetch_add(1, Ordering::Relaxed);
                        k * k
                    })
                });
                let want: Vec<usize> = (0..order.len()).map(|k| k * k).collect();
                assert_eq!(got, want, "{threads} threads, order {order:?}");
                assert_eq!(runs.load(Ordering::Relaxed), order.len());
            }
        }
    }
}
