//! `facetlab render CUT... -o FILE.png`: pictures of stones under the lights cutters use, side
//! by side, each captioned with its statistics; `--rock` makes an animated PNG of the stone
//! rocking.
//!
//! ```text
//! facetlab render tolkowsky -o tolkowsky.png                          # ISO, 512 px, face-up
//! facetlab render tolkowsky princess emerald --light aset -o aset.png
//! facetlab render tolkowsky --light fire --tilt 10@45 --size 400 -o fire.png
//! facetlab render tolkowsky --rock 15:24 --json rock.json -o rock.png  # animated PNG
//! facetlab render tolkowsky --size 200 --bare -o stone.png             # 200 × 200, no captions
//! ```
//!
//! Flags are read as text and validated here into [`RenderOptions`], so every bad value ends
//! in a one-line error naming the flag and what is allowed. The pictures, their sheet
//! (panels, captions, legend), the files and the statistics come from one library call,
//! [`facetlab::plot::render::draw`].
//!
//! **JSON** (`--json FILE`, written atomically): one object per cut (an array of them when
//! several cuts are given, in the order given) with `name` (the cut's name), `input` (CUT as
//! given), `light`, `size` (pixels per side), `mean` (the picture's mean over the stone's
//! outline relative to a white diffuser: the pose's brilliance for iso and cos, the returned
//! share for idealscope, luminance for fire), `aset.{blue,red,green,leak,port}` (ASET shares,
//! summing to 1; aset only), `placement_fire` (saturated light in percent under this one
//! placement of the lights, not `score`'s `fire`, which averages 17; fire only), `tilt_deg`,
//! `azimuth_deg` (the pose), `head_shadow_deg` (in use), `material`, `ri` (null unless
//! `--ri`), `polarization`, `exposure`, `cut_off` (share of light below the tracer's
//! thresholds), `exits` (exit beams drawn), `elapsed_s` (rendering time of this cut, all
//! frames), `output` (the PNG written). With `--rock`: `rock_deg` and `frames`, one object per
//! frame with `frame`, `tilt_deg`, `azimuth_deg`, `mean`, `aset`, `placement_fire`, `cut_off`,
//! `exits`, `elapsed_s`; the top-level statistics are frame 0's (the centre of the rock).

mod args;
mod photo;
mod run;
mod settings;

pub use args::RenderArgs;
pub use run::run;
pub use settings::settings;

#[cfg(test)]
mod tests;
