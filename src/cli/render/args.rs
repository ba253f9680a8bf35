//! The flags of `facetlab render`.

use super::photo;
use crate::cli::flags;
use facetlab::render::pose::{parse_rock, parse_tilt};
use facetlab::render::settings::{self as picture, LightChoice};
use facetlab::render::Tilt;
use std::path::PathBuf;
use std::sync::LazyLock;

/// `--light`'s values, from the library's table ([`facetlab::render::lights`]).
static LIGHT_VALUES: LazyLock<String> = LazyLock::new(facetlab::render::lights::values);
/// `--light`'s help, from the same table.
static LIGHT_HELP: LazyLock<String> = LazyLock::new(facetlab::render::lights::help);

/// Flags of `facetlab render`.
#[derive(clap::Args, Debug, Clone)]
pub struct RenderArgs {
    /// Cuts to draw side by side: preset names (tolkowsky, princess) or .toml/.asc/.gem/.obj/.stl
    /// files.
    #[arg(required = true, value_name = "CUT")]
    pub cuts: Vec<String>,
    // Its values and help come from the library's one table of lights (a new rig adds itself).
    #[arg(
        long,
        default_value = "iso",
        value_name = LIGHT_VALUES.as_str(),
        help = LIGHT_HELP.as_str(),
        value_parser = flags::parsed("--light", LightChoice::parse)
    )]
    // A laboratory light or a photograph's, read once (an env:FILE map with it); its refusal
    // names both lists.
    pub light: LightChoice,
    /// Pixels per side of each stone's picture (8–8192); the captions (and a grey margin)
    /// come outside it unless --bare.
    #[arg(
        long,
        default_value = "512",
        value_name = "PX",
        allow_hyphen_values = true,
        value_parser = flags::parsed("--size", picture::parse_size)
    )]
    pub size: usize,
    /// Tilt the stone DEG degrees (−90 to 90) toward azimuth AZ (degrees from +x, default 0):
    /// `--tilt 10@45`.
    #[arg(long, value_name = "DEG[@AZ]", allow_hyphen_values = true, value_parser = flags::parsed("--tilt", parse_tilt))]
    pub tilt: Option<Tilt>,
    /// Half-angle of the viewer's head shadow, the ASET port, the IdealScope head or the hearts
    /// & arrows viewer's dark tube, degrees (0–60; default 10 for aset and idealscope, 20 for
    /// arrows, 6 for hearts, 0 otherwise).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, value_parser = flags::parsed("--head-shadow", picture::parse_head_shadow))]
    pub head_shadow: Option<f64>,
    #[command(flatten)]
    pub material: flags::MaterialArgs,
    #[command(flatten)]
    pub colour: flags::ColourArgs,
    #[command(flatten)]
    pub crystal: flags::CrystalArgs,
    /// Track polarization (on) or use the unpolarized average (off).
    #[arg(long, default_value = "on", value_name = "on|off", action = clap::ArgAction::Set, value_parser = crate::cli::flags::on_off_parser("--polarization"))]
    pub polarization: bool,
    /// Change a parameter: a family's (`--set crown_angle=34.5`) or a design's tier angle
    /// (`--set P1=41.2`). Repeatable; applied to every CUT.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Animated PNG of the stone rocking: frame k tilted DEG·sin(2πk/FRAMES) more toward the
    /// --tilt azimuth; DEG in (0, 60], FRAMES in 2–240; loops forever.
    #[arg(long, value_name = "DEG:FRAMES", allow_hyphen_values = true, value_parser = flags::parsed("--rock", parse_rock))]
    pub rock: Option<(f64, usize)>,
    /// Brightness factor of the iso, cos, hearts, arrows and fire pictures (0.01–100).
    #[arg(
        long,
        default_value = "1",
        value_name = "X",
        allow_hyphen_values = true,
        value_parser = flags::parsed("--exposure", picture::parse_exposure)
    )]
    pub exposure: f64,
    /// Write the statistics as JSON to this file (keys in docs/commands.md).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Replace -o and --json files that already exist (an input is never replaced).
    #[arg(long)]
    pub force: bool,
    /// The picture to write (.png).
    #[arg(short = 'o', long = "output", value_name = "FILE.png")]
    pub output: PathBuf,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// The stones' pictures alone: no margin, captions or legend (one cut: exactly PX × PX).
    #[arg(long)]
    pub bare: bool,
    #[command(flatten)]
    pub photo: photo::PhotoArgs,
}
