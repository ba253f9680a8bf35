//! Checks of the renderer (the "Checks"):
//!
//! 1. against an independent brute-force backward ray tracer written here (its own
//!    ray–convex-polyhedron intersection, Snell refraction and unpolarized Fresnel reflectance,
//!    a jittered grid of sight lines per pixel, every interface split deterministically);
//! 2. a closed form: the ASET switch of the table centre at the pavilion angle
//!    p* = (180° − asin(sin 45° / n)) / 4;
//! 3. the 8-fold symmetry of a face-up round brilliant (the pixel grid's part of it);
//! 4. energy: ASET shares, per-pixel sums against the outline's coverage, a stone of index 1;
//! 5. the picture's mean equals `stats.mean`;
//! 6. the hearts & arrows viewer shows eight even hearts face-down, uneven ones when a
//!    pavilion main is steeper;
//! 7. a birefringent zircon's keel edge seen twice, offset by the closed-form walk-off.
//!
//! Nothing here calls the beam tracer or `optics::fresnel`: the brute-force tracer only shares
//! the renderer's definitions of the view (pose rotation, frame, picture square) and the
//! lights' radiance functions ([`Light::shade`]).
//!
//! The checks live by subject: [`brute`] (1), [`views`] (2 and 3), [`energy`] (4 and 5),
//! [`hearts`] (6), [`doubling`] (7).

use super::{Light, RenderOptions, Tilt};

mod brute;
mod colour;
mod doubling;
mod energy;
mod hearts;
mod views;

/// Render options of the comparisons: unpolarized, diamond at 589.3 nm.
fn opts(light: Light, size: usize, tilt: Tilt) -> RenderOptions {
    RenderOptions {
        size,
        tilt,
        ..RenderOptions::new(light)
    }
    .polarized(false)
}
