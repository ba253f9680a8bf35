//! The workbench page of `facetlab serve` in a real browser (Chromium over CDP, when
//! installed): loading, sliders, uploads, compare, downloads, screenshots.

use super::*;

/// Wait until the page's `expr` (a JavaScript expression) is true; false after `secs`.
pub(super) async fn wait_js(page: &chromiumoxide::Page, expr: &str, secs: u64) -> bool {
    let t = Instant::now();
    while t.elapsed() < Duration::from_secs(secs) {
        if let Ok(r) = page.evaluate(expr).await {
            if r.into_value::<bool>().unwrap_or(false) {
                return true;
            }
        }
        tokio::time::sleep(Duration::from_millis(25)).await;
    }
    eprintln!("waited {secs} s in vain for {expr}");
    false
}

/// Put `file` into the page's file input (DOM.setFileInputFiles), as a user's upload.
async fn upload(page: &chromiumoxide::Page, file: &std::path::Path) {
    upload_to(page, "#file", file).await
}

/// Put `file` into the file input `selector`.
async fn upload_to(page: &chromiumoxide::Page, selector: &str, file: &std::path::Path) {
    let input = page.find_element(selector).await.unwrap();
    page.execute(
        chromiumoxide::cdp::browser_protocol::dom::SetFileInputFilesParams::builder()
            .file(file.display().to_string())
            .backend_node_id(input.backend_node_id)
            .build()
            .unwrap(),
    )
    .await
    .unwrap();
}

pub(super) async fn js<T: serde::de::DeserializeOwned>(
    page: &chromiumoxide::Page,
    expr: &str,
) -> T {
    page.evaluate(expr)
        .await
        .unwrap_or_else(|e| panic!("{expr}: {e}"))
        .into_value()
        .unwrap_or_else(|e| panic!("{expr}: {e}"))
}

/// Whether Chromium is installed for the browser test `test`: when it is not, false (the test
/// is skipped, saying so), or a panic under CI.
pub(super) fn chromium_for(test: &str) -> bool {
    if std::path::Path::new("/usr/bin/chromium").exists() {
        return true;
    }
    if in_ci() {
        panic!("CI is set but /usr/bin/chromium is missing (.ci/run installs it)");
    }
    eprintln!("SKIPPED {test}: /usr/bin/chromium is not installed (apt-get install -y chromium)");
    false
}

/// The folder of the browser tests' screenshots (target/serve-screenshots), made.
pub(super) fn shots_dir() -> std::path::PathBuf {
    let shots = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/serve-screenshots");
    std::fs::create_dir_all(&shots).unwrap();
    shots
}

/// The runtime a browser session runs on: two worker threads.
pub(super) fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap()
}

/// A Chromium with a window and viewport of `width` × `height` and its profile in a temporary
/// folder, the task that pumps its events, and a blank page.
pub(super) struct Chromium {
    pub browser: chromiumoxide::Browser,
    pub pump: tokio::task::JoinHandle<()>,
    pub page: chromiumoxide::Page,
    /// The profile's folder, removed with it.
    pub profile: tempfile::TempDir,
}

/// Start a [`Chromium`] of `width` × `height`.
pub(super) async fn launch(width: u32, height: u32) -> Chromium {
    use chromiumoxide::browser::{Browser, BrowserConfig};
    use chromiumoxide::handler::viewport::Viewport;
    use futures::StreamExt;

    let profile = tempfile::tempdir().unwrap();
    let config = BrowserConfig::builder()
        .chrome_executable("/usr/bin/chromium")
        .no_sandbox()
        .user_data_dir(profile.path())
        .window_size(width, height)
        .viewport(Viewport {
            width,
            height,
            ..Viewport::default()
        })
        .build()
        .unwrap();
    let (browser, mut handler) = Browser::launch(config).await.expect("chromium starts");
    let pump = tokio::spawn(async move { while handler.next().await.is_some() {} });
    let page = browser.new_page("about:blank").await.unwrap();
    Chromium {
        browser,
        pump,
        page,
        profile,
    }
}

#[test]
fn serve_page_works_in_a_browser() {
    if !chromium_for("serve_page_works_in_a_browser") {
        return;
    }
    let server = Server::start();
    let url = format!("http://{}/", server.addr);
    let shots = shots_dir();
    // A small .asc fixture made by the binary itself.
    let dir = tempfile::tempdir().unwrap();
    let asc = dir.path().join("fixture-oval.asc");
    let out = Command::new(env!("CARGO_BIN_EXE_facetlab"))
        .args(["generate", "oval", "-o"])
        .arg(&asc)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let round = dir.path().join("fixture-round.asc");
    let out = Command::new(env!("CARGO_BIN_EXE_facetlab"))
        .args(["generate", "tolkowsky", "-o"])
        .arg(&round)
        .output()
        .unwrap();
    assert!(out.status.success());
    let rt = runtime();
    let rough = dir.path().join("octa.obj");
    std::fs::write(&rough, super::plan::octahedron_obj(0)).unwrap();
    // A design two of whose tiers cannot turn alone: the bundled split brilliant, as .gem.
    let split = dir.path().join("fixture-split.gem");
    let out = Command::new(env!("CARGO_BIN_EXE_facetlab"))
        .arg("generate")
        .arg(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/optim/quartz-split.asc"
        ))
        .arg("-o")
        .arg(&split)
        .output()
        .unwrap();
    assert!(out.status.success());
    rt.block_on(browser_session(&url, &shots, &asc, &round, &split, &rough));
}

async fn browser_session(
    url: &str,
    shots: &std::path::Path,
    asc: &std::path::Path,
    round: &std::path::Path,
    split: &std::path::Path,
    rough: &std::path::Path,
) {
    use chromiumoxide::cdp::js_protocol::runtime::{
        ConsoleApiCalledType, EventConsoleApiCalled, EventExceptionThrown,
    };
    use chromiumoxide::page::ScreenshotParams;
    use futures::StreamExt;

    let Chromium {
        mut browser,
        pump,
        page,
        profile: _profile,
    } = launch(1500, 950).await;
    let errors = std::sync::Arc::new(std::sync::Mutex::new(Vec::<String>::new()));
    let mut console = page
        .event_listener::<EventConsoleApiCalled>()
        .await
        .unwrap();
    let mut thrown = page.event_listener::<EventExceptionThrown>().await.unwrap();
    let e1 = errors.clone();
    tokio::spawn(async move {
        while let Some(ev) = console.next().await {
            if matches!(
                ev.r#type,
                ConsoleApiCalledType::Error | ConsoleApiCalledType::Assert
            ) {
                let args: Vec<String> = ev
                    .args
                    .iter()
                    .map(|a| {
                        a.value
                            .as_ref()
                            .map(|v| v.to_string())
                            .or_else(|| a.description.clone())
                            .unwrap_or_default()
                    })
                    .collect();
                e1.lock()
                    .unwrap()
                    .push(format!("console.error {}", args.join(" ")));
            }
        }
    });
    let e2 = errors.clone();
    tokio::spawn(async move {
        while let Some(ev) = thrown.next().await {
            let d = &ev.exception_details;
            e2.lock().unwrap().push(format!(
                "exception {} {:?}",
                d.text,
                d.exception.as_ref().and_then(|x| x.description.clone())
            ));
        }
    });
    // A collector in the page too (errors and unhandled rejections).
    page.evaluate_on_new_document(
        "window.__errs = []; window.addEventListener('error', e => window.__errs.push(String(e.message))); window.addEventListener('unhandledrejection', e => window.__errs.push('rejection: ' + String(e.reason)));",
    )
    .await
    .unwrap();
    page.goto(url).await.unwrap();
    assert!(
        wait_js(&page, "document.querySelector('#render-a').complete && document.querySelector('#render-a').naturalWidth === 512 && document.querySelector('#score-a-brilliance').textContent !== '—' && document.querySelectorAll('#params input[type=range]').length > 5", 30).await,
        "the page did not show tolkowsky's render, scores and sliders"
    );
    // Let the full scores arrive, then look at it.
    wait_js(
        &page,
        "document.querySelector('#scores').dataset.a === 'full'",
        30,
    )
    .await;
    let shot = |name: &str| shots.join(name);
    page.save_screenshot(ScreenshotParams::builder().build(), shot("1-tolkowsky.png"))
        .await
        .unwrap();
    // The first picture shows the stone's pattern (COS light with a head shadow), not a
    // near-uniform disc: the luminance of its stone pixels spreads widely.
    let spread: f64 = js(
        &page,
        "(() => { const img = document.querySelector('#render-a'); const c = document.createElement('canvas'); c.width = img.naturalWidth; c.height = img.naturalHeight; const g = c.getContext('2d'); g.drawImage(img, 0, 0); const d = g.getImageData(0, 0, c.width, c.height).data; const y = []; for (let i = 0; i < d.length; i += 4) { if (d[i] === d[0] && d[i + 1] === d[1] && d[i + 2] === d[2]) continue; y.push(0.2126 * d[i] + 0.7152 * d[i + 1] + 0.0722 * d[i + 2]); } const m = y.reduce((a, b) => a + b, 0) / y.length; return Math.sqrt(y.reduce((a, b) => a + (b - m) ** 2, 0) / y.length); })()",
    )
    .await;
    assert!(
        spread > 40.0,
        "the first picture is a near-uniform disc: luminance spread {spread:.1}"
    );
    // The stone says what it is traced in.
    let traced: String = js(
        &page,
        "document.querySelector('#prop-a-material').textContent",
    )
    .await;
    assert_eq!(traced, "diamond");

    // Move the pavilion slider by script: the picture and the scores change.
    let before_src: String = js(&page, "document.querySelector('#render-a').src").await;
    let before_b: String = js(
        &page,
        "document.querySelector('#score-a-brilliance').textContent",
    )
    .await;
    let t = Instant::now();
    let _: bool = js(
        &page,
        "(() => { const r = document.querySelector('#params input[type=range][data-key=pavilion_angle]'); r.value = '42.2'; r.dispatchEvent(new Event('input', {bubbles: true})); return true; })()",
    )
    .await;
    assert!(
        wait_js(
            &page,
            &format!("document.querySelector('#render-a').src !== {before_src:?} && document.querySelector('#render-a').complete && document.querySelector('#score-a-brilliance').textContent !== {before_b:?}"),
            30
        )
        .await,
        "moving the slider changed neither the picture nor the scores"
    );
    eprintln!(
        "slider → new picture and quick scores seen by the test after {} ms",
        t.elapsed().as_millis()
    );
    // A few more moves, one at a time: the page's own latency figures.
    let (mut pic, mut sco) = (Vec::new(), Vec::new());
    for v in ["41.0", "41.4", "40.6", "41.8", "42.2"] {
        let before_src: String = js(&page, "document.querySelector('#render-a').src").await;
        let before_b: String = js(
            &page,
            "document.querySelector('#score-a-brilliance').textContent",
        )
        .await;
        let _: bool = js(
            &page,
            &format!("(() => {{ const r = document.querySelector('#params input[type=range][data-key=pavilion_angle]'); r.value = '{v}'; r.dispatchEvent(new Event('input', {{bubbles: true}})); return true; }})()"),
        )
        .await;
        assert!(
            wait_js(
                &page,
                &format!("document.querySelector('#render-a').src !== {before_src:?} && document.querySelector('#render-a').complete && document.querySelector('#score-a-brilliance').textContent !== {before_b:?} && !document.querySelector('#score-a-brilliance').classList.contains('stale')"),
                30
            )
            .await,
            "pavilion {v}: no new picture and scores"
        );
        let p: String = js(
            &page,
            "document.querySelector('#render-a').dataset.ms || ''",
        )
        .await;
        let s: String = js(&page, "document.querySelector('#scores').dataset.ms || ''").await;
        pic.push(p.parse::<u64>().unwrap_or(0));
        sco.push(s.parse::<u64>().unwrap_or(0));
    }
    pic.sort();
    sco.sort();
    eprintln!(
        "slider → picture {pic:?} ms (median {}), → quick scores {sco:?} ms (median {})",
        pic[2], sco[2]
    );
    let num: String = js(&page, "document.querySelector('#num-pavilion_angle').value").await;
    assert_eq!(num, "42.20");

    // An out-of-range value typed in a number field: the server's message, inline.
    let _: bool = js(
        &page,
        "(() => { const n = document.querySelector('#num-crown_angle'); n.value = '75'; n.dispatchEvent(new Event('change', {bubbles: true})); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, "document.querySelector('.param[data-key=crown_angle] .err').textContent.includes('out of range')", 20).await,
        "no inline message for crown_angle 75"
    );
    page.save_screenshot(ScreenshotParams::builder().build(), shot("2-invalid.png"))
        .await
        .unwrap();
    let _: bool = js(
        &page,
        "(() => { const n = document.querySelector('#num-crown_angle'); n.value = '34.5'; n.dispatchEvent(new Event('change', {bubbles: true})); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, "document.querySelector('.param[data-key=crown_angle] .err').textContent === '' && !document.querySelector('#veil-a').classList.contains('on')", 20).await,
        "the inline message did not clear"
    );

    // Pin as B, change A's light to ASET: both pictures, the comparison columns.
    let _: bool = js(&page, "(document.querySelector('#compare').click(), true)").await;
    let _: bool = js(
        &page,
        "(() => { const l = document.querySelector('#light'); l.value = 'aset'; l.dispatchEvent(new Event('change')); return true; })()",
    )
    .await;
    let _: bool = js(
        &page,
        "(() => { const r = document.querySelector('#params input[type=range][data-key=table]'); r.value = '0.57'; r.dispatchEvent(new Event('input', {bubbles: true})); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, "!document.querySelector('#view-b').hidden && document.querySelector('#render-a').dataset.light === 'aset' && document.querySelector('#render-b').dataset.light === 'aset' && document.querySelector('#score-d-brilliance').textContent.trim().slice(1) !== '0.0000' && !document.querySelector('#render-a').parentElement.classList.contains('busy')", 30).await,
        "the comparison did not show"
    );
    wait_js(&page, "document.querySelector('#scores').dataset.a === 'full' && document.querySelector('#scores').dataset.b === 'full'", 30).await;
    page.save_screenshot(
        ScreenshotParams::builder().build(),
        shot("3-compare-aset.png"),
    )
    .await
    .unwrap();

    // Upload the .asc through the file input (DOM.setFileInputFiles).
    upload(&page, asc).await;
    assert!(
        wait_js(&page, "document.querySelector('#cut-name').textContent === 'fixture-oval' && document.querySelector('#preset').value === '__file' && document.querySelectorAll('#params .param.tier input[type=range]').length > 5 && document.querySelector('#params-note').textContent.includes('meets')", 30).await,
        "the uploaded .asc did not load with one slider per tier"
    );
    // Its tiers are sliders labelled by the design's names, in steps of 0.01°.
    let step: String = js(
        &page,
        "document.querySelector('#params input[type=range][data-key=pavilion-main]').step",
    )
    .await;
    assert_eq!(step, "0.01");
    // The oval's mains alone cannot keep their meets: the server's refusal, next to the
    // slider, and the last good picture stays.
    assert!(
        wait_js(&page, "document.querySelector('#render-a').dataset.name === 'fixture-oval' && !document.querySelector('#render-a').parentElement.classList.contains('busy')", 60).await,
        "the uploaded design was not rendered"
    );
    let before_src: String = js(&page, "document.querySelector('#render-a').src").await;
    let _: bool = js(
        &page,
        "(() => { const r = document.querySelector('#params input[type=range][data-key=pavilion-main]'); r.value = '41.5'; r.dispatchEvent(new Event('input', {bubbles: true})); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, "document.querySelector('.param[data-key=pavilion-main] .err').textContent.includes('meet')", 30).await,
        "no refusal next to the pavilion-main slider"
    );
    let after_src: String = js(&page, "document.querySelector('#render-a').src").await;
    assert_eq!(before_src, after_src, "the last good picture was not kept");
    // The notes on which tiers cannot move alone arrive from the background probe.
    wait_js(
        &page,
        "document.querySelector('.param[data-key=pavilion-main] .note').textContent.includes('alone opens')",
        30,
    )
    .await;
    page.save_screenshot(
        ScreenshotParams::builder().build(),
        shot("4-design-refused.png"),
    )
    .await
    .unwrap();
    let _: bool = js(&page, "(document.querySelector('#reset').click(), true)").await;
    let _: bool = js(
        &page,
        "(() => { const l = document.querySelector('#light'); l.value = 'fire'; l.dispatchEvent(new Event('change')); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, "document.querySelector('#render-a').dataset.name === 'fixture-oval' && document.querySelector('#render-a').dataset.light === 'fire' && document.querySelector('#render-b').dataset.light === 'fire' && document.querySelector('#cap-a').textContent.includes('Fire')", 60).await,
        "the uploaded cut was not rendered and scored"
    );
    wait_js(
        &page,
        "document.querySelector('#scores').dataset.a === 'full'",
        30,
    )
    .await;
    page.save_screenshot(
        ScreenshotParams::builder().build(),
        shot("5-upload-fire.png"),
    )
    .await
    .unwrap();

    // A round design: its mains turn alone, the depths follow, picture and scores change.
    let _: bool = js(&page, "(document.querySelector('#clear-b').click(), true)").await;
    upload(&page, round).await;
    assert!(
        wait_js(&page, "document.querySelector('#render-a').dataset.name === 'fixture-round' && document.querySelector('#score-a-brilliance').textContent !== '—' && !document.querySelector('#score-a-brilliance').classList.contains('stale') && document.querySelector('#params input[type=range][data-key=pavilion-main]') !== null", 60).await,
        "the round design did not load with its sliders"
    );
    let before_src: String = js(&page, "document.querySelector('#render-a').src").await;
    let before_b: String = js(
        &page,
        "document.querySelector('#score-a-brilliance').textContent",
    )
    .await;
    let _: bool = js(
        &page,
        "(() => { const r = document.querySelector('#params input[type=range][data-key=pavilion-main]'); r.value = '41.2'; r.dispatchEvent(new Event('input', {bubbles: true})); return true; })()",
    )
    .await;
    assert!(
        wait_js(
            &page,
            &format!("document.querySelector('#render-a').src !== {before_src:?} && document.querySelector('#score-a-brilliance').textContent !== {before_b:?} && !document.querySelector('#score-a-brilliance').classList.contains('stale') && document.querySelector('#prop-a-pavilion_angle').textContent === '41.20 °'"),
            30
        )
        .await,
        "moving the design's pavilion-main slider changed neither the picture nor the scores"
    );
    let facets: String = js(
        &page,
        "document.querySelector('#prop-a-facet_count').textContent",
    )
    .await;
    assert_eq!(facets, "73");
    wait_js(
        &page,
        "document.querySelector('#scores').dataset.a === 'full' && document.querySelector('#params-note').textContent.includes('alone')",
        30,
    )
    .await;
    page.save_screenshot(
        ScreenshotParams::builder().build(),
        shot("6-design-turned.png"),
    )
    .await
    .unwrap();

    // A .gem whose main tiers meet at the culet: the note under P1 offers the tie; tied, the
    // two sliders move together and the design turns.
    upload(&page, split).await;
    assert!(
        wait_js(&page, "document.querySelector('#render-a').dataset.name === 'fixture-split' && document.querySelector('#params input[type=range][data-key=P1b]') !== null && !document.querySelector('#score-a-brilliance').classList.contains('stale')", 60).await,
        "the .gem design did not load with its sliders"
    );
    assert!(
        wait_js(&page, "document.querySelector('.param[data-key=P1] .note .tie-it') !== null && document.querySelector('.param[data-key=P1] .note .tie-it').textContent === 'tie P1+P1b'", 30).await,
        "no tie offered under P1"
    );
    let before_src: String = js(&page, "document.querySelector('#render-a').src").await;
    let _: bool = js(
        &page,
        "(() => { document.querySelector('.param[data-key=P1] .note .tie-it').click(); const r = document.querySelector('#params input[type=range][data-key=P1]'); r.value = '42'; r.dispatchEvent(new Event('input', {bubbles: true})); return true; })()",
    )
    .await;
    assert!(
        wait_js(
            &page,
            &format!("document.querySelector('#params input[type=number][data-key=P1b]').value === '42.00' && document.querySelector('.param[data-key=P1b] .tie input').checked && document.querySelector('#render-a').src !== {before_src:?} && document.querySelector('.param[data-key=P1] .err').textContent === '' && !document.querySelector('#score-a-brilliance').classList.contains('stale')"),
            30
        )
        .await,
        "the tied sliders did not move together and turn the design"
    );
    page.save_screenshot(
        ScreenshotParams::builder().build(),
        shot("6b-design-tied.png"),
    )
    .await
    .unwrap();

    // The stone in its own colour, wider: the colour rows, a green picture, its caption.
    let _: bool = js(
        &page,
        "(() => { const l = document.querySelector('#light'); l.value = 'iso'; l.dispatchEvent(new Event('change')); const o = document.querySelector('#own-colour'); o.checked = true; o.dispatchEvent(new Event('change')); const c = document.querySelector('#colour'); c.value = '#2e8b57'; c.dispatchEvent(new Event('input')); const w = document.querySelector('#stone-mm'); w.value = '8'; w.dispatchEvent(new Event('change')); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, "document.body.classList.contains('coloured') && document.querySelector('#score-a-colour-l').textContent !== '—' && document.querySelector('#cap-a').textContent.includes('L*') && document.querySelector('#prop-a-carats').parentElement.firstChild.textContent === 'Weight at 8 mm' && !document.querySelector('#render-a').parentElement.classList.contains('busy')", 60).await,
        "the colour rows and the coloured picture did not show"
    );
    // The picture's mean colour over the stone is green.
    let mean: Vec<f64> = js(
        &page,
        "(() => { const i = document.querySelector('#render-a'); const c = document.createElement('canvas'); c.width = i.naturalWidth; c.height = i.naturalHeight; const g = c.getContext('2d'); g.drawImage(i, 0, 0); const d = g.getImageData(0, 0, c.width, c.height).data; const bg = [d[0], d[1], d[2]]; const s = [0, 0, 0]; let n = 0; for (let k = 0; k < d.length; k += 4) { if (d[k] === bg[0] && d[k + 1] === bg[1] && d[k + 2] === bg[2]) continue; s[0] += d[k]; s[1] += d[k + 1]; s[2] += d[k + 2]; n++; } return s.map((x) => x / Math.max(1, n)); })()",
    )
    .await;
    assert!(
        mean[1] > mean[0] + 5.0 && mean[1] > mean[2],
        "not green: {mean:?}"
    );
    wait_js(
        &page,
        "document.querySelector('#scores').dataset.a === 'full'",
        30,
    )
    .await;
    page.save_screenshot(ScreenshotParams::builder().build(), shot("7-colour.png"))
        .await
        .unwrap();

    // Plan from an uploaded rough: its plans in the table, the first one's three views.
    upload_to(&page, "#plan-file", rough).await;
    assert!(
        wait_js(
            &page,
            "document.querySelector('#plan-rough').value === '__upload'",
            10
        )
        .await,
        "the rough was not taken"
    );
    let _: bool = js(&page, "(document.querySelector('#plan-run').click(), true)").await;
    assert!(
        wait_js(&page, "document.querySelectorAll('#plan-table tbody tr').length === 2 && !document.querySelector('#plan-table').hidden && document.querySelector('#plan-views').complete && document.querySelector('#plan-views').naturalWidth > 100 && document.querySelector('#plan-status').textContent.includes('done')", 120).await,
        "the plans did not show"
    );
    let _: bool = js(
        &page,
        "(document.querySelector('#plan-views').scrollIntoView({block: 'end'}), true)",
    )
    .await;
    page.save_screenshot(ScreenshotParams::builder().build(), shot("8-plan.png"))
        .await
        .unwrap();
    // The chosen plan as A: its family and parameters, at its width: the plan's carats.
    let carats: f64 = js(&page, "plan.chosen.carats").await;
    let _: bool = js(
        &page,
        "(document.querySelector('#plan-open').click(), true)",
    )
    .await;
    assert!(
        wait_js(&page, "document.querySelector('#cut-family').textContent.includes('round-brilliant') && document.querySelector('#prop-a-carats').textContent !== '—' && document.querySelectorAll('#params .param.changed').length > 0 && !document.querySelector('#render-a').parentElement.classList.contains('busy')", 60).await,
        "the plan did not open as A"
    );
    let shown: String = js(
        &page,
        "document.querySelector('#prop-a-carats').textContent",
    )
    .await;
    let shown: f64 = shown.trim_end_matches(" ct").parse().unwrap();
    assert!(
        (shown - carats).abs() < 1.5e-3,
        "the workbench weighs {shown} ct, the plan {carats} ct"
    );
    page.save_screenshot(ScreenshotParams::builder().build(), shot("9-plan-as-a.png"))
        .await
        .unwrap();

    // The photo view: the studio map, the light turned by the slider; quick pictures while it
    // moves, the full one after; a white ground.
    let _: bool = js(
        &page,
        "(() => { const l = document.querySelector('#light'); l.value = 'studio'; l.dispatchEvent(new Event('change')); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, "!document.querySelector('#photo-bar').hidden && document.querySelector('#render-a').dataset.light === 'studio' && document.querySelector('#render-a').dataset.quick === '0' && !document.querySelector('#render-a').parentElement.classList.contains('busy')", 60).await,
        "the photo view did not show"
    );
    let full_src: String = js(&page, "document.querySelector('#render-a').src").await;
    let _: bool = js(
        &page,
        "(() => { const r = document.querySelector('#rotation'); r.value = '120'; r.dispatchEvent(new Event('input', {bubbles: true})); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, "document.querySelector('#render-a').dataset.rotation === '120' && document.querySelector('#render-a').dataset.quick === '1'", 30).await,
        "turning the light gave no quick picture"
    );
    let quick_ms: String = js(&page, "document.querySelector('#render-a').dataset.ms").await;
    eprintln!("photo view: light rotation slider → quick 512² picture in {quick_ms} ms");
    assert!(
        wait_js(&page, "document.querySelector('#render-a').dataset.rotation === '120' && document.querySelector('#render-a').dataset.quick === '0'", 60).await,
        "the full picture did not follow the quick one"
    );
    let turned_src: String = js(&page, "document.querySelector('#render-a').src").await;
    assert_ne!(full_src, turned_src);
    let cap: String = js(&page, "document.querySelector('#cap-a').textContent").await;
    assert!(
        cap.contains("light turned 120°") && cap.contains("view 30°"),
        "{cap}"
    );
    let _: bool = js(
        &page,
        "(() => { const g = document.querySelector('#ground'); g.value = 'white'; g.dispatchEvent(new Event('input', {bubbles: true})); return true; })()",
    )
    .await;
    assert!(
        wait_js(&page, "document.querySelector('#cap-a').textContent.includes('white ground') && document.querySelector('#render-a').dataset.quick === '0' && !document.querySelector('#render-a').parentElement.classList.contains('busy')", 90).await,
        "the ground did not show"
    );
    page.save_screenshot(ScreenshotParams::builder().build(), shot("10-photo.png"))
        .await
        .unwrap();

    let page_errs: Vec<String> = js(&page, "window.__errs || []").await;
    let errs = errors.lock().unwrap().clone();
    assert!(
        errs.is_empty() && page_errs.is_empty(),
        "browser errors: {errs:?} {page_errs:?}"
    );
    let _ = browser.close().await;
    let _ = browser.wait().await;
    pump.abort();
}
