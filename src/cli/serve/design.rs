//! A design (a cut without a family: an uploaded `.asc`, a TOML list of facets, a mesh) as
//! sliders: its tier angles ([`DesignSpace`]), each tier's slider bounds and the meets it
//! cannot keep when moved alone, and a small cache so that every slider move rebuilds from
//! the same adopted design without solving its depths afresh.
//!
//! The page sends the design's bytes with every request (nothing is written to disk); the
//! cache keys on those bytes, so two uploads of one file share one [`Design`].

use super::error::ApiError;
use axum::http::StatusCode;
use facetlab::cut::{Cut, CutSpace};
use facetlab::design::{DesignSpace, OpenMeets, MEET_TOL};
use facetlab::error::Error;
use serde_json::{json, Value};
use std::collections::{BTreeMap, VecDeque};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

/// How far each slider reaches from the design's own angle, degrees.
pub const SLIDER_REACH: f64 = 5.0;
/// The angles a slider never passes, degrees (a tier's angle is in (0, 90)).
pub const SLIDER_LIMITS: (f64, f64) = (0.5, 89.5);
/// A slider's step, degrees.
pub const SLIDER_STEP: f64 = 0.01;
/// Designs kept adopted (the most recently used).
const CACHED: usize = 8;

/// What moving one tier alone does: the meets it opens (by their tiers), and the smallest tie
/// that keeps them.
type Alone = (Vec<String>, Option<String>);

/// A design adopted once: its space, its tiers' slider bounds and, once probed
/// ([`Design::probe`]), the meets each tier opens when moved alone.
#[derive(Debug)]
pub struct Design {
    /// The design's tier angles as a cut space (meets refused when they would open).
    pub space: DesignSpace,
    /// Each key with its default angle and slider bounds, in tier order.
    bounds: Vec<(String, f64, f64, f64)>,
    /// Per key, the meets (by their tiers, `P1·P2·G1`) it opens when moved alone, and the
    /// smallest tie that keeps them ([`DesignSpace::tie_for`]).
    alone: OnceLock<BTreeMap<String, Alone>>,
    /// Whether a probe was started.
    probing: AtomicBool,
}

impl Design {
    /// Adopt `cut` ([`DesignSpace::new`]): its meets found and snapped, its tiers' bounds.
    pub fn adopt(cut: &Cut) -> facetlab::error::Result<Design> {
        let space = DesignSpace::new(cut, MEET_TOL, OpenMeets::Refuse)?;
        let bounds = space
            .keys()
            .into_iter()
            .filter_map(|k| {
                let d = space.range(k)?.default;
                let lo = (d - SLIDER_REACH).max(SLIDER_LIMITS.0);
                let hi = (d + SLIDER_REACH).min(SLIDER_LIMITS.1);
                Some((k.to_string(), d, lo, hi))
            })
            .collect();
        Ok(Design {
            space,
            bounds,
            alone: OnceLock::new(),
            probing: AtomicBool::new(false),
        })
    }

    /// True the first time it is asked while the tiers are not probed: the caller then runs
    /// [`Design::probe`] (a reangle per tier: from a tenth of a second to seconds).
    pub fn start_probe(&self) -> bool {
        self.alone.get().is_none() && !self.probing.swap(true, Ordering::SeqCst)
    }

    /// Undo [`Design::start_probe`] when the probe could not run.
    pub fn unstart_probe(&self) {
        self.probing.store(false, Ordering::SeqCst);
    }

    /// Turn each tier alone over its slider bounds ([`DesignSpace::unkeepable`]) and keep
    /// which meets it opens, and the tie that would keep them.
    pub fn probe(&self) {
        let free: Vec<(String, f64, f64)> = self
            .bounds
            .iter()
            .map(|(k, _, lo, hi)| (k.clone(), *lo, *hi))
            .collect();
        let mut alone: BTreeMap<String, Alone> = BTreeMap::new();
        if let Ok(opened) = self.space.unkeepable(&free) {
            for o in opened {
                let meet = self
                    .space
                    .model()
                    .meet_tiers(&self.space.meets()[o.meet])
                    .join("·");
                for k in o.by {
                    let (list, _) = alone.entry(k).or_default();
                    if !list.contains(&meet) {
                        list.push(meet.clone());
                    }
                }
            }
        }
        for (k, _, _, hi) in &self.bounds {
            if let Some((_, tie)) = alone.get_mut(k) {
                *tie = self.space.tie_for(k, *hi);
            }
        }
        let _ = self.alone.set(alone);
    }

    /// The design at the angles `set` ([`DesignSpace::build`]); an angle that would open a
    /// meet or change the design's facets is a 422 naming the tier.
    pub fn build(&self, name: &str, set: &BTreeMap<String, f64>) -> Result<Cut, ApiError> {
        self.space.build(name, set).map_err(|e| self.error(e, set))
    }

    /// A library error about angles, named by the request's field: `set.TIER` when it names
    /// a tier (or, for a changed design, when one tier was turned), else `set`.
    fn error(&self, e: Error, set: &BTreeMap<String, f64>) -> ApiError {
        let keys = self.space.keys();
        let (field, message) = match e {
            Error::Invalid { field, message } if keys.contains(&field.as_str()) => {
                (format!("set.{field}"), message)
            }
            Error::Invalid { field, message } if set.contains_key(&field) => {
                (format!("set.{field}"), message)
            }
            other => {
                let text = other.to_string();
                let text = text.strip_prefix("geometry: ").unwrap_or(&text).to_string();
                let turned: Vec<&String> = set
                    .iter()
                    .filter(|(k, v)| {
                        self.space
                            .range(k)
                            .is_some_and(|r| (r.default - **v).abs() > 1e-12)
                    })
                    .map(|(k, _)| k)
                    .collect();
                match turned.as_slice() {
                    [one] => (format!("set.{one}"), text),
                    _ => ("set".to_string(), text),
                }
            }
        };
        ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, field, message)
    }

    /// The `design_space` record of `POST /api/cut`: the tiers as sliders (key, default,
    /// bounds, step, unit, and `alone_opens` once probed, else `null`), the number of meets
    /// kept, and `probed`.
    pub fn json(&self) -> Value {
        let alone = self.alone.get();
        let tiers: Vec<Value> = self
            .bounds
            .iter()
            .map(|(k, d, lo, hi)| {
                json!({
                    "key": k, "default": d, "min": lo, "max": hi, "open": false,
                    "unit": "degrees", "step": SLIDER_STEP,
                    "doc": format!("angle of tier {k} to the girdle plane; its depth is solved so that the design's meets stay meets"),
                    "alone_opens": alone.map(|a| a.get(k).map(|x| x.0.clone()).unwrap_or_default()),
                    "tie": alone.and_then(|a| a.get(k).and_then(|x| x.1.clone())),
                })
            })
            .collect();
        json!({ "tiers": tiers, "meets": self.space.meets().len(), "probed": alone.is_some() })
    }
}

/// What a cache slot holds: the design adopted, or why it cannot be (a one-line message).
pub type Adopted = Result<Arc<Design>, String>;

/// A cache slot: a design's source key and its adoption (done once, when first asked for).
type Slot = (Vec<u8>, Arc<OnceLock<Adopted>>);

/// The designs adopted lately, keyed by their source (format, name and bytes).
#[derive(Default)]
pub struct Designs {
    slots: Mutex<VecDeque<Slot>>,
}

impl Designs {
    /// The design of `cut` (from the source `key`), adopted once: concurrent requests for one
    /// new design wait for one adoption.
    pub fn get(&self, key: Vec<u8>, cut: &Cut) -> Adopted {
        let slot = {
            let mut slots = self.slots.lock().unwrap_or_else(|p| p.into_inner());
            match slots.iter().position(|(k, _)| *k == key) {
                Some(i) => {
                    let hit = slots.remove(i).expect("a slot found");
                    let slot = hit.1.clone();
                    slots.push_front(hit);
                    slot
                }
                None => {
                    let slot = Arc::new(OnceLock::new());
                    slots.push_front((key, slot.clone()));
                    slots.truncate(CACHED);
                    slot
                }
            }
        };
        slot.get_or_init(|| Design::adopt(cut).map(Arc::new).map_err(|e| e.to_string()))
            .clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use facetlab::io;

    #[test]
    fn tiers_are_sliders_and_the_cache_adopts_once() {
        let cut = io::presets::load("tolkowsky").unwrap().unwrap();
        let text = io::asc::write(&cut, io::asc::DEFAULT_GEAR);
        let design = io::parse_cut("asc", text.as_bytes(), "t", "cut").unwrap();
        assert!(design.family.is_none());
        let cache = Designs::default();
        let a = cache.get(b"t".to_vec(), &design).unwrap();
        let b = cache.get(b"t".to_vec(), &design).unwrap();
        assert!(Arc::ptr_eq(&a, &b), "adopted twice");
        assert!(a.start_probe() && !a.start_probe());
        a.probe();
        let j = a.json();
        assert_eq!(j["probed"], true);
        let mains = j["tiers"]
            .as_array()
            .unwrap()
            .iter()
            .find(|t| t["key"] == "pavilion-main")
            .expect("a pavilion-main slider");
        let d = mains["default"].as_f64().unwrap();
        assert!((d - 40.75).abs() < 1e-9, "{d}");
        assert!((mains["min"].as_f64().unwrap() - (d - SLIDER_REACH)).abs() < 1e-12);
        // An unknown tier is about that key; the design's facets stay.
        let e = a
            .build("t", &BTreeMap::from([("nosuch".to_string(), 40.0)]))
            .unwrap_err();
        assert_eq!(e.field, "set.nosuch", "{e:?}");
        let c = a
            .build("t", &BTreeMap::from([("pavilion-main".to_string(), 41.0)]))
            .unwrap();
        assert_eq!(c.solid.facets().len(), design.solid.facets().len());
        // Steeper than the lower halves, the mains would vanish: refused, naming the tier.
        let e = a
            .build("t", &BTreeMap::from([("pavilion-main".to_string(), 43.0)]))
            .unwrap_err();
        assert_eq!(e.field, "set.pavilion-main", "{e:?}");
    }
}
