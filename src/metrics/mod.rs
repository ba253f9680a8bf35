//! Scores of a cut, computed from beam trees: overhead light return, brilliance, fire,
//! scintillation and ASET-style shares.
//!
//! All scores except `overhead_light_return` come from an orthographic viewer straight above
//! the stone, traced backwards: each exit beam of the backward trace is a bundle of the
//! viewer's sight lines that end up looking out of the stone in one direction `w`, and it
//! shows whatever the environment sends from `w`. By reciprocity (unpolarized light sources, a
//! polarization-blind eye) the backward trace's powers are the forward light's. The stone is
//! *tilted* for the off-face-up poses; the environment and the viewer stay put in the world
//! (z up), exactly as when a stone is rocked under a lamp. Lighting is described in
//! [`lighting`]; every edge there is soft, and the images of [`raster`] use exact area
//! coverage, so that every score is a continuous function of the cut's proportions (the beam
//! tree itself is: footprints and powers move continuously, beams appear and vanish with zero
//! area, and Fresnel's reflectance is continuous through the critical angle). The remaining
//! small jumps come from the tracer's approximations below its thresholds
//! ([`TraceOptions`]): each is at most a narrow beam's power (< 1e-4 of the light by default).
//! Narrow beams followed as discs that fork at facet edges ([`TraceOptions::narrow_forks`],
//! `[score] narrow_forks` in a config) move their light from facet to facet continuously
//! too: with a split threshold of 3e-4 and a ray floor of 0.02, brilliance's total variation
//! over its range on the 0.002° pavilion profile of `cargo bench --bench profile` falls from
//! 2.30 to 1.02 and its median absolute second difference from 1.3e-4 to 1.6e-5, for 1.4
//! times the time (a full score 1.9 times); but brilliance moves by up to 4.1e-4 from the
//! exactly split value (on tolkowsky from +6e-5 to +4.1e-4, 4.5 standard errors of a
//! million-photon check), so they are off by default. (Most of that bias is their rays'
//! closure: with each fork stopped at the ray floor of its own share instead of the whole
//! narrow beam's, brilliance's mean offset over the profile's 501 cuts from the same cuts
//! split down to 2e-6 falls from +1.9e-4 to +6.6e-5 (the default: +3.9e-5), its total
//! variation is 1.01 of its range and its median |second difference| 1.4e-5, but a score
//! takes 15 times as long.)
//!
//! The figures of this section were measured under an open sky (head shadow 0, the default
//! before the viewer's 15° head shadow). Under the 15° default (2026-12-05, the same 501
//! cuts): brilliance's total variation over its range is 1.35 and its median |second
//! difference| 1.24e-4 (open sky 2.30 and 1.26e-4: the same roughness over a range that has
//! doubled, 0.045 against 0.021, brilliance now rising toward 41° instead of falling), fire's
//! 2.65 and 8.9e-4 (2.51 and 9.1e-4), scintillation's 1.61 and 1.9e-4 (1.66 and 1.7e-4); from
//! every 25th cut their total variations are 1.00, 1.81 and 1.49 (0.98, 1.90 and 1.55).
//!
//! How smooth can brilliance be? Split finer, the profile converges (measured with
//! `cargo bench --bench profile`): with the tilted poses split down to 1e-5 its total
//! variation is 1.08 of its range and its median |second difference| 3.2e-5, at 2e-6 1.01
//! and 1.7e-5 (at 1e-4, the default, 2.30 and 1.3e-4). Much of that last figure is the
//! scores' own roughness on this scale, which splitting finer no longer removes: the face-up
//! pose alone, split down to 1e-6, 1e-7 and 1e-8 (nothing cut off above 1e-10), has median
//! |second differences| of 7.6e-5, 6.6e-5 and 6.0e-5 over the profile's first 0.1°, and its
//! second differences at 1e-6 and 1e-7 correlate by 0.81 over the whole degree. A beam
//! tree's powers are continuous in the cut but not smooth: Fresnel's reflectance has an
//! infinite slope at the critical angle (and a refracted exit's direction at grazing exit),
//! and as the cut changes, beams of the thousands of facet sequences cross it one after
//! another. Averaging over poses (and an optimizer's simplex, tenths of a degree wide)
//! smooths that; a median |second difference| of 1e-5 at 0.002° is out of reach by
//! splitting finer.
//!
//! How smooth are fire and scintillation? Both genuinely rise and fall over the profile's
//! degree (scintillation climbs from 0.47 to 0.65 at 40.65°, drops to 0.58 by 40.75° and
//! rises again; fire has two humps). Taken from every 25th cut only (0.05° apart), their
//! total variations are 1.90 and 1.55 of their ranges, so most of their 0.002° figures (2.51
//! and 1.66) is the functions' own shape, and a total variation near 1 would take a different
//! score, not a better trace. What the 0.002° figure adds is the fine-scale roughness: 0.61
//! for fire, 0.11 for scintillation, and 1.31 for brilliance, all of it below 0.01° (every
//! 5th cut: 1.08; split down to 1e-5, 0.08). Scintillation's shape stays with more rocking
//! azimuths (15 instead of 5: 1.61; for a round brilliant 10 are the 5's poses twice, exactly)
//! and with its images blurred before they are compared (1.79), and its rocked poses split
//! down to 1e-5 change it hardly at all (1.63).
//!
//! What the fine-scale roughness costs to remove, with today's narrow rays (2026-12-03;
//! excess = total variation over the range at 0.002° minus that at 0.05°; cost in
//! instructions, cachegrind, which unlike time does not drift with the machine):
//!
//! | tilted poses split to | brilliance excess | instructions of brilliance alone |
//! |---|---|---|
//! | 1e-4 (default) | 1.31 | 1 |
//! | 5e-5 | 0.65 | 1.41 |
//! | 3e-5 | 0.44 | 1.86 |
//! | 2e-5 | 0.24 | 2.35 |
//! | 1e-5 | 0.08 | 3.55 |
//!
//! Fire's face-up traces split to 1e-6 instead of 3e-6 take its excess from 0.61 to 0.35 for
//! 1.25 times a full score's instructions. Every jump is a narrow beam's ray crossing a
//! facet edge or a beam crossing the split threshold, so the excess falls about as the split
//! threshold does, and the tracer's cost rises about as its inverse: brilliance's excess of
//! 0.3 takes 2.35 times today's brilliance, and fire's about 1.4 times today's full score.
//!
//! Forks remove the edge jumps instead, at the default splits and ray floor: excess 0.015 for
//! brilliance, 0.31 for fire, 0.08 for scintillation (0.11 without), for 2.0 times a full
//! score's time (1.73 with forks in fire's and scintillation's traces only). Against the same
//! 51 cuts traced far finer (tilted poses to 2e-6, face-up traces to 3e-7), their fire and
//! scintillation are closer to exact (mean |error| 1.4e-3 and 2.8e-4 against the default's
//! 2.7e-3 and 6.9e-4), but brilliance is not: its closure biases it by +2.0e-4 (COS +3.2e-4)
//! against the default's +6.6e-5. Fire's traces split to 1e-6 without forks err by 8.7e-4
//! (always from above, as fire converges) for 1.22 times a full score's time. Neither is the
//! default while the score's time target is unmet.
//!
//! The smooth setting ([`ScoreConfig::smooth`], `[score] setting = "smooth"` in an
//! optimization's config) meets the fine-scale goal of excess ≤ 0.3 for both brilliance and
//! fire (measured 2026-12-06 on the profile's 501 cuts under the 15° head shadow): tilted
//! poses split down to 1e-5 (brilliance 0.352 → 0.008), fire's traces to 3e-7 and fire traced
//! at 32 wavelength bands instead of 8 (fire 0.847 → 0.297; scintillation 0.124 → 0.062), for
//! 5.8 times the default's instructions per cut (cachegrind, five cuts of the profile; 5.9
//! times its CPU time over the 501 cuts; with 16 bands fire's excess is 0.361 at 4.2 times the
//! CPU time). Splitting alone stops helping fire: over the profile's first 0.2° with 8 bands its
//! excess is 0.44 at the default, 0.22 at 3e-7, 0.21 at 1e-7 and 0.20 at 3e-8, the second
//! differences at 1e-7 and 3e-8 correlating by 0.99 (the trace has converged), and a ray floor
//! of 0 or images of 32 or 128 pixels change it by less than 0.03. What is left is the
//! sampling of the spectrum: each band is one beam of its own that crosses a spot light's soft
//! rim at its own pavilion angle, so over the profile's first 0.1° fire's excess is 0.54, 0.34
//! and 0.29 at 8, 16 and 32 bands, and the second differences at 16 and 32 bands correlate by
//! only 0.24 while fire's mean moves by 2e-5: the fine-scale shape at 16 bands is the band
//! sampling's, not fire's. (More placements of the spot lights are no cure: 51 instead of 17
//! change fire's shape over 0.2° itself, its 0.05° total variation 0.94 → 1.42.)
//!
//! Where a score's time goes (2026-12-03): with every narrow beam cut off instead of followed,
//! a full score takes 0.37–0.39 of its time, a tilted pose 0.28–0.29 and a fire band's face-up
//! trace 0.34 (`cargo bench --bench beam -- pose` prints the last two). Rays of more than 32
//! segments, light caught by total internal reflection, which loses no power and so never
//! reaches the ray floor, are 15 % of the rays and 56 % of the segments. Cutting them short
//! is no cure: stopped dark at 48 segments they bias brilliance by −1.1e-3 on the 51 cuts
//! above (−4.1e-3 at 16), handed back with the late exits' mean at 24 by +5.6e-4, against
//! the default's +6.6e-5.
//!
//! # Same solid, same scores; a turned stone too
//!
//! Scores are functions of the solid, not of its numbers: it is first put in the canonical
//! placement of [`canonical`] (centroid at the origin, unit size, turned about its axis to a
//! canonical azimuth, facets in a canonical order), so a translated, uniformly scaled,
//! reordered, symmetry-rotated or arbitrarily turned copy of a stone scores the same. The
//! canonical azimuth ([`canonical::azimuth_turn`]) is where the stone's k-th azimuthal harmonic
//! (k its rotation order) is real: it puts a mirror line on azimuth 0, and leaves the bundled
//! presets as drawn. Turned copies agree exactly when the turn is one of the stone's
//! symmetries, and otherwise to the ~1e-13 of the turn's arithmetic (so, at worst, to the
//! tracer's response to such a change; see [`TraceOptions`]).
//!
//! Turning a stone under the lights is still a real change of pose, and the scores average
//! over it from that canonical start: brilliance over the ring poses of [`Tilt::default_set`]
//! (five azimuths per ring), fire over [`fire_placements`] (turns of the lights in steps of
//! 360°/17), scintillation over [`scintillation_turns`] (five rocking azimuths).
//!
//! # The scores
//!
//! * **`overhead_light_return`** ∈ [0, 1]: the share of a parallel beam from straight above,
//!   over the stone's projected area, that leaves into the upper hemisphere (exit direction
//!   z > 0), external reflection included, at [`ScoreConfig::wavelength_nm`]. The photon
//!   tracer with directed light at 0° and no absorption measures the same thing. (Not
//!   continuous: a beam crossing the horizon jumps; it is the figure for cross-checks.)
//! * **`brilliance_iso`**, **`brilliance_cos`** ∈ [0, 1]: the light the viewer sees returned,
//!   as a share of what a perfect white diffuser of the same outline would show, under
//!   GemRay-style ISO lighting (radiance 1 over the upper hemisphere) and COS lighting
//!   (radiance = cosine of the angle from the zenith), both times the viewer's head shadow
//!   (a dark cone of half-angle [`ScoreConfig::head_shadow_deg`] around the line of sight,
//!   [`DEFAULT_HEAD_SHADOW_DEG`] = 15° by default, soft by ±1° at its rim), averaged
//!   with equal weights over the poses [`ScoreConfig::tilts`] (face-up and two rings of
//!   tilted poses by default) — GIA's weighted light return in spirit.
//!   **`brilliance`** = (ISO + COS) / 2. The head shadow is on by default because what the
//!   optimizer climbs must be what a person sees: with an open sky, light from straight
//!   overhead counts fully although the viewer's head blocks it, and a search for brilliance
//!   finds cuts that return mostly that light and look dark (a quartz brilliant's winner had
//!   73 % of its face-up view in the ASET port). The spot lights of fire and scintillation
//!   are shadowed by the same head; a head shadow of 0 gives the open-sky scores.
//! * **`fire`** ≥ 0, in percent (about 0.7 for a Tolkowsky diamond, more for the same cut in cubic
//!   zirconia): saturated colour under small light sources, as an *expectation over the ways a
//!   face-up stone meets its lights*. The face-up view is traced at [`ScoreConfig::bands`]
//!   wavelengths (band centres across 380–780 nm; a band whose colour weight is below
//!   [`color::FAINT_BAND`] of the white's in X, Y and Z — with 8 bands, 730–780 nm at ~2e-5 — is
//!   not traced but takes its neighbour's image, [`color::traced_bands`]: fire moves by < 1e-6 for
//!   ~5 % fewer instructions); for one placement of the spot lights ([`Spot::default_set`], seven
//!   5° spots of radiance 1) each band's image is rasterised with exact footprint coverage; each
//!   pixel's spectrum becomes CIE XYZ with D65-weighted CIE 1931 bands
//!   ([`color::band_weights_d65`]) and then CIELAB relative to the D65 white of the spots' radiance
//!   (Y = 1). One placement's fire is `100 · Σ Y·s` over the face-up outline per unit of its area,
//!   `s = C*ab / L*` the pixel's saturation: coloured light per unit of face-up area (`s` hardly
//!   depends on brightness, so fire is linear in the light and one concentrated flash cannot
//!   dominate). Fire is the weighted mean over [`fire_placements`]: the lights turned about the
//!   zenith in equal steps (the stone turning under them: the face-up traces are shared, only the
//!   lights move) and raised or lowered by up to [`FIRE_LIFT_DEG`] with a smooth raised-cosine
//!   weight (the stone rocking a little under them). A single placement is a checkerboard of single
//!   flashes in the cut's parameters (a dispersed fan crossing one spot's rim); the expectation
//!   varies smoothly. A grey pixel (every band the same) contributes exactly 0, so a material
//!   without dispersion has fire exactly 0. Fire's traces split down to
//!   [`ScoreConfig::fire_split_threshold`] (3e-6), thirty times finer than the others: on the
//!   0.002° profile of `cargo bench --bench profile` fire's total variation over its range falls
//!   from 3.56 at 1e-5 to 2.51 (2.25 at 1e-6, 2.18 at 3e-7; sampled every 0.1° the profile itself
//!   rises and falls by 1.7 times its range), for a quarter more time.
//! * **`scintillation`** ∈ [0, 1]: how much the face-up pattern of bright and dark changes as
//!   the stone rocks, in every direction. For each of [`ScoreConfig::scintillation_turns`]
//!   evenly spaced azimuths ψ ([`scintillation_turns`]) the stone is rocked toward ψ through
//!   [`ScoreConfig::scintillation_tilts`] (0° then 3° by default) under the spot lights
//!   turned by ψ — a turn of the whole scene, i.e. the stone turned by −ψ — and its image of
//!   the spots at [`ScoreConfig::wavelength_nm`] taken at each tilt. The score is
//!   `Σ_ψ Σₖ Σₚ |Iₖ₊₁ − Iₖ| / Σ_ψ Σₖ Σₚ (Iₖ₊₁ + Iₖ)`: 0 when nothing changes, 1 when
//!   consecutive patterns never overlap. Rocking poses that a symmetry of the stone maps onto
//!   each other (for a round brilliant, the turns 72° and 288°, 144° and 216°) share one
//!   trace, each image seen through its symmetry (the same pixels to rounding). (Rocking
//!   about one axis only made the score depend on how the stone was turned: 0.466 → 0.509
//!   for a round brilliant turned by 22.5°.)
//! * **`aset`** `{blue, red, green, leak, port}`, each ∈ [0, 1], sum 1: the shares of the
//!   face-up view (by power, over the traced light; cut-off light excluded) whose sight lines
//!   leave the stone toward 75–80° elevation (blue: 75–90° less the port), 45–75° (red), 0–45°
//!   (green), below the horizon (leak), or into the viewer's dark port within [`PORT_DEG`](crate::render::PORT_DEG)
//!   (10°) of the zenith (port, taken out of blue), with ±1° soft boundaries: the shares of
//!   the ASET picture at its default port ([`lighting::aset_shares_in`], one definition for
//!   both). The brilliance's head shadow does not apply to them.
//!
//! [`TraceOptions`]: crate::beam::TraceOptions
//! [`TraceOptions::narrow_forks`]: crate::beam::TraceOptions::narrow_forks
//! [`Spot::default_set`]: lighting::Spot::default_set
//! [`color::FAINT_BAND`]: crate::optics::color::FAINT_BAND
//! [`color::traced_bands`]: crate::optics::color::traced_bands
//! [`color::band_weights_d65`]: crate::optics::color::band_weights_d65

pub use crate::geometry::canonical;
pub use crate::render::{fire_of, lighting, raster, Tilt};

mod config;
mod driver;
mod fire;
mod material;
mod overhead;
mod scintillation;
pub mod score_name;
mod scores;
mod sink;
pub mod stones;
mod symmetry;

#[cfg(test)]
mod tests;

pub use config::{
    Parts, ScoreConfig, ScoreSetting, DEFAULT_HEAD_SHADOW_DEG, REFERENCE_WAVELENGTH_NM,
};
pub use driver::{colour_of, score};
pub use fire::{fire_placements, Placement, FIRE_LIFT_DEG};
pub use material::material_of;
pub use overhead::{overhead_light_return, overhead_light_return_with};
pub use scintillation::{scintillation_of, scintillation_turns};
pub use score_name::{ScoreInfo, ScoreName, SCORES};
pub use scores::{Aset, PoseScore, Scores};
pub use stones::{ColourNotes, CrystalChoice, NoteKind, StoneChoice, StoneFields, Stones};
pub use symmetry::symmetric_pose;
