//! Parsing of flag values shared by the subcommands; every error is one line naming the flag
//! and what is allowed.

use facetlab::error::{Error, Result, Setting};
use facetlab::metrics::{CrystalChoice, NoteKind, StoneChoice, StoneFields};
use facetlab::optics::{
    ColourFields, CrystalFields, Material, MaterialFields, OpticAxis, StoneSize, DENSITY_MAX,
};
use facetlab::sweep::{Shard, SweepScore};

pub use facetlab::io::text::{count, number};
pub use facetlab::metrics::stones::on_off;

/// The flag a user types for each of the library's settings ([`Setting`], named by the field
/// its errors give): the library speaks of a `trace depth`, the command line of `--depth`. A
/// `match` with no wildcard: a setting the library adds without a flag here does not compile.
/// Every error leaving a command passes through [`to_flags`].
pub const fn flag(s: Setting) -> &'static str {
    match s {
        Setting::LightAngle => "--angle",
        Setting::PhotonCount => "--photons",
        Setting::TraceDepth => "--depth",
        Setting::AbsorptionModel => "--absorption",
        Setting::FixedWavelength => "--spectrum",
        Setting::RefractiveIndex => "--ri",
        Setting::Material => "--material",
        Setting::RoughSize => "--size-mm",
        Setting::InclusionMesh => "--inclusion",
        Setting::SweepScore => "--score",
        Setting::SweepYAxis => "--y",
        Setting::SweepGrid => "--x/--y",
        Setting::RunFolder => "--run",
        Setting::FirstAxis => "--x",
        Setting::GridAxes => "--axis",
        Setting::SlicePoint => "--at",
        Setting::MapAxes => "--map",
        Setting::ShardFolder => "--out",
        Setting::Shard => "--shard",
        Setting::BatchOutput => "--jsonl",
        Setting::ScoreDocument => "--json",
        Setting::Output => "-o",
        Setting::JsonOutput => "--json",
        Setting::HdrOutput => "--hdr-out",
        Setting::PlotsFolder => "--plots",
        Setting::Force => "--force",
        Setting::PictureRock => "--rock",
        Setting::PictureTurn => "--turn",
        Setting::CutParameter => "--set",
        Setting::PictureLight => "--light",
        Setting::PictureSize => "--size",
        Setting::PictureTilt => "--tilt",
        Setting::PictureHeadShadow => "--head-shadow",
        Setting::PictureExposure => "--exposure",
        Setting::PictureView => "--view",
        Setting::PictureDistance => "--distance",
        Setting::PictureAperture => "--aperture",
        Setting::PictureGround => "--ground",
        Setting::PictureGroundGap => "--ground-gap",
        Setting::PictureLightRotation => "--light-rotation",
        Setting::PictureTone => "--tone",
        Setting::PictureBands => "--bands",
        Setting::PictureDiameter => "--diameter-mm",
    }
}

/// The flag that sets the library's setting `name` ([`flag`]).
pub fn flag_of(name: &str) -> Option<&'static str> {
    Setting::from_name(name).map(flag)
}

/// Settings the library names inside its text that the command line gives by a whole
/// command rather than a flag.
const COMMANDS: &[(&str, &str)] = &[(
    facetlab::optimize::MEETS_LISTING,
    "`facetlab info DESIGN --meets`",
)];

/// How the command line spells the setting `name` named inside a message or note
/// ([`facetlab::error::setting`]): its flag ([`flag`]), or the command that gives it.
pub fn spelling(name: &str) -> Option<String> {
    flag_of(name)
        .or_else(|| COMMANDS.iter().find(|(n, _)| *n == name).map(|(_, c)| *c))
        .map(String::from)
}

/// `text` (a note, a report) with the settings named inside it spelled as the command line
/// spells them ([`spelling`]).
pub fn spelled(text: &str) -> String {
    facetlab::error::spell_settings(text, &spelling)
}

/// `e` as the command line says it: a field the library names by its setting ([`flag`])
/// named by its flag instead (and so every setting its message names,
/// [`facetlab::error::setting`]), also behind a context the library put in front (`stone: trace
/// depth`) when the name is one of the library's phrases (several words: a config key, one
/// word, is never taken for a setting).
pub fn to_flags(e: Error) -> Error {
    let flagged = |field: String| -> String {
        if let Some(f) = flag_of(&field) {
            return f.to_string();
        }
        if let Some((ctx, name)) = field.rsplit_once(": ") {
            if name.contains(' ') {
                if let Some(f) = flag_of(name) {
                    return format!("{ctx}: {f}");
                }
            }
        }
        field
    };
    // The settings named inside the message, spelled as flags too.
    let e = e.spell_settings(&spelling);
    match e {
        Error::Invalid { field, message } => Error::Invalid {
            field: flagged(field),
            message,
        },
        Error::Parse { source, message } => Error::Parse {
            source: flagged(source),
            message,
        },
        other => other,
    }
}

/// `e` from a picture's `validate` (render's and photo's options) as the command line says it:
/// its field, one of the picture's own words (`view`, `distance`), looked up in [`flag`] as
/// `picture FIELD`; its material by the setting `material` names ([`MaterialArgs::setting`]).
/// A field no flag sets (the tile, the ground's cells) stays as the library names it.
pub fn picture_to_flags(e: Error, material: &MaterialArgs) -> Error {
    match e {
        Error::Invalid { field, message } => {
            let setting = if field == "material" {
                material.setting().to_string()
            } else {
                format!("picture {field}")
            };
            let field = if flag_of(&setting).is_some() {
                setting
            } else {
                field
            };
            to_flags(Error::Invalid { field, message })
        }
        other => other,
    }
}

/// `--shard` of `score --batch` and `sweep`: a share of the work, or `off` (a job array's
/// environment ignored).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShardFlag {
    /// `off`: all the work, whatever the environment.
    Off,
    /// `K/N`.
    Given(Shard),
}

/// The value parser of `--shard`: `off` or K/N ([`Shard::parse`]'s words and error line).
pub fn shard(s: &str) -> Result<ShardFlag> {
    match s {
        "off" => Ok(ShardFlag::Off),
        s => Shard::parse("--shard", s).map(ShardFlag::Given),
    }
}

/// The value parser of an on/off flag: [`on_off`]'s words, its error line naming `flag`.
pub fn on_off_parser(
    flag: &'static str,
) -> impl Fn(&str) -> Result<bool> + Clone + Send + Sync + 'static {
    move |s| on_off(flag, s)
}

/// The value parser of a flag read by a library parser that names its field (`parse_tilt`,
/// `Tone::parse`, …): its error line names `flag`, as the hand check's did.
pub fn parsed<T: 'static>(
    flag: &'static str,
    parse: fn(&str, &str) -> Result<T>,
) -> impl Fn(&str) -> Result<T> + Clone + Send + Sync + 'static {
    move |s| parse(flag, s)
}

/// The value parser of `trace --seed`: any whole number from 0.
pub fn seed(s: &str) -> Result<u64> {
    count("--seed", s, 0, u64::MAX)
}

/// The value parser of a whole-number flag in `lo..=hi` ([`count`]'s words and error line).
pub fn whole(
    flag: &'static str,
    lo: u64,
    hi: u64,
) -> impl Fn(&str) -> Result<u64> + Clone + Send + Sync + 'static {
    move |s| count(flag, s, lo, hi)
}

/// The value parser of a number flag in `[lo, hi]`, `what` it is ([`number`]'s words and
/// error line).
pub fn real(
    flag: &'static str,
    lo: f64,
    hi: f64,
    what: &'static str,
) -> impl Fn(&str) -> Result<f64> + Clone + Send + Sync + 'static {
    move |s| number(flag, s, lo, hi, what)
}

/// The value parser of a number flag whose range the library checks: its error line names
/// `flag` and says what to give (`what`) when the value is not a number.
pub fn a_number(
    flag: &'static str,
    what: impl Into<String>,
) -> impl Fn(&str) -> Result<f64> + Clone + Send + Sync + 'static {
    let what: String = what.into();
    move |s| {
        s.trim()
            .parse::<f64>()
            .map_err(|_| Error::invalid(flag, format!("`{s}` is not a number; {what}")))
    }
}

/// The value parser of `--score` (`sweep`, `merge`): [`SweepScore::parse`], its error named
/// by the flag.
pub fn sweep_score(s: &str) -> Result<SweepScore> {
    SweepScore::parse(s).map_err(to_flags)
}

/// The error line of a flag a value parser refused ([`on_off_parser`], …): the library's
/// error as it is printed after parsing, so a typed flag refuses with the line its hand check
/// gave. `None` for clap's own errors.
pub fn refused_value(e: &clap::Error) -> Option<String> {
    use std::error::Error as _;
    if e.kind() != clap::error::ErrorKind::ValueValidation {
        return None;
    }
    e.source()
        .and_then(|s| s.downcast_ref::<Error>())
        .map(|inner| to_flags(inner.clone()).to_string())
}

/// `--material` and `--ri`, shared by the commands that trace (`score`, `render`, `report`,
/// `trace`).
#[derive(Clone, Debug, Default, clap::Args)]
pub struct MaterialArgs {
    /// Material: diamond (default), a name from `facetlab materials`, or ri:N[:BG].
    #[arg(long, value_name = "NAME")]
    // A String on purpose: --ri over --material (both refused first, then the one given).
    pub material: Option<String>,
    /// A fixed refractive index instead of the material's dispersion curve (no fire).
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = a_number("--ri", "give a refractive index"))]
    pub ri: Option<f64>,
}

impl MaterialArgs {
    /// The material the flags name ([`material`]).
    pub fn material(&self) -> Result<Material> {
        material(self.ri, self.material.as_deref())
    }

    /// Whether the user chose a material (else a design is traced in its own).
    pub fn chosen(&self) -> bool {
        self.ri.is_some() || self.material.is_some()
    }

    /// The setting that chose it, as [`flag`] names it: `refractive index` (`--ri`) over
    /// `material` (`--material`).
    pub fn setting(&self) -> &'static str {
        if self.ri.is_some() {
            "refractive index"
        } else {
            "material"
        }
    }
}

/// `--head-shadow DEG`, shared by the commands that score (`score`, `report`, `retarget`):
/// the viewer's head shadow of the scores ([`ScoreConfig::head_shadow_deg`]).
///
/// [`ScoreConfig::head_shadow_deg`]: facetlab::metrics::ScoreConfig::head_shadow_deg
#[derive(Clone, Debug, clap::Args)]
pub struct HeadShadowArgs {
    /// Half-angle in degrees of the viewer's head shadow around the line of sight, darkening
    /// the skies and spot lights of the scores as the viewer's head does (default 15; 0 =
    /// none, the open-sky scores of earlier versions).
    #[arg(
        long,
        default_value = "15",
        value_name = "DEG",
        allow_hyphen_values = true,
        value_parser = real("--head-shadow", 0.0, 60.0, "a half-angle in degrees (0 = none)")
    )]
    pub head_shadow: f64,
}

/// `--colour`, `--colour-density`, `--diameter-mm` and `--size-mm`, shared by `score` and
/// `render`: a body colour and the stone's size (absorption depends on the path in mm).
#[derive(Clone, Debug, Default, clap::Args)]
pub struct ColourArgs {
    /// The stone's colour seen through a path under D65: #rrggbb[@Nmm] or lab(L,a,b)[@Nmm]
    /// (default path 10 mm), upsampled to a smooth absorption spectrum; replaces a coloured
    /// variety's.
    #[arg(long, value_name = "COLOUR")]
    // A String on purpose: checked against the stone's own colour, after the notes said first.
    pub colour: Option<String>,
    /// A factor on the body colour's absorption (0.5 paler, 2 darker).
    #[arg(long, value_name = "X", allow_hyphen_values = true, value_parser = a_number("--colour-density", format!("give a factor on the absorption in (0, {DENSITY_MAX}]")))]
    pub colour_density: Option<f64>,
    /// The stone's width W in millimetres, for its body colour (default 6.5).
    #[arg(
        long,
        value_name = "MM",
        conflicts_with = "size_mm",
        allow_hyphen_values = true,
        value_parser = a_number("--diameter-mm", "give a width in (0, 1000) mm")
    )]
    pub diameter_mm: Option<f64>,
    /// The stone's size in millimetres instead: its length L (the width follows from the
    /// design's L/W), or LxW.
    #[arg(long, value_name = "L[xW]", value_parser = parsed("--size-mm", size_mm))]
    pub size_mm: Option<StoneSize>,
}

/// The value parser of a `--material` that stands alone (no `--ri` beside it):
/// [`Material::by_name`], whose errors name the `material`.
pub fn material_name(_flag: &str, name: &str) -> Result<Material> {
    Material::by_name(name)
}

/// The value parser of `--size-mm`: a length L or LxW in mm ([`StoneSize::parse_length`]).
pub fn size_mm(flag: &str, text: &str) -> Result<StoneSize> {
    StoneSize::parse_length(text, flag)
}

impl ColourArgs {
    /// The stone's size from `--diameter-mm` or `--size-mm` (default a width of 6.5 mm).
    pub fn size(&self) -> Result<StoneSize> {
        match (self.diameter_mm, self.size_mm) {
            (Some(w), _) => StoneSize::width(w, "--diameter-mm"),
            (None, Some(l)) => Ok(l),
            (None, None) => Ok(StoneSize::default()),
        }
    }
}

/// The value parser of `--optic-axis` ([`OpticAxis::parse`], its error naming `field`).
fn optic_axis(field: &str, s: &str) -> Result<OpticAxis> {
    OpticAxis::parse(s, field)
}

/// `--birefringence`, `--optic-axis` and `--colour-e`, shared by the commands that trace:
/// how a uniaxial stone is traced ([`Material::choose_crystal`]).
#[derive(Clone, Debug, Default, clap::Args)]
pub struct CrystalArgs {
    /// Trace a uniaxial stone (sapphire, quartz, tourmaline, …) birefringent: on (the
    /// default for those stones) or off (its ordinary ray alone).
    #[arg(long, value_name = "on|off", action = clap::ArgAction::Set, value_parser = on_off_parser("--birefringence"))]
    pub birefringence: Option<bool>,
    /// The optic (c-)axis of a uniaxial stone: DEG[@AZ], its angle from the table's normal
    /// toward azimuth AZ (0 = c ⟂ table; 90@0 = c in the table along azimuth 0). Default: as
    /// cutters orient the material.
    #[arg(long, value_name = "DEG[@AZ]", allow_hyphen_values = true, value_parser = parsed("--optic-axis", optic_axis))]
    pub optic_axis: Option<OpticAxis>,
    /// A uniaxial stone's colour for light polarized ∥ its optic axis (the e-ray):
    /// #rrggbb[@Nmm] or lab(L,a,b)[@Nmm] (default path 10 mm); the stone's body colour (a
    /// coloured variety's, or --colour's where the command takes it) is then its E⊥c (o-ray)
    /// colour.
    #[arg(long, value_name = "COLOUR")]
    // A String on purpose: checked for each stone (a crystal or not), after its notes.
    pub colour_e: Option<String>,
}

impl CrystalArgs {
    /// The crystal settings these flags give, a birefringent stone's note at `wavelength_nm`.
    pub fn choice(&self, wavelength_nm: f64) -> CrystalChoice {
        CrystalChoice {
            birefringence: self.birefringence,
            optic_axis: self.optic_axis,
            colour_e: self.colour_e.clone(),
            wavelength_nm,
        }
    }
}

/// Where the command line takes a stone's settings: its flags.
pub const STONE_FIELDS: StoneFields<'static> = StoneFields {
    colour: ColourFields {
        colour: "--colour",
        density: "--colour-density",
    },
    crystal: CrystalFields {
        birefringence: "--birefringence",
        optic_axis: "--optic-axis",
        colour_e: "--colour-e",
    },
    width: "--diameter-mm",
    length: "--size-mm",
    overrides: "--material or --ri overrides",
};

/// The stones' choice from the material and colour flags: `material` (the material flags',
/// [`MaterialArgs::material`]) with its body colour chosen, the size from `--diameter-mm` or
/// `--size-mm`; `crystal` the crystal settings, if the command applies them.
pub fn stone_choice(
    material: Material,
    m: &MaterialArgs,
    c: &ColourArgs,
    crystal: Option<CrystalChoice>,
) -> Result<StoneChoice> {
    let mut choice = StoneChoice::new(
        material,
        m.chosen(),
        c.colour.clone(),
        c.colour_density,
        STONE_FIELDS.colour,
    )?;
    choice.size = c.size()?;
    choice.size_is_length = c.size_mm.is_some();
    choice.crystal = crystal;
    Ok(choice)
}

/// A stone's note, said on stderr.
pub fn say(_: NoteKind, line: String) {
    eprintln!("{}", spelled(&line));
}

/// The material from `--ri N` or `--material NAME` (diamond when neither is given), chosen by
/// [`Material::choose`] like a config's `score.material`/`score.ri`.
pub fn material(ri: Option<f64>, name: Option<&str>) -> Result<Material> {
    Material::choose(
        name,
        ri,
        MaterialFields {
            material: "--material",
            ri: "--ri",
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_setting_named_inside_a_message_is_spelled_as_its_flag() {
        let e = facetlab::plan::load_rough("octahedron", None).unwrap_err();
        assert_eq!(
            e.to_string(),
            "rough size: the crystal form `octahedron` needs rough size L (its largest extent in mm)"
        );
        assert_eq!(
            to_flags(e).to_string(),
            "--size-mm: the crystal form `octahedron` needs --size-mm L (its largest extent in mm)"
        );
        let env = |v: &str| (v == "SLURM_ARRAY_TASK_ID").then(|| "2".to_string());
        let e = to_flags(Shard::from_env(&env).unwrap_err()).to_string();
        assert!(e.ends_with("give --shard K/N"), "{e}");
    }

    #[test]
    fn each_setting_names_one_flag_the_command_line_has() {
        use clap::CommandFactory;
        let cmd = crate::cli::Cli::command();
        let args = || cmd.get_subcommands().flat_map(|s| s.get_arguments());
        let longs: std::collections::BTreeSet<String> = args()
            .filter_map(|a| a.get_long())
            .map(|l| format!("--{l}"))
            .chain(
                args()
                    .filter_map(|a| a.get_short())
                    .map(|c| format!("-{c}")),
            )
            .collect();
        for &s in Setting::ALL {
            let name = s.name();
            for f in flag(s).split('/') {
                assert!(longs.contains(f), "{name}: {f} is no flag of any command");
            }
        }
    }

    #[test]
    fn errors_leave_the_binary_named_by_flags() {
        let shown = |field: &str| to_flags(Error::invalid(field, "m")).to_string();
        assert_eq!(shown("trace depth"), "--depth: m");
        assert_eq!(shown("sweep grid"), "--x/--y: m");
        assert_eq!(shown("material"), "--material: m");
        // Behind a context the library puts in front (a stone's name).
        assert_eq!(shown("round: absorption model"), "round: --absorption: m");
        // A config's key is one word: never taken for a setting.
        assert_eq!(shown("plan.toml: material"), "plan.toml: material: m");
        assert_eq!(shown("--tilt"), "--tilt: m");
        assert_eq!(
            to_flags(Error::parse("photon count", "m")).to_string(),
            "--photons: m"
        );
        // The library's checks of outputs, their field and the settings in their message.
        let d = tempfile::tempdir().unwrap();
        let old = d.path().join("old.png");
        std::fs::write(&old, "x").unwrap();
        let e = facetlab::io::guard::PictureFiles {
            picture: &old,
            json: Some(&old),
            hdr: None,
        }
        .check_laboratory(&[], true)
        .unwrap_err();
        assert_eq!(
            to_flags(e).to_string(),
            format!(
                "--json: {} is also the -o picture; give another file",
                old.display()
            )
        );
        let e = facetlab::io::guard::check_new_file("hdr output", &old, false).unwrap_err();
        assert_eq!(
            to_flags(e).to_string(),
            format!(
                "--hdr-out: {} exists; pass --force to replace it, or choose another name",
                old.display()
            )
        );
    }

    #[test]
    fn a_pictures_settings_leave_named_by_flags() {
        let material = MaterialArgs::default();
        let ri = MaterialArgs {
            ri: Some(2.4),
            ..MaterialArgs::default()
        };
        let shown = |field: &str, m: &MaterialArgs| {
            picture_to_flags(Error::invalid(field, "m"), m).to_string()
        };
        for (field, flag) in [
            ("size", "--size"),
            ("tilt", "--tilt"),
            ("head-shadow", "--head-shadow"),
            ("bands", "--bands"),
            ("view", "--view"),
            ("ground-gap", "--ground-gap"),
            ("light-rotation", "--light-rotation"),
            ("distance", "--distance"),
            ("diameter-mm", "--diameter-mm"),
        ] {
            assert_eq!(shown(field, &material), format!("{flag}: m"));
        }
        assert_eq!(shown("material", &material), "--material: m");
        assert_eq!(shown("material", &ri), "--ri: m");
        // No flag sets the tile: named as the library names it.
        assert_eq!(shown("tile", &material), "tile: m");
        // A setting's bare word elsewhere (the score's bands) is not a picture's.
        assert_eq!(
            to_flags(Error::invalid("bands", "m")).to_string(),
            "bands: m"
        );
    }

    #[test]
    fn a_designs_index_follows_the_rule_of_ri() {
        use facetlab::io::asc::{RI_ABOVE, RI_MAX};
        assert_eq!((RI_ABOVE, RI_MAX), (Material::RI_ABOVE, Material::RI_MAX));
    }

    #[test]
    fn flags_parse_or_name_the_flag() {
        assert_eq!(count("--photons", "2e7", 1, u64::MAX).unwrap(), 20_000_000);
        assert_eq!(
            count("--photons", "20_000_000", 1, u64::MAX).unwrap(),
            20_000_000
        );
        assert!(count("--photons", "1.5", 1, 10)
            .unwrap_err()
            .to_string()
            .starts_with("--photons:"));
        assert!(count("--photons", "0", 1, 10).is_err());
        // 2^64 is one past the largest seed, not the largest seed.
        assert_eq!(seed("18446744073709551615").unwrap(), u64::MAX);
        assert!(seed("18446744073709551616").is_err() && seed("1.8446744073709552e19").is_err());
        assert!(seed("-1").is_err());
        assert_eq!(
            number("--angle", " 30 ", 0.0, 180.0, "an angle").unwrap(),
            30.0
        );
        assert!(number("--angle", "NaN", 0.0, 180.0, "an angle").is_err());
        assert!(
            !on_off("--polarization", "OFF").unwrap() && on_off("--polarization", "yes").unwrap()
        );
        assert!(on_off("--polarization", "maybe")
            .unwrap_err()
            .to_string()
            .contains("on or off"));
        assert_eq!(material(Some(2.0), None).unwrap().ri(500.0), 2.0);
        assert!(material(Some(2.0), Some("cz")).is_err());
        assert!(material(Some(0.9), None)
            .unwrap_err()
            .to_string()
            .starts_with("--ri:"));
        assert_eq!(material(None, Some("cz")).unwrap().name, "cubic-zirconia");
    }

    #[test]
    fn flag_and_config_accept_the_same_indices() {
        // `--ri`'s value parser, then the material it chooses.
        let ri_flag = a_number("--ri", "give a refractive index");
        let config = |ri: &str| {
            let text = format!(
                "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30, 38]\n[score]\nri = {ri}\n"
            );
            facetlab::optimize::Config::from_str(&text, "c.toml").map(|c| c.score.material)
        };
        for ri in [
            "0.5", "1", "1.00001", "1.0001", "2.4", "10", "10.0001", "11", "nan", "inf",
        ] {
            let flag = ri_flag(ri).and_then(|n| material(Some(n), None));
            let conf = config(ri);
            assert_eq!(flag.is_ok(), conf.is_ok(), "{ri}: {flag:?} vs {conf:?}");
            match (flag, conf) {
                (Ok(a), Ok(b)) => assert_eq!(a, b, "{ri}"),
                (Err(a), Err(b)) => {
                    let (a, b) = (a.to_string(), b.to_string());
                    assert!(a.starts_with("--ri: "), "{a}");
                    assert!(b.starts_with("c.toml: score.ri: "), "{b}");
                    assert_eq!(
                        a.split_once(": ").unwrap().1,
                        b.split_once("score.ri: ").unwrap().1
                    );
                }
                _ => unreachable!(),
            }
        }
        let e = ri_flag("abc").unwrap_err().to_string();
        assert!(e.starts_with("--ri: `abc` is not a number"), "{e}");
    }

    /// The materials and the stderr lines of `cuts` under `default` (`chosen`: the user chose
    /// it) and the colour flags `c`.
    fn stones_of(
        cuts: &[facetlab::cut::Cut],
        default: Material,
        chosen: bool,
        c: &ColourArgs,
        notes: facetlab::metrics::ColourNotes,
    ) -> Result<(Vec<Material>, Vec<String>)> {
        let m = MaterialArgs {
            material: chosen.then(|| default.name.clone()),
            ri: None,
        };
        let choice = stone_choice(default, &m, c, None)?;
        let mut lines = Vec::new();
        let s = choice.stones(cuts, &STONE_FIELDS, notes, &mut |_, l| lines.push(l))?;
        Ok((s.materials, lines))
    }

    #[test]
    fn design_index_is_mentioned_only_when_it_differs_and_nothing_was_chosen() {
        use facetlab::metrics::ColourNotes::Traced;
        let mut quartz = facetlab::io::load_cut("tolkowsky").unwrap();
        quartz.record = Some(facetlab::cut::GemcadRecord {
            ri: Some(1.54),
            ..Default::default()
        });
        let mut dia = quartz.clone();
        dia.record = Some(facetlab::cut::GemcadRecord {
            ri: Some(2.418),
            ..Default::default()
        });
        let plain = facetlab::io::load_cut("gia-reference").unwrap();
        let cuts = [quartz, dia, plain];
        let none = ColourArgs::default();
        let (m, notes) = stones_of(&cuts, Material::diamond(), false, &none, Traced).unwrap();
        let names: Vec<&str> = m.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["quartz", "diamond", "diamond"]);
        assert_eq!(notes.len(), 2, "{notes:?}");
        assert!(notes[0].contains("traced as quartz (the design's index 1.54)"));
        assert!(
            notes[0].ends_with("; --material or --ri overrides"),
            "{notes:?}"
        );
        let (m, notes) = stones_of(&cuts, Material::cubic_zirconia(), true, &none, Traced).unwrap();
        assert!(notes.is_empty() && m.iter().all(|m| m.name == "cubic-zirconia"));
    }

    #[test]
    fn a_design_note_names_a_coloured_material_and_colour_flags_apply() {
        use facetlab::metrics::ColourNotes::{NotTraced, Traced};
        let mut cut = facetlab::io::load_cut("tolkowsky").unwrap();
        cut.record = Some(facetlab::cut::GemcadRecord {
            ri: Some(1.54),
            footnotes: vec!["Material: amethyst".into()],
            ..Default::default()
        });
        let cuts = [cut];
        let none = ColourArgs::default();
        let (m, notes) = stones_of(&cuts, Material::diamond(), false, &none, Traced).unwrap();
        assert_eq!(m[0].name, "amethyst");
        assert!(m[0].colour.is_some());
        assert!(
            notes[1].contains("traced as amethyst (the design's notes)"),
            "{notes:?}"
        );
        // A chosen material wins over the note.
        let (m, _) = stones_of(&cuts, Material::diamond(), true, &none, Traced).unwrap();
        assert_eq!(m[0].name, "diamond");
        // The colour flags: a user colour colours the design's material; a density scales
        // what is there (and is refused with nothing to scale); the note for stderr names
        // the width.
        let args = ColourArgs {
            colour: None,
            colour_density: Some(2.0),
            diameter_mm: Some(8.0),
            size_mm: None,
        };
        let e = stones_of(&cuts, Material::diamond(), true, &args, Traced)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--colour-density: there is no colour"), "{e}");
        let args = ColourArgs {
            colour: Some("#2e8b57@10mm".into()),
            ..args
        };
        let (m, notes) = stones_of(&cuts, Material::diamond(), true, &args, NotTraced).unwrap();
        assert_eq!(m[0].colour.as_ref().unwrap().density, 2.0);
        assert!(notes[0].contains("stone width 8 mm") && notes[0].contains("not yet traced"));
        // The note names the trace's absorption setting; said, it is spelled as its flag.
        assert!(spelled(&notes[0]).contains("(give --absorption colour)"));
        assert!(spelled(&facetlab::document::info::info_text(
            &facetlab::document::info::info_json(
                &facetlab::io::load_cut("tolkowsky").unwrap(),
                6.5,
                &Material::diamond()
            )
        ))
        .contains("Parameters (--set KEY=VALUE)"));
        let bad = a_number("--diameter-mm", "give a width in (0, 1000) mm")("wide");
        assert!(bad
            .unwrap_err()
            .to_string()
            .starts_with("--diameter-mm: `wide`"));
        let bad = <ColourArgs as clap::Args>::augment_args(clap::Command::new("t"))
            .try_get_matches_from(["t", "--colour-density", "dark"])
            .unwrap_err();
        assert_eq!(
            refused_value(&bad).unwrap(),
            "--colour-density: `dark` is not a number; give a factor on the absorption in (0, 100]"
        );
    }
}
