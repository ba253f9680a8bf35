//! The cutting mode: one screen per step with the stone as cut so far.

use super::{header_lines, padded, three_views, Look, SheetOptions, DONE, FONT, INK, NOW, ROUGH};
use crate::cut::Cut;
use crate::design::{cut_so_far, step_of_facets, SheetStep, UNCUT};
use crate::error::Result;
use crate::geometry::Polyhedron;
use crate::report::escape as esc;
use std::fmt::Write as _;

/// The cutting mode: an HTML page with one screen per step (next and previous by buttons or
/// the arrow keys), each with the step's row and the stone as cut so far
/// ([`cut_so_far`]) face up, face down and from the side, the step's facets highlighted.
/// Each screen's `data-facets` is the number of facets cut so far.
pub fn cutting_mode_html(cut: &Cut, steps: &[SheetStep], o: &SheetOptions) -> Result<String> {
    let (title, lines, _) = header_lines(cut, o);
    let mut screens = String::new();
    let gear = crate::design::sheet_gear(cut);
    for k in 0..steps.len() {
        let solid = cut_so_far(cut, &steps[..=k])?;
        let owner = owners(cut, &solid, &steps[..=k]);
        let cut_facets = owner.iter().filter(|o| o.is_some()).count();
        let fill = |i: usize| match owner[i] {
            Some(s) if s == k => NOW,
            Some(_) => DONE,
            None => ROUGH,
        };
        let label = |i: usize| {
            let s = owner[i]?;
            let f = &solid.facets()[i];
            let idx = gear.index(f.plane.normal);
            let idx = if (idx - idx.round()).abs() < 1e-6 {
                format!("{:02.0}", idx.round())
            } else {
                format!("{idx:.2}")
            };
            Some((steps[s].name.clone(), idx))
        };
        let mut svg = String::new();
        let _ = writeln!(
            svg,
            r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 560 420" font-family="{FONT}" fill="{INK}">"#
        );
        three_views(
            &mut svg,
            &solid,
            (0.0, 0.0, 560.0, 420.0),
            &Look {
                fill: &fill,
                label: &label,
            },
            true,
        );
        svg.push_str("</svg>");
        let s = &steps[k];
        let _ = writeln!(
            screens,
            r#"<section class="step" data-step="{}" data-facets="{cut_facets}"{}><h2>Step {} of {} · {}</h2><p class="row"><b>{}</b> at <b>{:.2}°</b>, index {}</p><p class="do">{}</p>{svg}</section>"#,
            k + 1,
            if k == 0 { "" } else { " hidden" },
            k + 1,
            steps.len(),
            esc(s.section.heading()),
            esc(&s.name),
            s.angle.abs(),
            esc(&padded(&s.indices)),
            esc(&s.instruction)
        );
    }
    let header: String = lines
        .iter()
        .map(|(_, l)| format!("<div>{}</div>", esc(l)))
        .collect();
    Ok(format!(
        r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{t} — cutting mode</title>
<style>body {{ font-family: {FONT}; margin: 1em auto; max-width: 60em; color: #222 }} .hdr {{ color: #555; font-size: 0.85em }} h2 {{ margin: 0.6em 0 0.2em }} .row {{ font-size: 1.3em; margin: 0.2em 0 }} .do {{ font-size: 1.3em; margin: 0.2em 0; color: #1f4e8c }} nav button {{ font-size: 1.1em; margin-right: 0.5em }} svg {{ width: 100%; height: auto; max-height: 70vh }}</style></head>
<body><h1>{t}</h1><div class="hdr">{header}</div>
<nav><button id="prev">← previous</button><button id="next">next →</button> <span id="where"></span> <span class="hdr">(arrow keys too; cut facets blue, this step's yellow, the rough grey)</span></nav>
{screens}<script>
const s = [...document.querySelectorAll('section.step')]; let i = 0;
function show(k) {{ i = Math.max(0, Math.min(s.length - 1, k)); s.forEach((e, j) => e.hidden = j !== i); document.getElementById('where').textContent = 'step ' + (i + 1) + ' / ' + s.length; }}
document.getElementById('prev').onclick = () => show(i - 1);
document.getElementById('next').onclick = () => show(i + 1);
document.addEventListener('keydown', e => {{ if (e.key === 'ArrowRight' || e.key === ' ') show(i + 1); if (e.key === 'ArrowLeft') show(i - 1); }});
show(0);
</script></body></html>
"#,
        t = esc(&title)
    ))
}

/// The step each facet of a partial solid belongs to (`None`: the rough's block).
fn owners(cut: &Cut, solid: &Polyhedron, steps: &[SheetStep]) -> Vec<Option<usize>> {
    let partial = Cut {
        solid: solid.clone(),
        ..cut.clone()
    };
    step_of_facets(&partial, steps)
        .into_iter()
        .zip(solid.facets())
        .map(|(s, f)| if f.tier == UNCUT { None } else { s })
        .collect()
}
