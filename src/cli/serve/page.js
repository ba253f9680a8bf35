// facetlab workbench: plain JavaScript over the JSON API of `facetlab serve`.
'use strict';

const $ = (sel) => document.querySelector(sel);

// Score rows: key in `score --json`, label, whether higher is better (null: neither).
const SCORE_ROWS = [
  ['overhead_light_return', 'Overhead return', true],
  ['brilliance', 'Brilliance', true],
  ['brilliance_iso', 'ISO', true, true],
  ['brilliance_cos', 'COS', true, true],
  ['fire', 'Fire', true],
  ['scintillation', 'Scintillation', true],
  ['aset.blue', 'ASET blue 75–80°', null],
  ['aset.red', 'ASET red 45–75°', null],
  ['aset.green', 'ASET green 0–45°', null],
  ['aset.leak', 'ASET leak <0°', false],
  ['aset.port', 'ASET port 80–90°', null],
  // A coloured stone's face-up colour (shown when a slot has one).
  ['colour.l', 'Colour L*', null, false, true],
  ['colour.c', 'Colour C*', null, false, true],
  ['colour.h_deg', 'Colour h°', null, false, true],
  ['colour.extinction', 'Extinction', false, false, true],
  ['colour.windowing', 'Windowing', false, false, true],
];
// Proportion rows: key in `info --json` proportions, label, unit.
const PROP_ROWS = [
  ['table', 'Table', '%'],
  ['crown_angle', 'Crown angle', '°'],
  ['pavilion_angle', 'Pavilion angle', '°'],
  ['crown_height', 'Crown height', '%'],
  ['pavilion_depth', 'Pavilion depth', '%'],
  ['total_depth', 'Total depth', '%'],
  ['girdle', 'Girdle', '%'],
];
// The lights, from /api/presets' `light_table` (the library's one table): each one's menu
// title, whether it is a photograph's (a camera under a studio rig), the exposure it is first
// shown at (null: a false colour, which takes none) and its default head shadow.
let LIGHTS = {};
const isPhoto = (l) => !!(LIGHTS[l] && LIGHTS[l].photo);
const lightLabel = (l) => (LIGHTS[l] ? LIGHTS[l].label : l);
const firstExposure = (l) => (LIGHTS[l] ? LIGHTS[l].exposure : 1);
// Lights whose picture takes the head-shadow control: the laboratory ones under an open sky
// (the others have a port, head or tube of their own, or are photographs).
const takesHeadShadow = (l) => !!(LIGHTS[l] && LIGHTS[l].head_shadow_deg === 0);
const QUICK_DELAY = 15;     // ms of quiet before a request leaves (debounce) …
const MAX_WAIT = 100;       // … but while a slider keeps moving, one leaves at least this often
const FULL_DELAY = 700;     // ms of quiet before the full (slow) scores are asked for

// The page opens on COS light with a 15° head shadow, the report's brightness picture: the
// even ISO sky shows a good stone as a nearly uniform bright disc, the cosine sky and the
// viewer's head give the contrast a cutter looks at.
const FIRST_LIGHT = 'cos';

const state = {
  meta: null,
  light: FIRST_LIGHT,
  tilt: 0,
  exposure: 1, // the light's own once the table is read (start)
  // The viewer's head shadow (half-angle, degrees) of the ISO, COS and fire pictures.
  headShadow: 15,
  // A photograph's camera elevation, light rotation and ground.
  view: 30,
  rotation: 0,
  ground: 'none',
  // The camera's entrance pupil in mm ('' = the default ±1° filter, '0' = a pinhole).
  aperture: '',
  slots: { a: null, b: null },
  // The stone's material, body colour and width (both slots): see stoneBody(). Material ''
  // is each cut's own (a design's index or notes, else diamond), as every command traces it.
  stone: { material: '', own: false, colour: '#7a3fa0', colourMm: 10, density: 1, width: 6.5, axis: null },
};

function newSlot(source) {
  // design: a cut without a family whose tier angles are sliders (`design_space` of /api/cut);
  // lastKey: the slider moved last (a refusal that names no tier is shown there).
  // tied: the design's tiers whose sliders move together (by one change of angle).
  return { source, base: {}, set: {}, tied: new Set(), family: null, design: null, designError: '', lastKey: null, info: null, scores: null, quick: true, t0: 0, img: null, ms: {} };
}

// ---- requests -------------------------------------------------------------------------------

const inflight = new Map();

// POST `body` to `path`; a newer request with the same `key` aborts this one.
async function api(key, path, body, as) {
  const prev = inflight.get(key);
  if (prev) prev.abort();
  const ctl = new AbortController();
  inflight.set(key, ctl);
  try {
    const r = await fetch(path, {
      method: 'POST',
      headers: { 'content-type': 'application/json' },
      body: JSON.stringify(body),
      signal: ctl.signal,
    });
    if (!r.ok) {
      let e;
      try { e = await r.json(); } catch (_) { e = { error: `HTTP ${r.status}`, field: '' }; }
      const err = new Error(e.error || `HTTP ${r.status}`);
      err.field = e.field || '';
      err.api = true;
      throw err;
    }
    if (as === 'blob') return { blob: await r.blob(), headers: r.headers };
    return await r.json();
  } finally {
    if (inflight.get(key) === ctl) inflight.delete(key);
  }
}

const aborted = (e) => e && e.name === 'AbortError';

// The stone's fields of a score, render or cut request: material, colour, colour_density,
// diameter_mm (validated by the server into the library's types).
function stoneBody() {
  const st = state.stone;
  const b = { diameter_mm: st.width };
  if (st.material) b.material = st.material;
  if (st.own) b.colour = `${st.colour}@${st.colourMm}mm`;
  if (coloured() && st.density !== 1) b.colour_density = st.density;
  if (st.axis !== null) b.optic_axis = st.axis;
  return b;
}

// Whether the stone has a body colour: its own, or a coloured variety's.
function coloured() {
  const st = state.stone;
  if (st.own) return true;
  const m = state.meta && state.meta.materials.find((x) => x.name === st.material);
  return !!(m && m.colour);
}

function requestBody(s, extra) {
  const stone = extra && extra.to ? {} : stoneBody();
  return Object.assign({}, s.source, { set: s.set }, stone, extra || {});
}

// ---- refreshing a slot ----------------------------------------------------------------------

const timers = {};

const firstCall = {};

// Debounce with a longest wait: quiet for QUICK_DELAY ms, or MAX_WAIT ms since the first
// change not yet sent, whichever comes first. A newer request aborts the stale one (api()).
function schedule(name, what, delay) {
  const k = name + what;
  clearTimeout(timers[k]);
  const now = performance.now();
  if (firstCall[k] === undefined) firstCall[k] = now;
  let wait = delay === undefined ? QUICK_DELAY : delay;
  wait = Math.max(0, Math.min(wait, firstCall[k] + MAX_WAIT - now));
  timers[k] = setTimeout(() => {
    delete firstCall[k];
    refresh(name, what);
  }, wait);
}

function refresh(name, what) {
  const s = state.slots[name];
  if (!s) return;
  if (what === 'render') doRender(name);
  if (what === 'photo') doRender(name, false);
  if (what === 'all') {
    // The picture first, then the quick scores: both use every core of the server, so
    // asking for them one after the other shows the picture sooner and the scores no later.
    clearTimeout(timers[name + 'full']);
    markStale(name);
    s.needScore = true;
    doInfo(name);
    doRender(name);
  }
}

// A photograph is drawn quick while its controls move (one wavelength, coarser beams) and
// in full FULL_DELAY ms after the last change; `quick` false asks for the full one.
async function doRender(name, quick) {
  const s = state.slots[name];
  const t = performance.now();
  const t0 = s.t0 || t;
  const img = $('#render-' + name);
  const frame = img.parentElement;
  const want = { light: state.light, tilt: state.tilt, exposure: state.exposure };
  if (takesHeadShadow(state.light)) want.head_shadow = state.headShadow;
  const photo = isPhoto(state.light);
  clearTimeout(timers[name + 'photo']);
  if (photo) {
    Object.assign(want, { view: state.view, light_rotation: state.rotation, ground: state.ground });
    if (state.aperture !== '') want.aperture = Number(state.aperture);
    want.quick = quick !== false;
  }
  frame.classList.add('busy');
  try {
    const { blob, headers } = await api('render-' + name, '/api/render', requestBody(s, Object.assign({ size: 512 }, want)), 'blob');
    if (photo && want.quick) timers[name + 'photo'] = setTimeout(() => refresh(name, 'photo'), FULL_DELAY);
    if (state.slots[name] !== s) return false;
    const url = URL.createObjectURL(blob);
    const old = s.img;
    s.img = url;
    let stats = null;
    try { stats = JSON.parse(headers.get('x-facetlab-stats') || 'null'); } catch (_) { stats = null; }
    img.onload = () => {
      if (old && old !== url) URL.revokeObjectURL(old);
      const now = performance.now();
      s.ms.render = Math.round(now - t);
      s.ms.slider = Math.round(now - t0);
      img.dataset.ms = String(s.ms.slider);
      img.dataset.light = want.light;
      img.dataset.quick = want.quick ? '1' : '0';
      img.dataset.rotation = photo ? String(want.light_rotation) : '';
      img.dataset.name = s.info ? s.info.name : '';
      s.shown = Object.assign({ stats, name: s.info ? s.info.name : '', changed: Object.keys(s.set).length }, want);
      frame.classList.remove('busy');
      caption(name);
      showStatus();
    };
    img.src = url;
    clearError(name);
    if (s.needScore) {
      s.needScore = false;
      doScore(name, true);
    }
    return true;
  } catch (e) {
    if (!aborted(e)) {
      frame.classList.remove('busy');
      s.needScore = false;
      showError(name, e);
    }
    return false;
  }
}

async function doScore(name, quick) {
  const s = state.slots[name];
  const t = performance.now();
  const t0 = s.t0 || t;
  try {
    const j = await api('score-' + name, '/api/score', requestBody(s, { quick }));
    if (state.slots[name] !== s) return;
    s.scores = j;
    s.quick = quick;
    $('#scores').dataset[name] = quick ? 'quick' : 'full';
    const now = performance.now();
    s.ms[quick ? 'quick' : 'full'] = Math.round(now - t);
    if (quick) {
      s.ms.scoreSlider = Math.round(now - t0);
      $('#scores').dataset.ms = String(s.ms.scoreSlider);
    }
    fillScores();
    showStatus();
    if (quick) {
      clearTimeout(timers[name + 'full']);
      timers[name + 'full'] = setTimeout(() => doScore(name, false), FULL_DELAY);
    }
  } catch (e) {
    if (!aborted(e)) showError(name, e);
  }
}

async function doInfo(name) {
  const s = state.slots[name];
  try {
    // A recipe's stone (the tier editor's, recipe.js) is built by /api/recipe/build, which
    // answers as /api/cut does without adopting the design's tier angles as sliders.
    const j = await api('info-' + name, s.recipe ? '/api/recipe/build' : '/api/cut', s.recipe ? Object.assign({}, s.source, stoneBody()) : requestBody(s));
    if (state.slots[name] !== s) return;
    s.info = j;
    takeNotes(s, j);
    fillProps();
    caption(name);
    if (name === 'a') showDiagram(j.svg);
  } catch (e) {
    if (!aborted(e)) showError(name, e);
  }
}

let diagramUrl = null;
function showDiagram(svg) {
  const url = URL.createObjectURL(new Blob([svg], { type: 'image/svg+xml' }));
  const img = $('#diagram');
  img.onload = () => { if (diagramUrl && diagramUrl !== url) URL.revokeObjectURL(diagramUrl); diagramUrl = url; };
  img.src = url;
  $('#diagram-link').href = url;
}

// ---- loading a cut --------------------------------------------------------------------------

async function loadSource(source, label) {
  $('#source-err').textContent = '';
  const s = newSlot(source);
  let info;
  try {
    info = await api('load', '/api/cut', Object.assign({}, source));
  } catch (e) {
    if (!aborted(e)) $('#source-err').textContent = e.message;
    return false;
  }
  s.info = info;
  s.family = info.family || null;
  s.base = Object.assign({}, info.params || {});
  const ds = info.design_space;
  if (!s.family && ds && ds.tiers) {
    s.design = ds;
    for (const t of ds.tiers) s.base[t.key] = t.default;
  } else if (!s.family && ds && ds.error) {
    s.designError = ds.error;
  }
  state.slots.a = s;
  if (label) setFileOption(label);
  buildParams();
  fillProps();
  showDiagram(info.svg);
  caption('a');
  refresh('a', 'all');
  if (s.design && !s.design.probed) pollNotes(s, 0);
  return true;
}

// The meets each tier opens alone are probed in the background after a design's first
// answer: ask again (cheap, the design is cached) until they are known.
function pollNotes(s, n) {
  if (n > 40 || state.slots.a !== s || !s.design || s.design.probed) return;
  setTimeout(async () => {
    if (state.slots.a !== s || s.design.probed) return;
    try {
      const j = await api('notes', '/api/cut', Object.assign({}, s.source));
      takeNotes(s, j);
    } catch (e) {
      if (aborted(e)) return;
    }
    pollNotes(s, n + 1);
  }, n < 5 ? 500 : 1500);
}

// Take a design's probed notes from an answer of /api/cut, and show them.
function takeNotes(s, j) {
  const ds = j && j.design_space;
  if (!s.design || !ds || !ds.probed || s.design.probed) return;
  s.design = ds;
  if (state.slots.a === s) showNotes();
}

function showNotes() {
  const s = state.slots.a;
  if (!s || !s.design) return;
  for (const t of s.design.tiers) {
    const row = document.querySelector(`.param[data-key="${CSS.escape(t.key)}"]`);
    if (!row) continue;
    const el = row.querySelector('.note');
    const meets = t.alone_opens || [];
    el.textContent = meets.length === 0 ? ''
      : `moving ${t.key} alone opens the meet ${meets[0]}` + (meets.length > 1 ? ` (and ${meets.length - 1} more)` : '');
    el.title = meets.join('\n');
    if (meets.length && t.tie) {
      // The smallest tie that keeps the meets: one click ties those sliders.
      const b = document.createElement('button');
      b.type = 'button';
      b.className = 'small tie-it';
      b.textContent = `tie ${t.tie}`;
      b.title = 'move these tiers together, by one change of angle: every meet stays';
      b.addEventListener('click', () => {
        for (const k of t.tie.split('+')) setTied(k, true);
      });
      el.append(' — ', b);
    }
  }
  designNote();
}

// The note under a design's sliders: what the sliders do.
function designNote() {
  const s = state.slots.a;
  if (!s || !s.design) return;
  const d = s.design;
  const stuck = d.probed ? d.tiers.filter((t) => (t.alone_opens || []).length).length : 0;
  let text = `${d.tiers.length} tier angles; each depth is solved so that the design's ${d.meets} meets stay meets.`;
  text += d.probed ? (stuck ? ` ${stuck} of the tiers cannot move alone: tie them (☐ tie) to the tiers of the meet they open, and the tied sliders move together.` : ' Moved alone, every tier keeps its meets.')
    : ' Checking which tiers can move alone…';
  $('#params-note').textContent = text;
}

function setFileOption(label) {
  const sel = $('#preset');
  let opt = sel.querySelector('option[value="__file"]');
  if (!opt) {
    opt = document.createElement('option');
    opt.value = '__file';
    sel.prepend(opt);
  }
  opt.textContent = 'File: ' + label;
  sel.value = '__file';
}

function readFile(file) {
  const ext = (file.name.split('.').pop() || '').toLowerCase();
  if (!state.meta.formats.includes(ext)) {
    $('#source-err').textContent = `cut: ${file.name} is not a .asc, .gem, .obj, .stl or .toml file`;
    return;
  }
  const limit = state.meta.limits.body_bytes;
  const binary = ext === 'stl' || ext === 'gem';
  if (file.size > (binary ? limit * 0.7 : limit * 0.9)) {
    $('#source-err').textContent = `cut: ${file.name} is too large (over ${Math.round(limit / 1048576)} MB)`;
    return;
  }
  const reader = new FileReader();
  reader.onerror = () => { $('#source-err').textContent = `cut: could not read ${file.name}`; };
  if (binary) {
    reader.onload = () => {
      const bytes = new Uint8Array(reader.result);
      let bin = '';
      for (let i = 0; i < bytes.length; i += 0x8000) bin += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
      loadSource({ cut: btoa(bin), format: ext, encoding: 'base64', name: file.name }, file.name);
    };
    reader.readAsArrayBuffer(file);
  } else {
    reader.onload = () => loadSource({ cut: String(reader.result), format: ext, name: file.name }, file.name);
    reader.readAsText(file);
  }
}

// ---- parameters -----------------------------------------------------------------------------

function decimals(step) {
  const s = String(step);
  return s.includes('.') ? s.length - s.indexOf('.') - 1 : 0;
}

function buildParams() {
  const s = state.slots.a;
  const box = $('#params');
  box.textContent = '';
  $('#params-note').textContent = '';
  const fam = s.family && state.meta.families.find((f) => f.name === s.family);
  const params = fam ? fam.params : s.design ? s.design.tiers : null;
  $('#reset').hidden = !params;
  if (!params) {
    $('#params-note').textContent = 'An explicit facet design: it has no family parameters, and its tier angles cannot turn'
      + (s.designError ? ` (${s.designError})` : '') + '. Pin it as B and load a preset to compare.';
    return;
  }
  for (const p of params) {
    const value = p.key in s.set ? s.set[p.key] : (p.key in s.base ? s.base[p.key] : p.default);
    const dec = decimals(p.step);
    const lo = p.open ? p.min + p.step : p.min;
    const hi = p.open ? p.max - p.step : p.max;
    const row = document.createElement('div');
    row.className = 'param' + (p.key in s.set ? ' changed' : '');
    row.dataset.key = p.key;
    const unit = p.unit === 'degrees' ? '°' : p.unit === 'fraction' ? '× D' : p.unit === 'ratio' ? 'ratio' : '';
    row.innerHTML = `<div class="head"><label class="key"></label><span class="unit"></span>${fam ? '' : '<label class="tie"><input type="checkbox"> tie</label>'}</div>
      <div class="ctl"><input type="range"><input type="number"></div><div class="err" role="alert"></div><div class="note"></div>`;
    const label = row.querySelector('label');
    label.textContent = fam ? p.key.replace(/_/g, ' ') : p.key;
    label.title = p.doc;
    label.htmlFor = 'num-' + p.key;
    row.querySelector('.unit').textContent = fam
      ? `${unit} ${p.open ? '(' : '['}${p.min}, ${p.max}${p.open ? ')' : ']'}`
      : `${unit} (was ${p.default.toFixed(2)}°)`;
    const range = row.querySelector('input[type=range]');
    const num = row.querySelector('input[type=number]');
    num.id = 'num-' + p.key;
    if (!fam) row.classList.add('tier');
    range.setAttribute('aria-label', p.key);
    for (const el of [range, num]) {
      el.min = String(lo);
      el.max = String(hi);
      el.step = String(p.step);
      el.dataset.key = p.key;
    }
    range.value = String(value);
    num.value = Number(value).toFixed(dec);
    const tie = row.querySelector('.tie input');
    if (tie) {
      tie.checked = s.tied.has(p.key);
      tie.setAttribute('aria-label', `tie ${p.key}`);
      tie.addEventListener('change', () => setTied(p.key, tie.checked));
    }
    range.addEventListener('input', () => {
      num.value = Number(range.value).toFixed(dec);
      moveTied(p.key, Number(range.value));
      setParam(p.key, Number(range.value));
    });
    num.addEventListener('change', () => {
      const v = num.value.trim() === '' ? NaN : Number(num.value);
      if (Number.isFinite(v)) {
        range.value = String(v);
        num.value = v.toFixed(Math.max(dec, decimals(v)));
      }
      if (Number.isFinite(v)) moveTied(p.key, v);
      setParam(p.key, Number.isFinite(v) ? v : null);
    });
    box.appendChild(row);
  }
  if (s.design) showNotes();
}

// Tie or untie a design's tier: tied sliders move together.
function setTied(key, on) {
  const s = state.slots.a;
  if (on) s.tied.add(key); else s.tied.delete(key);
  const box = document.querySelector(`.param[data-key="${CSS.escape(key)}"] .tie input`);
  if (box) box.checked = on;
}

// A tied tier moved to `v`: the other tied tiers turn by the same change of angle.
function moveTied(key, v) {
  const s = state.slots.a;
  if (!s.tied.has(key) || s.tied.size < 2) return;
  const now = (k) => (k in s.set ? s.set[k] : s.base[k]);
  const d = v - now(key);
  for (const k of s.tied) {
    if (k === key || now(k) === undefined) continue;
    const w = Math.round((now(k) + d) * 1e6) / 1e6;
    if (Math.abs(w - s.base[k]) < 1e-12) delete s.set[k];
    else s.set[k] = w;
    const row = document.querySelector(`.param[data-key="${CSS.escape(k)}"]`);
    if (!row) continue;
    row.classList.toggle('changed', k in s.set);
    row.querySelector('input[type=range]').value = String(w);
    row.querySelector('input[type=number]').value = w.toFixed(2);
  }
}

function setParam(key, v) {
  const s = state.slots.a;
  if (v !== null && s.base[key] !== undefined && Math.abs(v - s.base[key]) < 1e-12) delete s.set[key];
  else s.set[key] = v;
  const row = document.querySelector(`.param[data-key="${CSS.escape(key)}"]`);
  if (row) row.classList.toggle('changed', key in s.set);
  s.lastKey = key;
  s.t0 = performance.now();
  schedule('a', 'all');
}

// ---- showing results ------------------------------------------------------------------------

function get(obj, path) {
  return path.split('.').reduce((o, k) => (o == null ? undefined : o[k]), obj);
}

function fmtScore(key, v) {
  if (typeof v !== 'number') return '—';
  if (key === 'colour.l' || key === 'colour.c' || key === 'colour.h_deg') return v.toFixed(1);
  return v.toFixed(key === 'fire' ? 3 : 4);
}

function buildTables() {
  const tb = $('#scores tbody');
  tb.textContent = '';
  for (const [key, label, , indent, colourRow] of SCORE_ROWS) {
    const tr = document.createElement('tr');
    if (colourRow) tr.className = 'colour-row';
    const id = key.replace('.', '-');
    tr.innerHTML = `<td></td><td id="score-a-${id}">—</td><td class="b-col" id="score-b-${id}">—</td><td class="b-col" id="score-d-${id}"></td>`;
    tr.firstChild.textContent = label;
    if (indent) tr.firstChild.classList.add('indent');
    tb.appendChild(tr);
  }
  const pb = $('#props tbody');
  pb.textContent = '';
  const rows = PROP_ROWS.concat([['facet_count', 'Facets', ''], ['material', 'Traced in', ''], ['carats', 'Weight', 'ct']]);
  for (const [key, label] of rows) {
    const tr = document.createElement('tr');
    tr.innerHTML = `<td></td><td id="prop-a-${key}">—</td><td class="b-col" id="prop-b-${key}">—</td>`;
    tr.firstChild.textContent = label;
    pb.appendChild(tr);
  }
}

function markStale(name) {
  for (const [key] of SCORE_ROWS) {
    const el = document.getElementById(`score-${name}-${key.replace('.', '-')}`);
    if (el) el.classList.add('stale');
  }
}

function fillScores() {
  const a = state.slots.a, b = state.slots.b;
  for (const [key, , better] of SCORE_ROWS) {
    const id = key.replace('.', '-');
    const va = a && a.scores ? get(a.scores, key) : undefined;
    const vb = b && b.scores ? get(b.scores, key) : undefined;
    const ea = $('#score-a-' + id), eb = $('#score-b-' + id), ed = $('#score-d-' + id);
    // Quick scores are coarse estimates of the same scores (fewer poses, bands, placements
    // and pixels): marked ≈ so a quick 0.89 is not read as the score's fire.
    const approx = (s, v) => (s && s.quick && typeof v === 'number' ? '≈ ' : '');
    ea.textContent = approx(a, va) + fmtScore(key, va);
    eb.textContent = approx(b, vb) + fmtScore(key, vb);
    ea.classList.remove('stale');
    eb.classList.remove('stale');
    ed.className = 'b-col';
    if (typeof va === 'number' && typeof vb === 'number') {
      const d = va - vb;
      ed.textContent = (d >= 0 ? '+' : '−') + fmtScore(key, Math.abs(d));
      if (better !== null && Math.abs(d) > 5e-5) ed.classList.add((d > 0) === better ? 'up' : 'down');
    } else {
      ed.textContent = '';
    }
  }
  const withColour = ['a', 'b'].some((n) => state.slots[n] && state.slots[n].scores && state.slots[n].scores.colour);
  document.body.classList.toggle('coloured', withColour);
  showSwatch();
  const kinds = ['a', 'b'].map((n) => state.slots[n]).filter((s) => s && s.scores).map((s) => s.quick);
  $('#score-kind').textContent = kinds.length === 0 ? '' : kinds.some((q) => q) ? 'quick' : 'full';
  if (!b) delete $('#scores').dataset.b;
  $('#score-kind').title = 'quick (≈): estimates with fewer poses, bands, fire placements and pixels while you move a slider (brilliance within about 0.001, fire and scintillation within tens of percent); full: the scores of `facetlab score`';
}

function fmtProp(key, unit, v) {
  if (typeof v !== 'number') return '—';
  if (unit === '%') return (100 * v).toFixed(1) + ' %';
  if (unit === '°') return v.toFixed(2) + ' °';
  if (unit === 'ct') return v.toFixed(3) + ' ct';
  return String(v);
}

function fillProps() {
  for (const name of ['a', 'b']) {
    const s = state.slots[name];
    const info = s && s.info;
    for (const [key, , unit] of PROP_ROWS) {
      $(`#prop-${name}-${key}`).textContent = fmtProp(key, unit, info ? info.proportions[key] : undefined);
    }
    $(`#prop-${name}-facet_count`).textContent = info ? String(info.facet_count) : '—';
    // The material this stone is traced in: the one chosen, else its own.
    $(`#prop-${name}-material`).textContent = info ? info.material : '—';
    $(`#prop-${name}-carats`).textContent = fmtProp('carats', 'ct', info ? info.carats : undefined);
  }
  const w = $('#prop-a-carats');
  if (w) w.parentElement.firstChild.textContent = `Weight at ${Number(state.stone.width.toFixed(2))} mm`;
  const a = state.slots.a;
  if (a && a.info) {
    $('#cut-name').textContent = a.info.name;
    $('#cut-family').textContent = a.info.family ? '· ' + a.info.family : a.recipe ? '· recipe, tier by tier' : a.design ? '· design, tier angles' : '· explicit facets';
  }
}

// The caption says what the picture shows (not what is being asked for).
function caption(name) {
  const s = state.slots[name];
  if (!s) return;
  const v = s.shown;
  const el = $('#cap-' + name);
  if (!v) {
    el.textContent = (s.info ? s.info.name : '') + ' · rendering…';
    return;
  }
  const parts = [v.name];
  if (v.changed) parts.push(`(${v.changed} changed)`);
  parts.push('· ' + lightLabel(v.light));
  if (v.head_shadow) parts.push(`· head shadow ${v.head_shadow}°`);
  if (s.info) parts.push('· ' + s.info.material);
  if (v.tilt) parts.push(`· tilt ${v.tilt}°`);
  if (isPhoto(v.light)) {
    parts.push(`· view ${v.view}°`);
    if (v.light_rotation) parts.push(`· light turned ${v.light_rotation}°`);
    if (v.ground !== 'none') parts.push(`· ${v.ground} ground`);
    if (v.aperture === 0) parts.push('· pinhole');
    else if (v.aperture) parts.push(`· ${v.aperture} mm aperture`);
    if (v.quick) parts.push('· quick');
    const st = v.stats || {};
    if (typeof st.mean === 'number') parts.push(`· mean ${st.mean.toFixed(3)}`);
    el.textContent = parts.join(' ');
    el.title = el.textContent;
    return;
  }
  const st = v.stats || {};
  if (st.colour) parts.push(`· L* ${st.colour.l.toFixed(1)} C* ${st.colour.c.toFixed(1)} h ${st.colour.h_deg.toFixed(0)}°`);
  if (typeof st.placement_fire === 'number') parts.push(`· placement fire ${st.placement_fire.toFixed(3)}`);
  else if (!st.aset && typeof st.mean === 'number') parts.push(`· face-up mean ${st.mean.toFixed(3)}`);
  el.textContent = parts.join(' ');
  el.title = el.textContent;
}

function showStatus() {
  const el = $('#status');
  el.classList.remove('bad');
  const bits = [];
  for (const name of ['a', 'b']) {
    const s = state.slots[name];
    if (!s) continue;
    const m = s.ms;
    const t = [];
    if (m.render !== undefined) t.push(`render ${m.render} ms`);
    if (m.quick !== undefined) t.push(`quick scores ${m.quick} ms`);
    if (m.full !== undefined) t.push(`full scores ${m.full} ms`);
    if (m.slider !== undefined && s.t0) t.push(`last change → picture ${m.slider} ms`);
    if (m.scoreSlider !== undefined && s.t0) t.push(`→ scores ${m.scoreSlider} ms`);
    if (t.length) bits.push(name.toUpperCase() + ': ' + t.join(', '));
  }
  el.textContent = bits.join('   ·   ');
}

// ---- errors ---------------------------------------------------------------------------------

function showError(name, e) {
  let field = e.field || '';
  const msg = e.message || String(e);
  const design = state.slots[name] && state.slots[name].design;
  // A design's refusal that names no tier belongs to the slider moved last.
  if (name === 'a' && design && field === 'set' && state.slots.a.lastKey) field = 'set.' + state.slots.a.lastKey;
  if (name === 'a' && field.startsWith('set.')) {
    const row = document.querySelector(`.param[data-key="${CSS.escape(field.slice(4))}"]`);
    if (row) {
      row.classList.add('invalid');
      row.querySelector('.err').textContent = msg.replace(/^set\.[^:]*:\s*/, '');
    } else {
      $('#params-note').textContent = msg;
    }
  } else if (name === 'a' && field === 'cut') {
    $('#source-err').textContent = msg;
  } else if (name === 'a' && field === 'set') {
    $('#params-note').textContent = msg;
  } else if (STONE_FIELDS.includes(field)) {
    $('#stone-err').textContent = msg;
    $('#render-' + name).parentElement.classList.remove('busy');
    return;
  } else {
    const el = $('#status');
    el.textContent = name.toUpperCase() + ': ' + msg;
    el.classList.add('bad');
  }
  if (design && field.startsWith('set')) {
    // The design at these angles is refused: the picture and scores stay those of the last
    // angles that kept it (no veil), and the status line says so.
    const el = $('#status');
    el.textContent = `${name.toUpperCase()}: refused (${msg.replace(/^set[^:]*:\s*/, '')}); the picture and scores are of the last angles that kept the design`;
    el.classList.add('bad');
    $('#render-' + name).parentElement.classList.remove('busy');
    return;
  }
  const veil = $('#veil-' + name);
  veil.textContent = 'Not a valid cut: ' + msg;
  veil.classList.add('on');
}

function clearError(name) {
  $('#veil-' + name).classList.remove('on');
  $('#stone-err').textContent = '';
  if (name !== 'a') return;
  for (const row of document.querySelectorAll('.param.invalid')) {
    row.classList.remove('invalid');
    row.querySelector('.err').textContent = '';
  }
  if (state.slots.a.design) {
    designNote();
    $('#source-err').textContent = '';
    return;
  }
  if (!state.slots.a.family) return;
  $('#params-note').textContent = '';
  $('#source-err').textContent = '';
}

// ---- compare, downloads ---------------------------------------------------------------------

function pinB() {
  const a = state.slots.a;
  if (!a) return;
  const b = newSlot(a.source);
  b.base = Object.assign({}, a.base);
  b.set = Object.assign({}, a.set);
  b.family = a.family;
  b.design = a.design;
  b.designError = a.designError;
  b.recipe = a.recipe;
  b.info = a.info;
  b.scores = a.scores;
  b.quick = a.quick;
  b.shown = a.shown;
  state.slots.b = b;
  document.body.classList.add('comparing');
  $('#view-b').hidden = false;
  $('#render-b').src = $('#render-a').src;
  fillScores();
  fillProps();
  caption('b');
  refresh('b', 'all');
}

function clearB() {
  state.slots.b = null;
  document.body.classList.remove('comparing');
  $('#view-b').hidden = true;
  fillScores();
  fillProps();
  showStatus();
}

function swap() {
  const { a, b } = state.slots;
  if (!a || !b) return;
  state.slots.a = b;
  state.slots.b = a;
  const ia = $('#render-a').src;
  $('#render-a').src = $('#render-b').src;
  $('#render-b').src = ia;
  [a.img, b.img] = [b.img, a.img];
  buildParams();
  fillScores();
  fillProps();
  caption('a');
  caption('b');
  if (b.info) showDiagram(b.info.svg);
  refresh('a', 'render');
  refresh('b', 'render');
}

async function download(to) {
  const s = state.slots.a;
  if (!s) return;
  try {
    const { blob, headers } = await api('export', '/api/export', requestBody(s, { to }), 'blob');
    const m = /filename="([^"]+)"/.exec(headers.get('content-disposition') || '');
    const a = document.createElement('a');
    a.href = URL.createObjectURL(blob);
    a.download = m ? m[1] : 'cut.' + to;
    document.body.appendChild(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 2000);
  } catch (e) {
    if (!aborted(e)) showError('a', e);
  }
}

// ---- start ----------------------------------------------------------------------------------

function setTilt(v) {
  if (!Number.isFinite(v)) return;
  const lim = state.meta.limits.tilt[1];
  v = Math.max(-lim, Math.min(lim, v));
  state.tilt = v;
  $('#tilt').value = String(v);
  $('#tilt-num').value = String(v);
  for (const n of ['a', 'b']) {
    if (state.slots[n]) {
      state.slots[n].t0 = performance.now();
      schedule(n, 'render');
    }
  }
}

async function start() {
  const r = await fetch('/api/presets');
  state.meta = await r.json();
  const sel = $('#preset');
  for (const p of state.meta.presets) {
    const o = document.createElement('option');
    o.value = p.name;
    o.textContent = `${p.name} — ${p.family || 'facets'}`;
    sel.appendChild(o);
  }
  const light = $('#light');
  for (const l of state.meta.light_table) {
    LIGHTS[l.name] = l;
    const o = document.createElement('option');
    o.value = l.name;
    o.textContent = l.label;
    light.appendChild(o);
  }
  light.value = state.light;
  state.exposure = firstExposure(state.light) || 1;
  const exposure = $('#exposure');
  buildTables();
  setupStone();

  sel.addEventListener('change', () => {
    if (sel.value === '__file') return;
    const opt = sel.querySelector('option[value="__file"]');
    if (opt) opt.remove();
    loadSource({ cut: sel.value });
  });
  $('#file').addEventListener('change', (ev) => {
    const f = ev.target.files && ev.target.files[0];
    if (f) readFile(f);
    ev.target.value = '';
  });
  const head = $('#head-shadow');
  const setHeadShadow = () => {
    const on = takesHeadShadow(state.light);
    head.disabled = !on;
    $('#head-shadow-val').textContent = on ? `${state.headShadow}°` : 'n/a';
  };
  head.value = String(state.headShadow);
  setHeadShadow();
  head.addEventListener('input', () => {
    state.headShadow = Number(head.value);
    setHeadShadow();
    for (const n of ['a', 'b']) if (state.slots[n]) { state.slots[n].t0 = performance.now(); schedule(n, 'render'); }
  });
  const setExposure = (v) => {
    state.exposure = v;
    exposure.value = String(v);
    const falseColour = firstExposure(state.light) === null;
    exposure.disabled = falseColour;
    $('#exposure-val').textContent = falseColour ? 'n/a' : v.toFixed(2);
  };
  setExposure(state.exposure);
  const photoBar = $('#photo-bar');
  light.addEventListener('change', () => {
    state.light = light.value;
    photoBar.hidden = !isPhoto(state.light);
    setExposure(firstExposure(state.light) || 1);
    setHeadShadow();
    for (const n of ['a', 'b']) if (state.slots[n]) { state.slots[n].t0 = performance.now(); schedule(n, 'render', 0); }
  });
  // The photograph's controls: every move re-draws quick pictures (debounced), the full one
  // follows when they rest.
  const photoControl = (id, key, unit) => {
    const el = $('#' + id);
    el.addEventListener('input', () => {
      state[key] = el.type === 'range' ? Number(el.value) : el.value;
      const val = $('#' + id + '-val');
      if (val) val.textContent = el.value + unit;
      for (const n of ['a', 'b']) if (state.slots[n]) { state.slots[n].t0 = performance.now(); schedule(n, 'render'); }
    });
  };
  photoControl('view', 'view', '°');
  photoControl('rotation', 'rotation', '°');
  photoControl('ground', 'ground', '');
  photoControl('aperture', 'aperture', '');
  exposure.addEventListener('input', () => {
    state.exposure = Number(exposure.value);
    $('#exposure-val').textContent = state.exposure.toFixed(2);
    for (const n of ['a', 'b']) if (state.slots[n]) { state.slots[n].t0 = performance.now(); schedule(n, 'render'); }
  });
  $('#tilt').addEventListener('input', () => setTilt(Number($('#tilt').value)));
  $('#tilt-num').addEventListener('change', () => setTilt(Number($('#tilt-num').value)));
  $('#reset').addEventListener('click', () => {
    const s = state.slots.a;
    if (!s) return;
    s.set = {};
    s.t0 = performance.now();
    buildParams();
    schedule('a', 'all', 0);
  });
  $('#compare').addEventListener('click', pinB);
  $('#clear-b').addEventListener('click', clearB);
  $('#swap').addEventListener('click', swap);
  for (const b of document.querySelectorAll('.downloads button')) {
    b.addEventListener('click', () => download(b.dataset.to));
  }
  // Drop a file anywhere.
  const drop = $('#drop');
  let depth = 0;
  window.addEventListener('dragenter', (e) => { e.preventDefault(); depth++; drop.hidden = false; });
  window.addEventListener('dragleave', () => { depth = Math.max(0, depth - 1); if (!depth) drop.hidden = true; });
  window.addEventListener('dragover', (e) => e.preventDefault());
  window.addEventListener('drop', (e) => {
    e.preventDefault();
    depth = 0;
    drop.hidden = true;
    const f = e.dataTransfer && e.dataTransfer.files && e.dataTransfer.files[0];
    if (f) readFile(f);
  });

  const first = state.meta.presets.find((p) => p.name === 'tolkowsky') || state.meta.presets[0];
  sel.value = first.name;
  await loadSource({ cut: first.name });
}


// ---- optimization runs --------------------------------------------------------------------------

const opt = { configs: [], timer: null };

function drawCurve(curve) {
  const c = $('#opt-chart');
  const g = c.getContext('2d');
  g.clearRect(0, 0, c.width, c.height);
  if (!curve || curve.length < 1) return;
  const xs = curve.map((p) => p[0]);
  const ys = curve.map((p) => p[1]);
  const x0 = Math.min(...xs), x1 = Math.max(...xs, x0 + 1);
  let y0 = Math.min(...ys), y1 = Math.max(...ys);
  if (y1 - y0 < 1e-9) { y0 -= 0.01; y1 += 0.01; }
  const px = (x) => 6 + (c.width - 12) * (x - x0) / (x1 - x0);
  const py = (y) => 6 + (c.height - 12) * (y1 - y) / (y1 - y0);
  g.strokeStyle = '#6aa9ff';
  g.lineWidth = 2;
  g.beginPath();
  curve.forEach((p, i) => (i ? g.lineTo(px(p[0]), py(p[1])) : g.moveTo(px(p[0]), py(p[1]))));
  g.stroke();
}

async function pollRun() {
  let s;
  try {
    const r = await fetch('/api/optimize');
    if (!r.ok) return;
    s = await r.json();
  } catch (e) {
    return;
  }
  drawCurve(s.curve);
  const best = s.best_cost == null ? '—' : (-s.best_cost).toFixed(4);
  let text = `${s.name}: ${s.state}, ${s.evaluations}/${s.budget} evaluations, best score ${best}, ${s.elapsed_s.toFixed(1)} s`;
  if (s.error) text += ' — ' + s.error;
  $('#opt-status').textContent = text;
  const running = s.state === 'running';
  $('#opt-run').disabled = running;
  $('#opt-stop').disabled = !running;
  $('#opt-report').hidden = !s.report;
  if (!running && opt.timer) {
    clearInterval(opt.timer);
    opt.timer = null;
  }
}

async function startRun() {
  const name = $('#opt-config').value;
  try {
    const r = await fetch('/api/optimize', {
      method: 'POST',
      headers: { 'content-type': 'application/json' },
      body: JSON.stringify({ config: name }),
    });
    const j = await r.json();
    if (!r.ok) throw new Error(j.error || r.statusText);
  } catch (e) {
    $('#opt-status').textContent = 'Could not start: ' + e.message;
    return;
  }
  $('#opt-report').hidden = true;
  if (!opt.timer) opt.timer = setInterval(pollRun, 500);
  pollRun();
}

async function setupRuns() {
  try {
    const r = await fetch('/api/configs');
    opt.configs = (await r.json()).configs;
  } catch (e) {
    return;
  }
  const sel = $('#opt-config');
  for (const c of opt.configs) {
    const o = document.createElement('option');
    o.value = c.name;
    o.textContent = c.name;
    sel.appendChild(o);
  }
  const describe = () => {
    const c = opt.configs.find((x) => x.name === sel.value);
    $('#opt-desc').textContent = c ? (c.description || '') + (c.budget ? ` (${c.budget} evaluations)` : '') : '';
  };
  sel.addEventListener('change', describe);
  describe();
  $('#opt-run').addEventListener('click', startRun);
  $('#opt-stop').addEventListener('click', () => fetch('/api/optimize/stop', { method: 'POST' }).then(pollRun));
  pollRun();
}

// ---- the stone: material, body colour, width ---------------------------------------------------

const STONE_FIELDS = ['material', 'colour', 'colour_density', 'diameter_mm', 'size_mm', 'optic_axis', 'birefringence'];

function setupStone() {
  const sel = $('#material');
  for (const m of state.meta.materials) {
    const o = document.createElement('option');
    o.value = m.name;
    o.textContent = m.colour ? `${m.name} (coloured)` : m.name;
    if (m.colour) o.style.color = m.colour;
    sel.appendChild(o);
  }
  const ownOption = document.createElement('option');
  ownOption.value = '';
  ownOption.textContent = "the cut's own (a design's index, else diamond)";
  sel.prepend(ownOption);
  sel.value = state.stone.material;
  const own = $('#own-colour'), colour = $('#colour'), mm = $('#colour-mm'), density = $('#density');
  const axis = $('#optic-axis');
  // A uniaxial material brings its default optic axis; the slider shows for those only.
  const materialAxis = (name) => {
    const m = state.meta.materials.find((x) => x.name === name);
    return m && m.optic_axis !== null && m.optic_axis !== undefined ? m.optic_axis : null;
  };
  const changed = (ev) => {
    const st = state.stone;
    if (ev && ev.target === sel) {
      const d = materialAxis(sel.value);
      if (d !== null) axis.value = d;
    }
    st.material = sel.value;
    st.axis = materialAxis(sel.value) === null ? null : Number(axis.value);
    $('#axis-ctl').hidden = st.axis === null;
    if (st.axis !== null) $('#optic-axis-val').textContent = `${st.axis}°`;
    st.own = own.checked;
    st.colour = colour.value;
    const t = Number(mm.value);
    if (Number.isFinite(t) && t > 0) st.colourMm = t;
    st.density = Number(density.value);
    const w = Number($('#stone-mm').value);
    if (Number.isFinite(w) && w > 0) st.width = w;
    colour.disabled = mm.disabled = !own.checked;
    density.disabled = !coloured();
    $('#density-val').textContent = st.density.toFixed(2);
    for (const n of ['a', 'b']) if (state.slots[n]) { state.slots[n].t0 = performance.now(); schedule(n, 'all'); }
  };
  for (const el of [sel, own, colour, mm, $('#stone-mm')]) el.addEventListener('change', changed);
  colour.addEventListener('input', changed);
  density.addEventListener('input', changed);
  axis.addEventListener('input', changed);
}

// The swatch beside the width: A's face-up mean colour (CIELAB of its scores) in sRGB.
function showSwatch() {
  const el = $('#stone-swatch');
  const a = state.slots.a;
  const c = a && a.scores && a.scores.colour;
  if (!c) { el.removeAttribute('style'); return; }
  const h = c.h_deg * Math.PI / 180;
  const [L, A, B] = [c.l, c.c * Math.cos(h), c.c * Math.sin(h)];
  const fy = (L + 16) / 116, fx = fy + A / 500, fz = fy - B / 200;
  const inv = (t) => (t > 6 / 29 ? t * t * t : 3 * (6 / 29) ** 2 * (t - 4 / 29));
  const [X, Y, Z] = [0.95047 * inv(fx), inv(fy), 1.08883 * inv(fz)];
  const lin = [3.2406 * X - 1.5372 * Y - 0.4986 * Z, -0.9689 * X + 1.8758 * Y + 0.0415 * Z, 0.0557 * X - 0.2040 * Y + 1.0570 * Z];
  const g = lin.map((v) => {
    v = Math.max(0, Math.min(1, v));
    return Math.round(255 * (v <= 0.0031308 ? 12.92 * v : 1.055 * v ** (1 / 2.4) - 0.055));
  });
  el.style.background = `rgb(${g.join(',')})`;
  el.title = `A's face-up mean colour: L* ${c.l.toFixed(1)}, C* ${c.c.toFixed(1)}, h ${c.h_deg.toFixed(0)}°`;
}


start().then(setupRuns).catch((e) => {
  const el = $('#status');
  el.textContent = 'Could not start: ' + e.message;
  el.classList.add('bad');
});

