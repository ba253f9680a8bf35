//! A recipe: a design written as a faceter cuts it, tier by tier ("cut to meet").
//!
//! A [`Recipe`] is an ordered list of [`RecipeTier`]s on an index gear with a symmetry. Each
//! tier has an angle (a number, or an expression of earlier tiers' angles such as `=P1-2`),
//! indices on the gear (expanded by the design's symmetry and mirror, as a faceting machine's
//! symmetry cuts a whole tier from one facet), and a [`Place`]: how deep it is cut —
//!
//! - [`Place::Meet`]: until it reaches the vertex where the named tiers meet (a tier named
//!   twice asks for a vertex on two of its facets);
//! - [`Place::Centre`]: to the point where the stone cut so far meets its axis on the tier's
//!   side (the first tier cut to centre sets the scale: its point is one unit from the girdle
//!   plane);
//! - [`Place::Depth`] / [`Place::Scale`]: at a distance from the axis point (GemCad's
//!   distance, in the recipe's units; `scale` is a depth that marks the tier anchoring the
//!   size);
//! - [`Place::Girdle`]: a crown or pavilion tier leaving a girdle of that thickness (a
//!   fraction of the width) above (below) the other side's highest (lowest) point on the girdle;
//! - [`Place::Table`]: a flat crown tier cut down until the table is that fraction of the width.
//!
//! [`Recipe::build`] cuts the tiers in order from a block and returns the cut (scaled to width
//! 1 like every import), one [`Step`] per tier (what to do at the machine) and the
//! [`Finding`]s a faceter should hear about (facets under 1 % of the width, pavilion tiers
//! below the critical angle). What cannot be cut is an error naming the tier: a tier that never
//! touches the stone or is cut away by a later one, a meet whose tiers do not meet, an index off
//! the gear, a stone left open (no tier closes a side), a first tier with nothing to anchor it;
//! with the fix where one is obvious. [`infer`] writes a recipe for any design (each tier's meet
//! from the vertices it passes through), and building it gives the same solid.
//!
//! The TOML form of a recipe is read and written by [`crate::io::recipe`].
//!
//! ```
//! use facetlab::design::recipe::{Place, Recipe, RecipeTier};
//!
//! // A simple round: mains to the centre point, a level girdle, crown mains leaving a girdle,
//! // a table of 55 % of the width.
//! let mut r = Recipe::new("simple", 96, 8, true, 1.54);
//! r.add(RecipeTier::new("P1", -42.0, &[96.0], Place::Centre));
//! r.add(RecipeTier::new("G1", 90.0, &[96.0], Place::Depth(0.9)));
//! r.add(RecipeTier::new("C1", 38.0, &[96.0], Place::Girdle(0.03)));
//! r.add(RecipeTier::new("T", 0.0, &[], Place::Table(0.55)));
//! let built = r.build().unwrap();
//! assert_eq!(built.cut.solid.facets().len(), 8 + 8 + 8 + 1);
//! assert_eq!(built.steps[0].instruction, "cut to centre point");
//! let t = built.cut.ratios();
//! assert!((t.t_w - 0.55).abs() < 1e-9, "{t:?}");
//! ```

mod build;
mod expr;
mod finish;
mod index;
mod infer;
mod place;
mod space;
#[cfg(test)]
mod tests;

pub use build::{Built, Finding, FindingKind, Step};
pub use expr::eval_angle;
pub use index::{parse_indices, symmetric_indices};
pub use infer::{infer, Inferred};
pub use space::RecipeSpace;

/// Where a tier is cut: see the module documentation.
#[derive(Clone, Debug, PartialEq)]
pub enum Place {
    /// Until it reaches the vertex where these tiers meet (a name twice: two of its facets).
    Meet(Vec<String>),
    /// To the centre point: where the stone cut so far meets its axis on this tier's side.
    Centre,
    /// At this distance from the axis point, in the recipe's units.
    Depth(f64),
    /// A depth that anchors the design's size (built as [`Place::Depth`]).
    Scale(f64),
    /// Leaving a girdle this thick (a fraction of the width) against the other side.
    Girdle(f64),
    /// A flat crown tier cut until the table is this fraction of the width.
    Table(f64),
}

/// A tier's angle: a number of degrees, or an expression of earlier tiers' angles.
#[derive(Clone, Debug, PartialEq)]
pub enum Angle {
    /// Degrees from the girdle plane; negative: a pavilion tier (GemCad's sign).
    Degrees(f64),
    /// An expression such as `=P1-2` or `=(C1+C2)/2`, of the tilts (angles without sign) of
    /// tiers cut before; the tier takes the side of its `side`, else of the first tier named.
    Expr(String),
}

/// The side of the stone a tier is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// Above the girdle (the table is a crown tier at 0°).
    Crown,
    /// Below the girdle (a culet is a pavilion tier at 0°).
    Pavilion,
}

impl Side {
    /// `crown` or `pavilion`.
    pub fn name(self) -> &'static str {
        match self {
            Side::Crown => "crown",
            Side::Pavilion => "pavilion",
        }
    }
}

/// One tier as it is cut.
#[derive(Clone, Debug, PartialEq)]
pub struct RecipeTier {
    /// The tier's name (GemCad's: one word, usually ≤ 3 characters: `P1`, `G1`, `C2`, `T`).
    pub name: String,
    /// Its angle.
    pub angle: Angle,
    /// Its side when the angle does not say (a culet at 0°, an expression).
    pub side: Option<Side>,
    /// Indices on the gear as written; the design's symmetry adds the rest. Empty for a flat
    /// tier (table or culet), which has one facet whatever its indices.
    pub indices: Vec<f64>,
    /// How deep it is cut.
    pub place: Place,
    /// A note printed with the tier's instruction (GemCad's `G` text), if any.
    pub note: Option<String>,
}

impl RecipeTier {
    /// A tier at `angle` degrees (negative: pavilion) on `indices`, placed by `place`.
    pub fn new(name: &str, angle: f64, indices: &[f64], place: Place) -> RecipeTier {
        RecipeTier {
            name: name.to_string(),
            angle: Angle::Degrees(angle),
            side: None,
            indices: indices.to_vec(),
            place,
            note: None,
        }
    }
}

/// A design as an ordered list of tiers on a gear; see the module documentation.
#[derive(Clone, Debug, PartialEq)]
pub struct Recipe {
    /// The design's name (its title).
    pub name: String,
    /// Teeth of the index gear.
    pub gear: u32,
    /// Gear offset: the index at 6 o'clock in the top view.
    pub offset: f64,
    /// Rotational symmetry (fold count); a divisor of the gear.
    pub symmetry: u32,
    /// Mirror symmetry about the line through the offset index.
    pub mirror: bool,
    /// The refractive index the angles are meant for (GemCad's `I`; the critical angle).
    pub index: f64,
    /// Whether indices may fall between the gear's teeth (a design computed rather than cut
    /// on a gear, or a machine with a cheater); off, such an index is an error.
    pub fractional: bool,
    /// Further title and credit lines.
    pub title: Vec<String>,
    /// Footnotes.
    pub notes: Vec<String>,
    /// The tiers in cutting order.
    pub tiers: Vec<RecipeTier>,
}

/// GemCad's index for a new design: quartz, 1.54.
pub const DEFAULT_INDEX: f64 = 1.54;

/// The smallest facet a faceter can cut and see, as a fraction of the width.
pub const SMALL_FACET: f64 = 0.01;

impl Recipe {
    /// An empty recipe on a gear of `gear` teeth (offset 0) with `symmetry`-fold symmetry,
    /// mirrored or not, for the refractive index `index`.
    pub fn new(name: &str, gear: u32, symmetry: u32, mirror: bool, index: f64) -> Recipe {
        Recipe {
            name: name.to_string(),
            gear,
            offset: 0.0,
            symmetry,
            mirror,
            index,
            fractional: false,
            title: Vec::new(),
            notes: Vec::new(),
            tiers: Vec::new(),
        }
    }

    /// Add a tier at the end (cut last).
    pub fn add(&mut self, tier: RecipeTier) -> &mut Recipe {
        self.tiers.push(tier);
        self
    }

    /// The position of the tier named `name`.
    pub fn position(&self, name: &str) -> Option<usize> {
        self.tiers.iter().position(|t| t.name == name)
    }
}
