// facetlab workbench: the "Plan from a rough" panel, over POST/GET /api/plan.
'use strict';

const plan = { meta: null, upload: null, timer: null, shown: null, chosen: null, material: null, inclusions: [] };

const $p = (sel) => document.querySelector(sel);

// The body of POST /api/plan from the panel's controls.
function planBody() {
  const body = {
    families: Array.from($p('#plan-families').selectedOptions).map((o) => o.value),
    top: Number($p('#plan-top').value),
    starts: Number($p('#plan-starts').value),
  };
  // A layout of several stones (or one kept off inclusions): the saw's settings too.
  const stones = Number($p('#plan-stones').value);
  if (stones > 1 || plan.inclusions.length > 0) {
    body.stones = stones;
    body.kerf_mm = Number($p('#plan-kerf').value);
    body.allowance_mm = Number($p('#plan-allowance').value);
    body.margin_mm = Number($p('#plan-margin').value);
    body.cutter = $p('#plan-cutter').value;
    if (plan.inclusions.length > 0) body.inclusions = plan.inclusions;
  }
  const size = $p('#plan-size').value.trim();
  const which = $p('#plan-rough').value;
  if (which === '__upload') {
    if (!plan.upload) return null;
    Object.assign(body, plan.upload);
    if (size !== '' && plan.scale) body.size_mm = Number(size);
  } else {
    body.crystal = which;
    body.size_mm = size === '' ? NaN : Number(size);
  }
  return body;
}

async function startPlan() {
  const body = planBody();
  const status = $p('#plan-status');
  if (!body) {
    status.textContent = 'Open a rough first (a closed .obj or .stl mesh in mm), or choose a crystal form.';
    return;
  }
  status.classList.remove('bad');
  try {
    const r = await fetch('/api/plan', {
      method: 'POST',
      headers: { 'content-type': 'application/json' },
      body: JSON.stringify(body),
    });
    const j = await r.json();
    if (!r.ok) throw new Error(j.error || r.statusText);
  } catch (e) {
    status.textContent = 'Not planned: ' + e.message;
    status.classList.add('bad');
    return;
  }
  plan.shown = null;
  plan.chosen = null;
  $p('#plan-open').hidden = true;
  $p('#plan-table').hidden = true;
  $p('#plan-stone-table').hidden = true;
  $p('#plan-saw').hidden = true;
  $p('#plan-overview-link').hidden = true;
  $p('#plan-views-link').hidden = true;
  $p('#plan-report').hidden = true;
  if (!plan.timer) plan.timer = setInterval(pollPlan, 400);
  pollPlan();
}

async function pollPlan() {
  let s;
  try {
    const r = await fetch('/api/plan');
    if (!r.ok) return;
    s = await r.json();
  } catch (e) {
    return;
  }
  const running = s.state === 'running';
  $p('#plan-run').disabled = running;
  $p('#plan-stop').disabled = !running;
  const status = $p('#plan-status');
  status.classList.toggle('bad', s.state === 'failed');
  let text = `${s.name}: ${s.state}`;
  if (running) {
    text += s.family ? ', ' + s.family : '';
    text += `, ${s.starts_done}/${s.starts} ${Number($p('#plan-stones').value) > 1 || plan.inclusions.length ? 'saw cuts' : 'starts'}`;
  }
  text += `, ${s.elapsed_s.toFixed(1)} s`;
  if (s.rough) {
    text += ` · rough ${s.rough.volume_mm3.toFixed(2)} mm³`;
    if (s.rough.hull_excess > 0) text += ` (hull +${(100 * s.rough.hull_excess).toFixed(1)} %)`;
  }
  if (s.error) text += ' — ' + s.error;
  status.textContent = text;
  $p('#plan-report').hidden = !s.report;
  plan.material = s.material || null;
  if (!running) {
    if (plan.timer) { clearInterval(plan.timer); plan.timer = null; }
    if (plan.shown !== s.id) {
      plan.shown = s.id;
      showPlans(s.plans || []);
      showStones(s);
    }
  }
}

function showPlans(plans) {
  const table = $p('#plan-table');
  const tb = table.querySelector('tbody');
  tb.textContent = '';
  table.hidden = plans.length === 0;
  plans.forEach((p, i) => {
    const tr = document.createElement('tr');
    const cells = [`${p.family} #${p.rank}`, p.carats.toFixed(3), (100 * p.yield).toFixed(1) + ' %', p.width_mm.toFixed(2), p.grade || '—', p.scores.brilliance.toFixed(3)];
    for (const c of cells) {
      const td = document.createElement('td');
      td.textContent = c;
      tr.appendChild(td);
    }
    const pr = p.params || {};
    tr.title = `depth ${(100 * p.total_depth).toFixed(1)} %, crown ${(100 * p.crown_height).toFixed(1)} %, pavilion ${(100 * p.pavilion_depth).toFixed(1)} %`
      + (pr.table !== undefined ? `, table ${(100 * pr.table).toFixed(1)} %` : '')
      + `; fire ${p.scores.fire.toFixed(3)}, scintillation ${p.scores.scintillation.toFixed(3)}`;
    tr.addEventListener('click', () => showViews(tr, p));
    tb.appendChild(tr);
    if (i === 0) showViews(tr, p);
  });
}

// A layout's stones (family, carats, value, position), its saw plan and overview picture.
function showStones(s) {
  const stones = s.stones || [];
  const table = $p('#plan-stone-table');
  const tb = table.querySelector('tbody');
  tb.textContent = '';
  table.hidden = stones.length === 0;
  for (const st of stones) {
    const tr = document.createElement('tr');
    const c = st.centre_mm;
    const cells = [`${st.stem} (${st.piece})`, st.family, st.carats.toFixed(3), st.objective.toFixed(2),
      c ? c.map((x) => x.toFixed(2)).join(', ') : '—'];
    for (const x of cells) {
      const td = document.createElement('td');
      td.textContent = x;
      tr.appendChild(td);
    }
    tr.title = `width ${st.width_mm.toFixed(2)} mm, yield ${(100 * st.yield).toFixed(1)} %` + (st.holds.length ? `; holds ${st.holds.join(', ')}` : '');
    tb.appendChild(tr);
  }
  const saw = $p('#plan-saw');
  const l = s.layout;
  saw.hidden = !l;
  if (l) {
    saw.textContent = `${l.stones} of ${l.stones_asked} stones, ${l.total_carats.toFixed(3)} ct, objective ${l.total_objective.toFixed(2)}; `
      + `${(s.saw_plan || []).length} ${l.cutter || 'saw'} cuts, kerf loss ${l.kerf_loss_mm3.toFixed(2)} mm³`;
  }
  const link = $p('#plan-overview-link');
  link.hidden = !(l && s.overview);
  if (l && s.overview) {
    $p('#plan-overview').src = s.overview + '?id=' + s.id;
    link.href = s.overview;
  }
}

function showViews(tr, p) {
  for (const r of document.querySelectorAll('#plan-table tbody tr')) r.classList.toggle('on', r === tr);
  plan.chosen = p;
  $p('#plan-open').hidden = !plan.meta.presets.some((x) => x.family === p.family);
  if (!p.views) return;
  $p('#plan-views').src = p.views;
  $p('#plan-views-link').href = p.views;
  $p('#plan-views-link').hidden = false;
}

// Load the chosen plan's cut as A (its family's first preset with the plan's parameters), at the
// plan's width and in its material: the weight row then shows the plan's carats.
async function openPlan() {
  const p = plan.chosen;
  const preset = p && plan.meta.presets.find((x) => x.family === p.family);
  if (!preset) return;
  const st = state.stone;
  st.width = p.width_mm;
  $p('#stone-mm').value = p.width_mm.toFixed(2);
  if (plan.material && state.meta.materials.some((m) => m.name === plan.material)) {
    st.material = plan.material;
    $p('#material').value = plan.material;
  }
  const sel = $p('#preset');
  const file = sel.querySelector('option[value="__file"]');
  if (file) file.remove();
  sel.value = preset.name;
  if (!(await loadSource({ cut: preset.name }))) return;
  const s = state.slots.a;
  for (const [k, v] of Object.entries(p.params || {})) {
    if (s.base[k] === undefined || Math.abs(v - s.base[k]) > 1e-12) s.set[k] = v;
  }
  buildParams();
  s.t0 = performance.now();
  schedule('a', 'all', 0);
}

function readRough(file) {
  const ext = (file.name.split('.').pop() || '').toLowerCase();
  const status = $p('#plan-status');
  if (ext !== 'obj' && ext !== 'stl') {
    status.textContent = `rough: ${file.name} is not an .obj or .stl mesh`;
    return;
  }
  const reader = new FileReader();
  reader.onerror = () => { status.textContent = `rough: could not read ${file.name}`; };
  const take = (upload) => {
    plan.upload = upload;
    // A mesh is planned as it is (mm) unless a size is typed after choosing it.
    plan.scale = false;
    $p('#plan-size').value = '';
    const sel = $p('#plan-rough');
    sel.querySelector('option[value="__upload"]').textContent = 'mesh: ' + file.name;
    sel.value = '__upload';
    status.textContent = `${file.name} ready; Plan starts it`;
  };
  if (ext === 'stl') {
    reader.onload = () => {
      const bytes = new Uint8Array(reader.result);
      let bin = '';
      for (let i = 0; i < bytes.length; i += 0x8000) bin += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
      take({ rough: btoa(bin), format: 'stl', encoding: 'base64', name: file.name });
    };
    reader.readAsArrayBuffer(file);
  } else {
    reader.onload = () => take({ rough: String(reader.result), format: 'obj', name: file.name });
    reader.readAsText(file);
  }
}

async function setupPlan() {
  let meta;
  try {
    meta = await (await fetch('/api/presets')).json();
  } catch (e) {
    return;
  }
  plan.meta = meta;
  // The rough's largest extent: the library's one range (its own checks refuse the rest).
  $p('#plan-size').max = String(meta.limits.rough_mm[1]);
  const sel = $p('#plan-rough');
  for (const c of meta.crystals) {
    const o = document.createElement('option');
    o.value = c;
    o.textContent = 'crystal: ' + c;
    sel.appendChild(o);
  }
  sel.value = meta.crystals[0];
  const fams = $p('#plan-families');
  for (const f of meta.families) {
    const o = document.createElement('option');
    o.value = f.name;
    o.textContent = f.name;
    o.selected = f.name === meta.plan.default_family;
    fams.appendChild(o);
  }
  $p('#plan-top').value = String(meta.plan.top[2]);
  $p('#plan-starts').value = String(meta.plan.starts[2]);
  $p('#plan-size').addEventListener('input', () => { plan.scale = true; });
  sel.addEventListener('change', () => {
    if (sel.value !== '__upload' && $p('#plan-size').value.trim() === '') $p('#plan-size').value = '6';
  });
  $p('#plan-file').addEventListener('change', (ev) => {
    const f = ev.target.files && ev.target.files[0];
    if (f) readRough(f);
    ev.target.value = '';
  });
  $p('#plan-inclusions').addEventListener('change', async (ev) => {
    const files = Array.from(ev.target.files || []);
    plan.inclusions = await Promise.all(files.map((f) => f.text()));
    $p('#plan-inclusions-n').textContent = files.length ? `${files.length} inclusion${files.length > 1 ? 's' : ''}` : '';
    ev.target.value = '';
  });
  $p('#plan-run').addEventListener('click', startPlan);
  $p('#plan-open').addEventListener('click', openPlan);
  $p('#plan-stop').addEventListener('click', () => fetch('/api/plan/stop', { method: 'POST' }).then(pollPlan));
  pollPlan();
}

setupPlan();
