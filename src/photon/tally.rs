//! Tallies: integer counts while tracing, shares with standard errors when reported.

use super::config::WEIGHTS;
use super::light::Light;
use super::solid::TraceSolid;
use crate::geometry::DVec3;
use serde::ser::{Serialize, SerializeMap, Serializer};

/// JSON keys of the four face categories.
pub const CATEGORY_KEYS: [&str; 4] = ["lt45", "45_90", "90_135", "gt135"];
/// Human labels of the four face categories.
pub const CATEGORY_LABELS: [&str; 4] = ["< 45°", "45–90°", "90–135°", "> 135°"];

/// Integer counts of a run (merged by adding).
#[derive(Clone, Debug, PartialEq)]
pub struct Counts {
    /// Photons shot.
    pub shot: u64,
    /// Photons that hit the stone.
    pub hit: u64,
    /// Photons absorbed inside.
    pub absorbed: u64,
    /// Photons stopped by the depth limit.
    pub depth_limited: u64,
    /// Exited photons leaving upward (z > 0).
    pub light_return: u64,
    /// Exited photons by face category of the exit facet.
    pub categories: [u64; 4],
    /// Exited photons by exit facet.
    pub per_facet: Vec<u64>,
    /// Exited photons by angle of the exit direction from up, 1° bins (bin k: [k, k+1)).
    pub angle_hist: Vec<u64>,
    /// Surface interactions of all hit photons.
    pub interactions: u64,
    /// Sums over exited photons of the exit weights (see [`crate::photon::trace_weights`];
    /// [`crate::photon::trace_weighted`] uses the first).
    pub weight_sum: [f64; WEIGHTS],
    /// Sums over exited photons of the squared exit weights.
    pub weight_sq: [f64; WEIGHTS],
    /// A birefringent stone's exited photons by the mode they left from (ordinary,
    /// extraordinary; external reflections in neither), and of those the ones leaving
    /// upward (z > 0).
    pub mode_exits: [u64; 2],
    /// See [`Counts::mode_exits`].
    pub mode_return: [u64; 2],
}

impl Counts {
    /// Zero counts for a solid of `facets` facets.
    pub fn new(facets: usize) -> Counts {
        Counts {
            shot: 0,
            hit: 0,
            absorbed: 0,
            depth_limited: 0,
            light_return: 0,
            categories: [0; 4],
            per_facet: vec![0; facets],
            angle_hist: vec![0; 180],
            interactions: 0,
            weight_sum: [0.0; WEIGHTS],
            weight_sq: [0.0; WEIGHTS],
            mode_exits: [0; 2],
            mode_return: [0; 2],
        }
    }

    /// Add `o` to these counts.
    pub fn add(&mut self, o: &Counts) {
        self.shot += o.shot;
        self.hit += o.hit;
        self.absorbed += o.absorbed;
        self.depth_limited += o.depth_limited;
        self.light_return += o.light_return;
        self.interactions += o.interactions;
        for w in 0..WEIGHTS {
            self.weight_sum[w] += o.weight_sum[w];
            self.weight_sq[w] += o.weight_sq[w];
        }
        for m in 0..2 {
            self.mode_exits[m] += o.mode_exits[m];
            self.mode_return[m] += o.mode_return[m];
        }
        for (a, b) in self.categories.iter_mut().zip(&o.categories) {
            *a += b;
        }
        for (a, b) in self.per_facet.iter_mut().zip(&o.per_facet) {
            *a += b;
        }
        for (a, b) in self.angle_hist.iter_mut().zip(&o.angle_hist) {
            *a += b;
        }
    }

    /// Photons that left the stone.
    pub fn exited(&self) -> u64 {
        self.categories.iter().sum()
    }

    /// Photons that missed the stone.
    pub fn missed(&self) -> u64 {
        self.shot - self.hit
    }

    /// Check the bookkeeping: hit ≤ shot; hit = exited + absorbed + depth-limited; the
    /// categories, the facets and the angle histogram each sum to the exited photons; light
    /// return ≤ exited. Returns a description of the first violation.
    pub fn check(&self) -> std::result::Result<(), String> {
        let ex = self.exited();
        if self.hit > self.shot {
            return Err(format!("hit {} > shot {}", self.hit, self.shot));
        }
        if ex + self.absorbed + self.depth_limited != self.hit {
            return Err(format!(
                "exited {ex} + absorbed {} + depth-limited {} != hit {}",
                self.absorbed, self.depth_limited, self.hit
            ));
        }
        if self.per_facet.iter().sum::<u64>() != ex {
            return Err("exits per facet do not sum to the exited photons".into());
        }
        if self.angle_hist.iter().sum::<u64>() != ex {
            return Err("exit-angle histogram does not sum to the exited photons".into());
        }
        if self.light_return > ex {
            return Err("light return exceeds the exited photons".into());
        }
        Ok(())
    }
}

/// How a photon's path ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fate {
    /// Left the stone through this facet.
    Exited(usize),
    /// Absorbed inside.
    Absorbed,
    /// Stopped by the depth limit.
    DepthLimited,
}

/// A recorded photon path (for pictures).
#[derive(Clone, Debug, PartialEq)]
pub struct PhotonPath {
    /// Wavelength, nm.
    pub wavelength: f64,
    /// The light point, the entry point, every later interaction point, and an end point: one
    /// girdle diameter along the exit direction, or where the photon was absorbed or stopped.
    pub points: Vec<DVec3>,
    /// How it ended.
    pub fate: Fate,
}

/// The result of a run: counts, what they are of, and timing.
///
/// Serialized (`serde::Serialize`), a tally has these JSON keys (shares are of the photons that hit the stone unless said):
///
/// | key | meaning |
/// | --- | --- |
/// | `cut` | the cut's name |
/// | `light` | the light's description; `light_angle`: rotation angle in degrees or null |
/// | `photons_shot`, `photons_hit` | photons shot from the light, photons that hit the stone |
/// | `face_categories.{lt45,45_90,90_135,gt135}` | share leaving through facets whose outward normal is < 45°, 45–90° (90° included), 90–135°, > 135° from up |
/// | `thesis_light_return` | the thesis's light return: share of the photons that hit leaving with an upward direction (z > 0), under this light, absorption and depth (not `score`'s `overhead_light_return`) |
/// | `absorbed`, `depth_limited` | share absorbed, share stopped by the depth limit |
/// | `exited` | share that left the stone (= the sum of the four categories) |
/// | `*_stderr` | the standard error of each share, sqrt(p(1 − p)/n) |
/// | `exit_angle_cdf` | 181 values: value k is the share of *exited* photons whose exit direction is less than k° from up (0 at k = 0, 1 at k = 180) |
/// | `exit_angle_cdf_stderr` | its standard errors |
/// | `exits_per_facet` | per facet: `name`, `tier`, `category`, `share` (of hit), `stderr` |
/// | `mean_interactions` | surface interactions per hit photon |
/// | `elapsed_s`, `photons_per_second` | wall-clock time and photons shot per second |
#[derive(Clone, Debug)]
pub struct Tally {
    /// The cut's name (empty when traced from a bare solid).
    pub cut: String,
    /// The light's description.
    pub light: String,
    /// The rotation angle (degrees) for a light of the rotation sweep.
    pub light_angle: Option<f64>,
    /// The counts.
    pub counts: Counts,
    /// Facet names.
    pub facet_names: Vec<String>,
    /// Facet tiers.
    pub facet_tiers: Vec<String>,
    /// Face category of each facet.
    pub facet_categories: Vec<u8>,
    /// Wall-clock seconds of the tracing.
    pub elapsed_s: f64,
    /// Recorded paths (not serialized).
    pub paths: Vec<PhotonPath>,
}

/// A share `k/n` and its binomial standard error sqrt(p(1 − p)/n); (0, 0) when n = 0.
pub fn share(k: u64, n: u64) -> (f64, f64) {
    if n == 0 {
        return (0.0, 0.0);
    }
    let p = k as f64 / n as f64;
    (p, (p * (1.0 - p) / n as f64).sqrt())
}

impl Tally {
    pub(crate) fn new(
        cut: String,
        light: &Light,
        s: &TraceSolid,
        counts: Counts,
        elapsed_s: f64,
        paths: Vec<PhotonPath>,
    ) -> Tally {
        Tally {
            cut,
            light: light.label.clone(),
            light_angle: light.angle,
            counts,
            facet_names: s.names.clone(),
            facet_tiers: s.tiers.clone(),
            facet_categories: s.category.clone(),
            elapsed_s,
            paths,
        }
    }

    /// Share of hit photons leaving through face category `k` (0..4), with its standard error.
    pub fn category(&self, k: usize) -> (f64, f64) {
        share(self.counts.categories[k], self.counts.hit)
    }
    /// Light return (share of hit photons leaving upward) and its standard error.
    pub fn light_return(&self) -> (f64, f64) {
        share(self.counts.light_return, self.counts.hit)
    }
    /// Share of hit photons absorbed, with its standard error.
    pub fn absorbed(&self) -> (f64, f64) {
        share(self.counts.absorbed, self.counts.hit)
    }
    /// Share of hit photons stopped by the depth limit, with its standard error.
    pub fn depth_limited(&self) -> (f64, f64) {
        share(self.counts.depth_limited, self.counts.hit)
    }
    /// Share of hit photons that left the stone, with its standard error.
    pub fn exited(&self) -> (f64, f64) {
        share(self.counts.exited(), self.counts.hit)
    }
    /// Share of hit photons leaving through facet `i`, with its standard error.
    pub fn facet(&self, i: usize) -> (f64, f64) {
        share(self.counts.per_facet[i], self.counts.hit)
    }
    /// The cumulative distribution of the exit angle from up: 181 values, value k the share
    /// of exited photons less than k° from up; with standard errors.
    pub fn exit_angle_cdf(&self) -> (Vec<f64>, Vec<f64>) {
        let n = self.counts.exited();
        let mut acc = 0u64;
        let mut p = vec![0.0; 181];
        let mut e = vec![0.0; 181];
        for k in 0..=180 {
            (p[k], e[k]) = share(acc, n);
            if k < 180 {
                acc += self.counts.angle_hist[k];
            }
        }
        if n > 0 {
            p[180] = 1.0;
        }
        (p, e)
    }
    /// Photons shot per second of wall-clock time.
    pub fn photons_per_second(&self) -> f64 {
        if self.elapsed_s > 0.0 {
            self.counts.shot as f64 / self.elapsed_s
        } else {
            0.0
        }
    }
    /// Mean surface interactions per hit photon.
    pub fn mean_interactions(&self) -> f64 {
        if self.counts.hit == 0 {
            0.0
        } else {
            self.counts.interactions as f64 / self.counts.hit as f64
        }
    }
}

#[derive(serde::Serialize)]
struct FacetExit<'a> {
    name: &'a str,
    tier: &'a str,
    category: &'static str,
    share: f64,
    stderr: f64,
}

struct Cats([f64; 4]);

impl Serialize for Cats {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(4))?;
        for (k, v) in CATEGORY_KEYS.iter().zip(self.0) {
            m.serialize_entry(k, &v)?;
        }
        m.end()
    }
}

impl Serialize for Tally {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let cats: Vec<(f64, f64)> = (0..4).map(|k| self.category(k)).collect();
        let (cdf, cdf_e) = self.exit_angle_cdf();
        let facets: Vec<FacetExit> = (0..self.facet_names.len())
            .map(|i| {
                let (share, stderr) = self.facet(i);
                FacetExit {
                    name: &self.facet_names[i],
                    tier: &self.facet_tiers[i],
                    category: CATEGORY_KEYS[self.facet_categories[i] as usize],
                    share,
                    stderr,
                }
            })
            .collect();
        let mut m = s.serialize_map(None)?;
        m.serialize_entry("cut", &self.cut)?;
        m.serialize_entry("light", &self.light)?;
        m.serialize_entry("light_angle", &self.light_angle)?;
        m.serialize_entry("photons_shot", &self.counts.shot)?;
        m.serialize_entry("photons_hit", &self.counts.hit)?;
        m.serialize_entry(
            "face_categories",
            &Cats([cats[0].0, cats[1].0, cats[2].0, cats[3].0]),
        )?;
        m.serialize_entry(
            "face_categories_stderr",
            &Cats([cats[0].1, cats[1].1, cats[2].1, cats[3].1]),
        )?;
        for (key, (v, e)) in [
            ("thesis_light_return", self.light_return()),
            ("absorbed", self.absorbed()),
            ("depth_limited", self.depth_limited()),
            ("exited", self.exited()),
        ] {
            m.serialize_entry(key, &v)?;
            m.serialize_entry(&format!("{key}_stderr"), &e)?;
        }
        m.serialize_entry("exit_angle_cdf", &cdf)?;
        m.serialize_entry("exit_angle_cdf_stderr", &cdf_e)?;
        m.serialize_entry("exits_per_facet", &facets)?;
        m.serialize_entry("mean_interactions", &self.mean_interactions())?;
        m.serialize_entry("elapsed_s", &self.elapsed_s)?;
        m.serialize_entry("photons_per_second", &self.photons_per_second())?;
        m.end()
    }
}
