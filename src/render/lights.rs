//! The one table of the lights a picture can be drawn under ([`table`]), made from their own
//! homes: the laboratory lights ([`Light::ALL`]), the studio rigs ([`Rig::ALL`]) and the bundled
//! map ([`STUDIO`]). Every face lists the lights from it (the command line's values and help,
//! the web page's menu through its presets), so a new rig is written in one place.

use super::photo::{Rig, STUDIO};
use super::Light;
use serde::Serialize;

/// How a user's own environment map is named: `env:` then its file.
pub const MAP_FILE: &str = "env:FILE";

/// One light as the faces list it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LightEntry {
    /// Its name, as every face takes it.
    pub name: &'static str,
    /// A photograph's light (a rig or a map), else a laboratory light.
    pub photo: bool,
    /// A short title for menus.
    pub label: &'static str,
    /// What it is, in a few words.
    pub about: &'static str,
    /// The exposure a picture under it is best first shown at; `None`: a false colour, which
    /// takes none.
    pub exposure: Option<f64>,
    /// A laboratory light's default head shadow, degrees (its port, head or dark tube; 0: an
    /// open sky); `None` for a photograph's.
    pub head_shadow_deg: Option<f64>,
}

/// Every light, in the order the faces list them: the laboratory lights, the rigs, the
/// bundled map.
pub fn table() -> Vec<LightEntry> {
    let lab = Light::ALL.map(|l| LightEntry {
        name: l.name(),
        photo: false,
        label: l.label(),
        about: l.about(),
        exposure: l.first_exposure(),
        head_shadow_deg: Some(l.default_head_shadow_deg()),
    });
    let rigs = Rig::ALL.map(|r| LightEntry {
        name: r.name(),
        photo: true,
        label: r.label(),
        about: r.about(),
        exposure: Some(r.first_exposure()),
        head_shadow_deg: None,
    });
    let studio = LightEntry {
        name: STUDIO,
        photo: true,
        label: "Photo: studio map",
        about: "the bundled procedural environment map",
        exposure: Some(1.0),
        head_shadow_deg: None,
    };
    lab.into_iter().chain(rigs).chain([studio]).collect()
}

/// The names a light is given by, the user's map last: `iso|cos|…|studio|env:FILE`.
pub fn values() -> String {
    let mut names: Vec<&str> = table().iter().map(|e| e.name).collect();
    names.push(MAP_FILE);
    names.join("|")
}

/// The lights with what each is, as a help text says them: `iso (uniform sky), …; or a
/// photograph under a studio rig: tent (…), …, or env:FILE (…)`.
pub fn help() -> String {
    let said = |photo: bool| -> Vec<String> {
        table()
            .iter()
            .filter(|e| e.photo == photo)
            .map(|e| format!("{} ({})", e.name, e.about))
            .collect()
    };
    format!(
        "Lighting: {}; or a photograph under a studio rig: {}, or {MAP_FILE} (your \
         equirectangular .hdr or .exr environment map).",
        said(false).join(", "),
        said(true).join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::photo::PhotoLight;
    use crate::render::LightChoice;

    #[test]
    fn every_name_in_the_table_parses_to_its_own_kind_and_nothing_else_does() {
        let t = table();
        assert_eq!(t.len(), Light::ALL.len() + Rig::ALL.len() + 1);
        for (i, e) in t.iter().enumerate() {
            assert!(t[..i].iter().all(|o| o.name != e.name), "{} twice", e.name);
            let c = LightChoice::parse("light", e.name).unwrap();
            assert_eq!(c.is_photo(), e.photo, "{}", e.name);
            assert_eq!(c.name(), e.name);
            assert_eq!(e.head_shadow_deg.is_none(), e.photo);
            assert!(e.exposure.is_none_or(|x| x > 0.0 && x <= 100.0));
        }
        // The photographs' names are exactly those PhotoLight takes, and the false colours
        // (several channels mixed by fixed colours) are the lights without an exposure.
        let photo: Vec<&str> = t.iter().filter(|e| e.photo).map(|e| e.name).collect();
        assert_eq!(photo, PhotoLight::names());
        for l in Light::ALL {
            assert_eq!(l.first_exposure().is_none(), !l.false_colours().is_empty());
        }
        let v = values();
        assert_eq!(v.split('|').count(), t.len() + 1);
        assert!(
            v.starts_with("iso|cos|") && v.ends_with("|studio|env:FILE"),
            "{v}"
        );
        let h = help();
        for e in &t {
            assert!(h.contains(&format!("{} ({})", e.name, e.about)), "{h}");
        }
    }
}
