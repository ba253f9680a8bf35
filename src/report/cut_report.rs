//! A cut measured for a report: the report's options, and a cut's scores, pictures and checks
//! ([`measure`]).

use crate::cut::Cut;
use crate::error::Result;
use crate::metrics::{score, ScoreConfig, Scores};
use crate::render::{render, Image, Light, RenderOptions, Tilt};
use crate::verify::{verify_scores, Check};
use rayon::prelude::*;

/// What a report shows and how it is made.
#[derive(Clone, Debug)]
pub struct ReportOptions {
    /// Scoring settings (material, lighting, poses).
    pub score: ScoreConfig,
    /// Pixels per side of the pictures.
    pub size: usize,
    /// Photons for the photon tracer's check; 0 = no check.
    pub verify_photons: u64,
    /// Seed of the check.
    pub seed: u64,
    /// Standard errors beyond which a check is flagged.
    pub sigma: f64,
    /// Title of the page.
    pub title: String,
    /// Tilts, degrees, of the stone's tilt performance: one brightness picture
    /// ([`BRIGHTNESS_LIGHT`]) per tilt, the stone
    /// tipped toward azimuth 0°, and a chart of their light return; empty = none.
    pub tilts: Vec<f64>,
    /// Sections placed above the cuts: a heading and its HTML (made by the caller: text in it
    /// escaped with [`escape`](super::escape)).
    pub sections: Vec<(String, String)>,
}

impl Default for ReportOptions {
    fn default() -> Self {
        ReportOptions {
            score: ScoreConfig::default(),
            size: 320,
            verify_photons: 0,
            seed: 1,
            sigma: 4.0,
            title: "facetlab cut report".into(),
            tilts: Vec::new(),
            sections: Vec::new(),
        }
    }
}

/// Everything a report shows of one cut.
#[derive(Clone, Debug)]
pub struct CutReport {
    /// The cut's label on the page.
    pub label: String,
    /// The cut.
    pub cut: Cut,
    /// Its scores.
    pub scores: Scores,
    /// The photon tracer's checks (empty without a check).
    pub checks: Vec<Check>,
    /// Its pictures: brightness ([`BRIGHTNESS_LIGHT`]), ASET, fire.
    pub pictures: Vec<(Light, Image)>,
    /// Its brightness pictures at [`ReportOptions::tilts`], with their tilt in degrees.
    pub tilted: Vec<(f64, Image)>,
}

/// The light of a report's brightness pictures and its head shadow's half-angle in degrees:
/// GemRay's cosine sky with the viewer's head shadowing 15° around the line of sight (as the
/// gallery's COS pictures), which shows the contrast of the facets' reflections where the even
/// ISO sky is nearly flat. Its captions say so ([`brightness_caption`]).
pub const BRIGHTNESS_LIGHT: (Light, f64) = (Light::Cos, 15.0);

/// What a brightness picture shows, for captions: "COS light, 15° head shadow".
pub fn brightness_caption() -> String {
    format!(
        "{} light, {}° head shadow",
        BRIGHTNESS_LIGHT.0.name().to_uppercase(),
        BRIGHTNESS_LIGHT.1
    )
}

/// Score, draw and (optionally) verify `cut` for a report.
pub fn measure(label: &str, cut: &Cut, o: &ReportOptions) -> Result<CutReport> {
    measure_scored(label, cut, None, o)
}

/// [`measure`], with `cut`'s scores under `o.score` when they are known already (an optimizer
/// run's full evaluations): the cut is then drawn and verified but not scored again.
pub fn measure_scored(
    label: &str,
    cut: &Cut,
    known: Option<Scores>,
    o: &ReportOptions,
) -> Result<CutReport> {
    let picture = |light: Light, tilt_deg: f64| {
        let mut r = RenderOptions::new(light);
        if light == BRIGHTNESS_LIGHT.0 {
            r.head_shadow_deg = Some(BRIGHTNESS_LIGHT.1);
        }
        r.size = o.size;
        r.material = o.score.material.clone();
        r.trace.polarization = o.score.trace.polarization;
        r.tilt = Tilt {
            tilt_deg,
            azimuth_deg: 0.0,
        };
        render(&cut.solid, &r)
    };
    // The face-up pictures, then the brightness pictures of the non-zero tilts (face-up is the
    // brightness picture already made). The score and the pictures are independent: they run side by
    // side, each picture whole (small pictures gain little from their own parallel rows), and
    // are kept in this order, so the report is the same on any thread count.
    let faces = [BRIGHTNESS_LIGHT.0, Light::Aset, Light::Fire];
    let jobs: Vec<(Light, f64)> = faces
        .iter()
        .map(|&l| (l, 0.0))
        .chain(
            o.tilts
                .iter()
                .filter(|&&t| t != 0.0)
                .map(|&t| (BRIGHTNESS_LIGHT.0, t)),
        )
        .collect();
    let (scores, mut images) = rayon::join(
        || known.unwrap_or_else(|| score(&cut.solid, &o.score)),
        || {
            jobs.par_iter()
                .map(|&(l, t)| picture(l, t))
                .collect::<Vec<Image>>()
        },
    );
    let checks = if o.verify_photons > 0 {
        verify_scores(&cut.solid, &o.score, &scores, o.verify_photons, o.seed)?
    } else {
        Vec::new()
    };
    let mut rest = images.split_off(faces.len()).into_iter();
    let pictures: Vec<(Light, Image)> = faces.into_iter().zip(images).collect();
    let tilted = o
        .tilts
        .iter()
        .map(|&t| {
            let img = if t == 0.0 {
                pictures[0].1.clone()
            } else {
                rest.next().expect("one picture per non-zero tilt")
            };
            (t, img)
        })
        .collect();
    Ok(CutReport {
        label: label.to_string(),
        cut: cut.clone(),
        scores,
        checks,
        pictures,
        tilted,
    })
}
