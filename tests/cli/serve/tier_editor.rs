//! The workbench's tier editor ("Design tier by tier", recipe.js) in a real browser (Chromium
//! over CDP, when installed): the recipe of the stone shown, its tiers as rows, the stone
//! re-cut as an angle is typed, an error shown at its tier, undo, add, move and remove; a
//! screenshot under target/serve-screenshots/.

use super::browser::{chromium_for, js, launch, runtime, shots_dir, wait_js, Chromium};
use super::*;

#[test]
fn the_tier_editor_recuts_the_stone_as_you_type() {
    if !chromium_for("the_tier_editor_recuts_the_stone_as_you_type") {
        return;
    }
    let server = Server::start();
    let url = format!("http://{}/", server.addr);
    runtime().block_on(session(&url, &shots_dir()));
}

/// Set the input `sel` of tier row `i` to `v` as typing does (an `input` event).
fn type_into(i: usize, sel: &str, v: &str) -> String {
    format!("(() => {{ const el = document.querySelectorAll('#recipe-tiers .tier-row')[{i}].querySelector('{sel}'); el.value = {v:?}; el.dispatchEvent(new Event('input', {{bubbles: true}})); return true; }})()")
}

async fn session(url: &str, shots: &std::path::Path) {
    use chromiumoxide::page::ScreenshotParams;

    let Chromium {
        mut browser,
        pump,
        page,
        profile: _profile,
    } = launch(1500, 1100).await;
    page.evaluate_on_new_document(
        "window.__errs = []; window.addEventListener('error', e => window.__errs.push(String(e.message))); window.addEventListener('unhandledrejection', e => window.__errs.push('rejection: ' + String(e.reason)));",
    )
    .await
    .unwrap();
    page.goto(url).await.unwrap();
    assert!(
        wait_js(&page, "document.querySelector('#render-a').complete && document.querySelector('#render-a').naturalWidth === 512 && document.querySelector('#score-a-brilliance').textContent !== '—'", 60).await,
        "the page did not show tolkowsky"
    );
    // The panel: closed at first, its editor hidden until there is a recipe.
    let hidden: bool = js(&page, "document.querySelector('#recipe-editor').hidden").await;
    assert!(hidden);
    let _: bool = js(&page, "(() => { document.querySelector('#design-panel').open = true; document.querySelector('#recipe-from').click(); return true; })()").await;
    assert!(
        wait_js(&page, "document.querySelectorAll('#recipe-tiers .tier-row').length > 5 && /built/.test(document.querySelector('#recipe-status').textContent) && document.querySelector('#cut-name').textContent === 'Tolkowsky'", 60).await,
        "From cut A did not give tolkowsky's tiers, built"
    );
    // Every row: name, angle, indices, a placement with its value, ↑ ↓ ×, and its instruction.
    let rows: Vec<(String, String, String, String, usize, String)> = js(
        &page,
        "Array.from(document.querySelectorAll('#recipe-tiers .tier-row')).map(r => [r.querySelector('.t-name').value, r.querySelector('.t-angle').value, r.querySelector('.t-indices').value, r.querySelector('select.t-place').value, r.querySelectorAll('button').length, r.querySelector('.t-msg').textContent])",
    )
    .await;
    assert_eq!(rows[0].3, "centre", "{rows:?}");
    assert_eq!(rows[0].5, "cut to centre point", "{rows:?}");
    assert!(
        rows.iter()
            .all(|r| r.4 == 3 && !r.0.is_empty() && !r.5.is_empty()),
        "{rows:?}"
    );
    assert!(
        rows.iter()
            .any(|r| r.3 == "meet" && r.5.starts_with("meet")),
        "{rows:?}"
    );
    for id in [
        "#recipe-add",
        "#recipe-undo",
        "#recipe-name",
        "#recipe-gear",
        "#recipe-symmetry",
        "#recipe-mirror",
        "#recipe-index",
    ] {
        let there: bool = js(&page, &format!("!!document.querySelector('{id}')")).await;
        assert!(there, "{id}");
    }
    let saves: Vec<String> = js(
        &page,
        "Array.from(document.querySelectorAll('#recipe-save button')).map(b => b.dataset.save)",
    )
    .await;
    assert_eq!(saves, ["recipe", "asc", "gem"]);
    let p1 = rows[0].1.clone();
    let wait_render = "document.querySelector('#render-a').complete && document.querySelector('#render-a').src.startsWith('blob:') && !!state.slots.a.recipe && !!state.slots.a.shown";
    if !wait_js(&page, wait_render, 60).await {
        let why: String = js(&page, "JSON.stringify({errs: window.__errs, status: document.querySelector('#status').textContent, veil: document.querySelector('#veil-a').textContent, recipe: !!state.slots.a.recipe, shown: !!state.slots.a.shown, src: document.querySelector('#render-a').src.slice(0, 30), rs: document.querySelector('#recipe-status').textContent})").await;
        panic!("the recipe's stone is not pictured: {why}");
    }
    let volume: f64 = js(&page, "recipe.built.volume").await;
    let src: String = js(&page, "document.querySelector('#render-a').src").await;
    // Type a steeper first tier: the stone is re-cut, pictured and scored again.
    let steeper = format!("{}", p1.parse::<f64>().unwrap() - 0.8);
    let _: bool = js(&page, &type_into(0, ".t-angle", &steeper)).await;
    assert!(
        wait_js(&page, &format!("recipe.built && recipe.built.volume !== {volume} && document.querySelector('#render-a').src !== {src:?} && document.querySelector('#render-a').complete"), 60).await,
        "typing an angle did not re-cut the stone"
    );
    let v2: f64 = js(&page, "recipe.built.volume").await;
    assert!(v2 > volume, "a steeper pavilion holds more: {v2} {volume}");
    let ms: f64 = js(
        &page,
        "Number(document.querySelector('#recipe-status').dataset.ms)",
    )
    .await;
    eprintln!("tier editor: the page's build request answered in {ms} ms");
    wait_js(
        &page,
        "document.querySelector('#scores').dataset.a === 'full'",
        30,
    )
    .await;
    page.save_screenshot(
        ScreenshotParams::builder().full_page(true).build(),
        shots.join("11-tier-editor.png"),
    )
    .await
    .unwrap();
    // An index off the gear: the row says so, naming nothing else.
    let _: bool = js(&page, &type_into(0, ".t-indices", "96.5")).await;
    assert!(
        wait_js(&page, "document.querySelector('#recipe-tiers .tier-row').classList.contains('invalid') && /off the 96 gear/.test(document.querySelector('#recipe-tiers .tier-row .t-msg').textContent)", 30).await,
        "the error is not shown at its tier"
    );
    let status: String = js(
        &page,
        "document.querySelector('#recipe-status').textContent",
    )
    .await;
    assert!(
        status.starts_with(&format!("tier {}: ", rows[0].0)),
        "{status}"
    );
    page.save_screenshot(
        ScreenshotParams::builder().full_page(true).build(),
        shots.join("12-tier-editor-error.png"),
    )
    .await
    .unwrap();
    // Undo: the indices as they were, built again.
    let _: bool = js(
        &page,
        "(() => { document.querySelector('#recipe-undo').click(); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, &format!("!document.querySelector('#recipe-tiers .tier-row.invalid') && document.querySelector('#recipe-tiers .t-indices').value === {:?} && recipe.built && Math.abs(recipe.built.volume - {v2}) < 1e-12", rows[0].2), 30).await,
        "undo did not bring the indices back"
    );
    // Add a tier (cut last), move it up, remove it.
    let n = rows.len();
    let _: bool = js(
        &page,
        "(() => { document.querySelector('#recipe-add').click(); return true; })()",
    )
    .await;
    let count: usize = js(
        &page,
        "document.querySelectorAll('#recipe-tiers .tier-row').length",
    )
    .await;
    assert_eq!(count, n + 1);
    let _: bool = js(&page, &format!("(() => {{ document.querySelectorAll('#recipe-tiers .tier-row')[{n}].querySelectorAll('button')[0].click(); return true; }})()")).await;
    let moved: String = js(&page, &format!("document.querySelectorAll('#recipe-tiers .tier-row')[{}].querySelector('.t-name').value", n - 1)).await;
    assert!(moved.starts_with('X'), "{moved}");
    let _: bool = js(&page, &format!("(() => {{ document.querySelectorAll('#recipe-tiers .tier-row')[{}].querySelectorAll('button')[2].click(); return true; }})()", n - 1)).await;
    let names: Vec<String> = js(
        &page,
        "Array.from(document.querySelectorAll('#recipe-tiers .t-name')).map(e => e.value)",
    )
    .await;
    assert_eq!(names, rows.iter().map(|r| r.0.clone()).collect::<Vec<_>>());
    let errs: Vec<String> = js(&page, "window.__errs").await;
    assert!(errs.is_empty(), "{errs:?}");
    browser.close().await.unwrap();
    pump.abort();
}
