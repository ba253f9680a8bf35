// facetlab workbench: the "Design tier by tier" panel (the tier editor), over
// POST /api/recipe/build and /api/recipe/infer. The recipe is held here as the editor shows it
// (each tier's angle, indices and placement value as text) and sent to the server as a recipe
// file's TOML text, read by the library's one parser of recipes; the built stone becomes cut A.
'use strict';

const $r = (sel) => document.querySelector(sel);

const PLACES = ['meet', 'centre', 'depth', 'scale', 'girdle', 'table'];
const PLACE_HINT = {
  meet: 'tiers whose vertex it is cut to, e.g. G1-P1',
  centre: 'to the centre point',
  depth: 'distance from the axis point',
  scale: 'a depth that sets the size',
  girdle: 'girdle thickness, fraction of W',
  table: 'table width, fraction of W',
};
const RECIPE_DELAY = 150;   // ms of quiet typing before the recipe is built
const UNDO_LIMIT = 200;

const recipe = {
  model: null,      // { design: {...}, tiers: [{ name, angle, indices, place, value, side, note }] }
  undo: [],         // earlier models (JSON text), newest last
  editing: null,    // the input being typed into (one undo step per field edited)
  timer: null,
  built: null,      // the last answer of /api/recipe/build
  toml: '',
};

// A TOML basic string (JSON's escapes are TOML's).
const tq = (s) => JSON.stringify(String(s));
// A number as TOML when the text is one, else the text quoted (the server names the field).
function tnum(text) {
  const t = String(text).trim();
  return /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/.test(t) ? String(Number(t)) + (/[.eE]/.test(String(Number(t))) ? '' : '.0') : tq(t);
}
const tint = (text) => (/^\d+$/.test(String(text).trim()) ? String(Number(text)) : tq(text));

// The recipe file (docs/design.md's form) of the editor's model.
function recipeToml(m) {
  const d = m.design;
  const out = ['[design]', `name = ${tq(d.name || 'recipe')}`, `gear = ${tint(d.gear)}`];
  if (Number(d.offset)) out.push(`offset = ${tnum(d.offset)}`);
  out.push(`symmetry = ${tint(d.symmetry)}`, `mirror = ${d.mirror ? 'true' : 'false'}`, `index = ${tnum(d.index)}`);
  if (d.fractional) out.push('fractional = true');
  if (d.title && d.title.length) out.push(`title = [${d.title.map(tq).join(', ')}]`);
  if (d.notes && d.notes.length) out.push(`notes = [${d.notes.map(tq).join(', ')}]`);
  for (const t of m.tiers) {
    out.push('', '[[tier]]', `name = ${tq(t.name)}`);
    const a = String(t.angle).trim();
    out.push(`angle = ${a.startsWith('=') ? tq(a) : tnum(a)}`);
    if (t.side) out.push(`side = ${tq(t.side)}`);
    if (String(t.indices).trim()) out.push(`indices = ${tq(String(t.indices).trim())}`);
    if (t.place === 'centre') out.push('centre = true');
    else if (t.place === 'meet') out.push(`meet = ${tq(t.value)}`);
    else out.push(`${t.place} = ${tnum(t.value)}`);
    if (t.note) out.push(`note = ${tq(t.note)}`);
  }
  return out.join('\n') + '\n';
}

function snapshot() {
  recipe.undo.push(JSON.stringify(recipe.model));
  if (recipe.undo.length > UNDO_LIMIT) recipe.undo.shift();
  $r('#recipe-undo').disabled = false;
}

function undo() {
  const prev = recipe.undo.pop();
  if (prev === undefined) return;
  recipe.model = JSON.parse(prev);
  recipe.editing = null;
  $r('#recipe-undo').disabled = recipe.undo.length === 0;
  drawRecipe();
  scheduleRecipe(0);
}

// A structural change (add, remove, move, load): one undo step, redraw, build now.
function change(f) {
  snapshot();
  recipe.editing = null;
  f();
  drawRecipe();
  scheduleRecipe(0);
}

function scheduleRecipe(delay) {
  clearTimeout(recipe.timer);
  recipe.timer = setTimeout(buildRecipe, delay === undefined ? RECIPE_DELAY : delay);
}

function input(cls, value, title, onInput) {
  const el = document.createElement('input');
  el.className = cls;
  el.value = value;
  el.title = title;
  el.setAttribute('aria-label', title);
  el.addEventListener('input', () => {
    // One undo step per field typed into.
    if (recipe.editing !== el) { snapshot(); recipe.editing = el; }
    onInput(el.value);
    scheduleRecipe();
  });
  return el;
}

function button(text, title, f) {
  const b = document.createElement('button');
  b.type = 'button';
  b.className = 'small';
  b.textContent = text;
  b.title = title;
  b.addEventListener('click', f);
  return b;
}

function drawRecipe() {
  const m = recipe.model;
  const box = $r('#recipe-tiers');
  box.textContent = '';
  $r('#recipe-editor').hidden = !m;
  if (!m) return;
  const d = m.design;
  for (const [id, key] of [['#recipe-name', 'name'], ['#recipe-gear', 'gear'], ['#recipe-symmetry', 'symmetry'], ['#recipe-index', 'index']]) {
    const el = $r(id);
    if (document.activeElement !== el) el.value = d[key];
  }
  $r('#recipe-mirror').checked = !!d.mirror;
  m.tiers.forEach((t, i) => {
    const row = document.createElement('div');
    row.className = 'tier-row';
    row.dataset.i = String(i);
    row.dataset.tier = t.name;
    const line1 = document.createElement('div');
    line1.className = 'tier-line';
    line1.append(
      input('t-name', t.name, 'tier name', (v) => { t.name = v; row.dataset.tier = v; }),
      input('t-angle', t.angle, 'angle, degrees (negative: pavilion; 90: girdle; 0: table) or an expression such as =P1-2', (v) => { t.angle = v; }),
      input('t-indices', t.indices, 'indices on the gear: 3 93, 3-93, 0:12:96 or 12 x8 (the symmetry cuts the rest)', (v) => { t.indices = v; }),
    );
    const line2 = document.createElement('div');
    line2.className = 'tier-line';
    const sel = document.createElement('select');
    sel.className = 't-place';
    sel.setAttribute('aria-label', 'placement');
    for (const p of PLACES) {
      const o = document.createElement('option');
      o.value = p;
      o.textContent = p;
      sel.appendChild(o);
    }
    sel.value = t.place;
    const value = input('t-value', t.value, PLACE_HINT[t.place], (v) => { t.value = v; });
    value.disabled = t.place === 'centre';
    value.placeholder = t.place === 'meet' ? 'G1-P1' : '';
    sel.addEventListener('change', () => {
      snapshot();
      recipe.editing = null;
      t.place = sel.value;
      if (t.place === 'centre') t.value = '';
      value.disabled = t.place === 'centre';
      value.value = t.value;
      value.title = PLACE_HINT[t.place];
      value.placeholder = t.place === 'meet' ? 'G1-P1' : '';
      scheduleRecipe(0);
    });
    line2.append(sel, value,
      button('↑', 'cut this tier one earlier', () => change(() => { if (i > 0) m.tiers.splice(i - 1, 0, m.tiers.splice(i, 1)[0]); })),
      button('↓', 'cut this tier one later', () => change(() => { if (i + 1 < m.tiers.length) m.tiers.splice(i + 1, 0, m.tiers.splice(i, 1)[0]); })),
      button('×', 'remove this tier', () => change(() => { m.tiers.splice(i, 1); })));
    const msg = document.createElement('div');
    msg.className = 't-msg small';
    row.append(line1, line2, msg);
    box.appendChild(row);
  });
  showSteps();
}

// Each tier's instruction (or its error) under it; findings in the status line.
function showSteps() {
  const b = recipe.built;
  for (const row of document.querySelectorAll('#recipe-tiers .tier-row')) {
    row.classList.remove('invalid');
    const msg = row.querySelector('.t-msg');
    msg.classList.remove('err');
    const step = b && b.steps ? b.steps.find((s) => s.tier === row.dataset.tier) : null;
    const found = b && b.findings ? b.findings.filter((f) => f.tier === row.dataset.tier) : [];
    msg.textContent = step ? step.instruction + (found.length ? ' — ' + found.map((f) => f.message).join('; ') : '') : '';
    msg.classList.toggle('warn', found.length > 0);
  }
}

function showRecipeError(e) {
  const status = $r('#recipe-status');
  status.textContent = e.message;
  status.classList.add('bad');
  const field = e.field || '';
  if (!field.startsWith('tier ')) return;
  const who = field.slice(5);
  const rows = Array.from(document.querySelectorAll('#recipe-tiers .tier-row'));
  const row = rows.find((r) => r.dataset.tier === who) || rows[Number(who) - 1];
  if (!row) return;
  row.classList.add('invalid');
  const msg = row.querySelector('.t-msg');
  msg.textContent = e.message.replace(/^tier [^:]*:\s*/, '');
  msg.classList.add('err');
}

// Build the recipe (POST /api/recipe/build); the stone becomes cut A, pictured and scored.
async function buildRecipe() {
  const m = recipe.model;
  if (!m) return;
  const toml = recipeToml(m);
  const name = (m.design.name || 'recipe').replace(/[^A-Za-z0-9_-]+/g, '-') + '.toml';
  const source = { cut: toml, format: 'toml', name };
  const t = performance.now();
  let j;
  try {
    j = await api('recipe', '/api/recipe/build', Object.assign({}, source, stoneBody()));
  } catch (e) {
    if (aborted(e)) return;
    recipe.built = null;
    showSteps();
    showRecipeError(e);
    return;
  }
  recipe.toml = toml;
  recipe.built = j;
  const ms = Math.round(performance.now() - t);
  const status = $r('#recipe-status');
  status.classList.remove('bad');
  status.textContent = `${m.tiers.length} tiers built in ${j.build_ms.toFixed(1)} ms (answer ${ms} ms)` +
    (j.findings.length ? ` · ${j.findings.length} finding${j.findings.length > 1 ? 's' : ''}` : '');
  status.dataset.ms = String(ms);
  showSteps();
  // The stone as cut A: the other endpoints build the same text (a recipe is a .toml cut).
  const prev = state.slots.a;
  const s = newSlot(source);
  s.recipe = true;
  s.info = j;
  s.t0 = t;
  if (prev && prev.img) s.img = prev.img;
  state.slots.a = s;
  setFileOption('recipe ' + name);
  buildParams();
  $r('#params-note').textContent = 'A recipe: change its tiers under "Design tier by tier".';
  fillProps();
  showDiagram(j.svg);
  caption('a');
  s.needScore = true;
  markStale('a');
  doRender('a');
}

// The recipe of cut A (POST /api/recipe/infer): each tier placed as a faceter would place it.
async function inferRecipe() {
  const s = state.slots.a;
  if (!s) return;
  const status = $r('#recipe-status');
  try {
    const j = await api('recipe-infer', '/api/recipe/infer', Object.assign({}, s.source, { set: s.set }));
    change(() => { recipe.model = j.recipe; });
    if (j.notes && j.notes.length) status.title = j.notes.join('\n');
  } catch (e) {
    if (!aborted(e)) { status.textContent = e.message; status.classList.add('bad'); }
  }
}

function newRecipe() {
  change(() => {
    recipe.model = {
      design: { name: 'new design', gear: 96, offset: 0, symmetry: 8, mirror: true, index: 1.54, fractional: false, title: [], notes: [] },
      tiers: [
        { name: 'P1', angle: '-42', indices: '96', place: 'centre', value: '' },
        { name: 'G1', angle: '90', indices: '96', place: 'depth', value: '0.9' },
        { name: 'C1', angle: '38', indices: '96', place: 'girdle', value: '0.03' },
        { name: 'T', angle: '0', indices: '', place: 'table', value: '0.55' },
      ],
    };
  });
}

function addTier() {
  const m = recipe.model;
  if (!m) return;
  change(() => {
    const names = new Set(m.tiers.map((t) => t.name));
    let k = m.tiers.length + 1;
    while (names.has('X' + k)) k++;
    m.tiers.push({ name: 'X' + k, angle: '30', indices: '3', place: 'meet', value: '' });
  });
}

function saveBlob(bytes, name, type) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([bytes], { type }));
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 2000);
}

// Save the recipe (its TOML text, as built) or the stone (.asc, .gem through /api/export).
async function saveRecipe(to) {
  const m = recipe.model;
  if (!m) return;
  const toml = recipeToml(m);
  const stem = (m.design.name || 'recipe').replace(/[^A-Za-z0-9_-]+/g, '-');
  if (to === 'recipe') {
    saveBlob(toml, stem + '.toml', 'text/plain');
    return;
  }
  try {
    const { blob } = await api('recipe-save', '/api/export', { cut: toml, format: 'toml', name: stem + '.toml', to });
    saveBlob(blob, stem + '.' + to, 'application/octet-stream');
  } catch (e) {
    if (!aborted(e)) showRecipeError(e);
  }
}

function setupRecipe() {
  $r('#recipe-from').addEventListener('click', inferRecipe);
  $r('#recipe-new').addEventListener('click', newRecipe);
  $r('#recipe-undo').addEventListener('click', undo);
  $r('#recipe-add').addEventListener('click', addTier);
  for (const b of document.querySelectorAll('#recipe-save button')) b.addEventListener('click', () => saveRecipe(b.dataset.save));
  const design = (id, key, read) => {
    const el = $r(id);
    el.addEventListener('input', () => {
      if (!recipe.model) return;
      if (recipe.editing !== el) { snapshot(); recipe.editing = el; }
      recipe.model.design[key] = read(el);
      scheduleRecipe();
    });
  };
  design('#recipe-name', 'name', (el) => el.value);
  design('#recipe-gear', 'gear', (el) => el.value);
  design('#recipe-symmetry', 'symmetry', (el) => el.value);
  design('#recipe-index', 'index', (el) => el.value);
  design('#recipe-mirror', 'mirror', (el) => el.checked);
  drawRecipe();
}

setupRecipe();
