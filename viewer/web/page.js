// The page (viewer/web/README.md): the controls of the desktop viewer (handout/viewer.md) around
// the kit's C++ compiled to WebAssembly. Every step, every parameter check, the critical step and
// the divergence diagnosis are the kit's (binding.cpp); this file only draws and forwards input.
// URL: ?scene=task2 (or task1 ... task5, task4-damped), or ?scene-file=NAME for scenes/NAME beside
// the page; &impl=student for "yours" against the reference; &paused=1 to start paused.
'use strict';

const query = new URLSearchParams(location.search);
const $ = id => document.getElementById(id);
const shownElsewhere = new Set(['name', 'task', 'integrator', 'step', 'duration']);
const familyNames = ['structural', 'shear', 'bend'];

const page = {
  lab: null,
  module: null,
  camera: new Camera(),
  referenceCamera: null,  // side by side: the reference's view shares the camera
  springs: null,
  builds: -1,
  freshStarts: -1,
  selected: -1,
  hidden: new Set(),
  strainScale: 0.05,
  stepSeconds: 0,  // one step's wall time, s (a running mean): how many fit in a frame
  lastFrame: 0,
  frames: [],  // {interval, work, steps, dropped, simulated} of each frame while running
  panelShown: 0,
  fieldsOf: -1,
  gesture: null,
};

// ---- frames -----------------------------------------------------------------------------------

function viewRects() {
  const canvas = $('scene-canvas');
  const w = canvas.width, h = canvas.height;
  if (page.lab.compare() === 'side-by-side' && page.lab.code() === 'student')
    return {primary: {x: 0, y: 0, width: w / 2, height: h}, reference: {x: w / 2, y: 0, width: w / 2, height: h}};
  return {primary: {x: 0, y: 0, width: w, height: h}, reference: null};
}

function resizeCanvases() {
  const dpr = window.devicePixelRatio || 1;
  for (const canvas of [$('scene-canvas'), $('energy-plot'), $('momentum-plot')]) {
    const w = Math.max(1, Math.round(canvas.clientWidth * dpr));
    const h = Math.max(1, Math.round(canvas.clientHeight * dpr));
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  }
}

function fit() {
  const positions = page.lab.positions(false);
  if (!positions) return;
  const view = viewRects().primary;
  page.camera.fit(positions, view.width, view.height, page.gravity);
}

function draw() {
  resizeCanvases();
  const lab = page.lab;
  const state = lab.state();
  if (state.builds !== page.builds) {
    page.builds = state.builds;
    page.springs = lab.springs();
    page.spacing = fieldValue('spacing');
    page.gravity = fieldValue('gravity.enabled');
    page.fieldsOf = -1;
  }
  if (state.freshStarts !== page.freshStarts) {
    page.freshStarts = state.freshStarts;
    page.selected = -1;
    fit();
  }
  const canvas = $('scene-canvas');
  const ctx = canvas.getContext('2d');
  ctx.fillStyle = colours.background;
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  const positions = lab.positions(false);
  if (positions && page.springs) {
    if (!page.camera.fitted) fit();
    const views = viewRects();
    const problem = lab.problem();
    const rings = [page.selected];
    if (problem.kind === 'diverged' && problem.particle >= 0) rings.push(problem.particle);
    const options = {strainScale: page.strainScale, hidden: page.hidden, spacing: page.spacing,
                     rings, ghost: false};
    const reference = lab.positions(true);
    const pinned = lab.pinned();
    if (page.springs.rest.length > pixelSprings) {
      if (!page.image || page.image.width !== canvas.width || page.image.height !== canvas.height)
        page.image = ctx.createImageData(canvas.width, canvas.height);
      new Uint32Array(page.image.data.buffer).fill(backgroundPixel);
      if (reference)
        pixelSpringLines(page.image, page.camera, views.reference || views.primary,
                         {positions: reference, springs: page.springs}, {...options, ghost: !views.reference});
      pixelSpringLines(page.image, page.camera, views.primary, {positions, springs: page.springs}, options);
      ctx.putImageData(page.image, 0, 0);
      options.pixels = true;
    }
    if (reference && views.reference) {
      drawRun(ctx, page.camera, views.reference, {positions: reference, springs: page.springs, pinned},
              {...options, rings: []});
      ctx.strokeStyle = 'rgb(70, 74, 88)';
      ctx.beginPath(); ctx.moveTo(views.reference.x, 0); ctx.lineTo(views.reference.x, canvas.height); ctx.stroke();
      label(ctx, 'yours', views.primary);
      label(ctx, 'the reference', views.reference);
    } else if (reference) {
      drawRun(ctx, page.camera, views.primary, {positions: reference, springs: page.springs, pinned},
              {...options, ghost: true, rings: []});
    }
    drawRun(ctx, page.camera, views.primary, {positions, springs: page.springs, pinned}, options);
  }
  const h = lab.history();
  drawPlot($('energy-plot'), h.time, [
    {values: h.kinetic, colour: 'rgb(255, 120, 80)'},
    {values: h.potential, colour: 'rgb(90, 200, 255)'},
    {values: h.total, colour: 'rgb(235, 235, 245)'}]);
  drawPlot($('momentum-plot'), h.time, [
    {values: h.momentumX, colour: 'rgb(120, 255, 120)'},
    {values: h.momentumY, colour: 'rgb(255, 60, 200)'}]);
  return state;
}

function label(ctx, text, view) {
  ctx.fillStyle = 'rgb(150, 155, 170)';
  ctx.font = `${13 * (window.devicePixelRatio || 1)}px system-ui, sans-serif`;
  ctx.fillText(text, view.x + 10, view.y + 20 * (window.devicePixelRatio || 1));
}

function tick(now) {
  const lab = page.lab;
  const seconds = page.lastFrame ? (now - page.lastFrame) / 1000 : 1 / 60;
  const interval = page.lastFrame ? now - page.lastFrame : 0;
  page.lastFrame = now;
  const start = performance.now();
  const before = lab.state().time;
  // No more steps than fit in 90 % of a 60 Hz frame, as the desktop viewer does.
  const most = page.stepSeconds > 0 ? Math.max(1, Math.floor(0.9 / 60 / page.stepSeconds)) : 1;
  const steps = lab.running() ? lab.frame(seconds, most) : 0;
  const stepped = performance.now() - start;
  if (steps > 0) {
    const each = stepped / 1000 / steps;
    page.stepSeconds = page.stepSeconds > 0 ? 0.8 * page.stepSeconds + 0.2 * each : each;
  }
  const state = draw();
  const work = performance.now() - start;
  if (state.running && interval > 0)
    page.frames.push({interval, work, stepping: stepped, steps, dropped: lab.droppedSteps(),
                      simulated: state.time - before});
  if (page.frames.length > 5000) page.frames.shift();
  if (now - page.panelShown > 100) {  // the other read-outs ten times a second
    page.panelShown = now;
    showPanel(state);
  } else {
    showTime(state);
  }
  requestAnimationFrame(tick);
}

function percentile(values, p) {
  if (values.length === 0) return NaN;
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.floor(p / 100 * sorted.length))];
}

// The frames measured since the last call of resetFrames: intervals between frames and the page's
// own work in each (stepping and drawing), ms; the simulated time per wall time.
function frameStats() {
  const f = page.frames;
  const wall = f.reduce((s, x) => s + x.interval, 0) / 1000;
  const simulated = f.reduce((s, x) => s + x.simulated, 0);
  const pick = key => f.map(x => x[key]);
  return {
    frames: f.length,
    interval: {p50: percentile(pick('interval'), 50), p95: percentile(pick('interval'), 95),
               p99: percentile(pick('interval'), 99)},
    work: {p50: percentile(pick('work'), 50), p95: percentile(pick('work'), 95),
           p99: percentile(pick('work'), 99)},
    stepping: {p50: percentile(pick('stepping'), 50), p95: percentile(pick('stepping'), 95)},
    steps: f.reduce((s, x) => s + x.steps, 0),
    dropped: f.reduce((s, x) => s + x.dropped, 0),
    realTime: wall > 0 ? simulated / wall : NaN,
  };
}

// ---- the panel --------------------------------------------------------------------------------

function fieldValue(key) {
  const f = page.lab.fields().find(x => x.key === key);
  return f ? f.value : undefined;
}

function number(x) {
  return Number.isFinite(x) ? Number(x.toPrecision(4)).toString() : String(x);
}

// The time, every frame: the same t as the plots' last point.
function showTime(state) {
  $('time').textContent = `t = ${state.time.toFixed(3)} s, ${state.steps} steps; ` +
    `${state.particles} particles, ${state.springs} springs`;
}

function showPanel(state) {
  const lab = page.lab;
  $('run').textContent = state.running ? 'Pause' : 'Run';
  showTime(state);
  const info = lab.stepInfo();
  if ($('integrator').value !== info.integrator) $('integrator').value = info.integrator;
  if (document.activeElement !== $('h')) $('h').value = String(info.h);
  showCritical(info);
  showProblem(lab.problem());
  const compared = lab.comparison();
  $('note').hidden = !(compared && (compared.remark || lab.compare() !== 'off'));
  if (compared) $('note').textContent = `Yours ${compared.figures}` + (compared.remark ? `. ${compared.remark}` : '');
  showParticle();
  if (page.fieldsOf !== page.builds) showFields();
  const s = frameStats();
  $('frames').textContent = s.frames === 0 ? 'paused' :
    `frame interval p50 ${number(s.interval.p50)} ms, p95 ${number(s.interval.p95)} ms; ` +
    `the page's work p50 ${number(s.work.p50)} ms; ${number(s.realTime)}× real time` +
    (s.dropped ? `; ${s.dropped} steps dropped` : '');
  while (page.frames.length > 600) page.frames.shift();
}

function showCritical(info) {
  const warning = $('h-warning');
  let text = '', warn = '';
  const limit = info.critical;
  if (limit === null) text = `critical step ${info.note}`;
  else if (limit === 0) warn = 'critical step: none, unstable at every h';
  else if (!Number.isFinite(limit)) text = 'critical step: none, stable at every h';
  else if (info.estimate && info.h > limit) warn = `h > ${number(limit)} s, the step known to be safe: it may blow up`;
  else if (info.h > limit) warn = `h > critical step ${number(limit)} s: expect it to blow up`;
  else if (info.estimate) text = `safe step ${number(limit)} s (h is ${Math.round(100 * info.h / limit)}% of it)`;
  else text = `critical step ${number(limit)} s (h is ${Math.round(100 * info.h / limit)}% of it)`;
  if (info.estimate)
    text += (text ? '; ' : '') + 'from a bound on ω_max (no eigen-solve above 100 particles): ' +
      'the critical step itself is larger (handout section 5)';
  $('critical').textContent = text;
  warning.hidden = !warn;
  warning.textContent = warn;
}

function showProblem(problem) {
  const banner = $('banner');
  banner.hidden = problem.kind === 'none';
  if (banner.hidden) return;
  let headline = problem.headline;
  if (problem.kind === 'diverged' && problem.particle >= 0)
    headline += `, particle ${problem.particle} (${problem.quantity})`;
  $('banner-headline').textContent = headline;
  $('banner-detail').textContent = problem.detail;
  banner.dataset.kind = problem.kind;
}

function showParticle() {
  const i = page.selected;
  const positions = page.lab.positions(false);
  const ok = positions && i >= 0 && i < positions.length / 2;
  $('pin').disabled = $('push').disabled = !ok;
  if (!ok) { $('particle').textContent = 'Tap or click a particle.'; return; }
  const v = page.lab.velocities(false);
  const pinned = page.lab.pinned()[i];
  $('pin').textContent = pinned ? 'Unpin' : 'Pin';
  $('particle').textContent = `particle ${i}${pinned ? ' (pinned)' : ''}: r = (${number(positions[2 * i])}, ` +
    `${number(positions[2 * i + 1])}) m, v = (${number(v[2 * i])}, ${number(v[2 * i + 1])}) m/s`;
}

// A slider's ends for a real field, as the desktop viewer sets them (parameter_widgets.cpp): a
// logarithmic span of 100× either way around a positive value as loaded, the field's own range
// when it is narrow, otherwise a span around the value.
function spanOf(field) {
  const loaded = field.loaded;
  if (field.type === 'int')
    return {low: Math.max(field.min, -1e9), high: Math.min(field.max, Math.max(10 * loaded, 100)), log: false};
  if (loaded > 0 && field.min >= 0)
    return {low: field.minOpen || field.min === 0 ? Math.max(loaded / 100, field.min) : field.min,
            high: Math.min(loaded * 100, field.max), log: true};
  if (field.max - field.min <= 1000) return {low: field.min, high: field.max, log: false};
  const half = Math.max(2 * Math.abs(loaded), 1);
  return {low: Math.max(field.min, loaded - half), high: Math.min(field.max, loaded + half), log: false};
}

const sliderSteps = 1000;
function toSlider(span, value) {
  const t = span.log ? Math.log(value / span.low) / Math.log(span.high / span.low)
                     : (value - span.low) / (span.high - span.low);
  return Math.round(Math.max(0, Math.min(1, t)) * sliderSteps);
}
function fromSlider(span, position, integer) {
  const t = position / sliderSteps;
  const value = span.log ? span.low * Math.pow(span.high / span.low, t) : span.low + t * (span.high - span.low);
  return integer ? String(Math.round(value)) : String(Number(value.toPrecision(4)));
}

// One control per scene parameter (booleans a box, numbers a slider and a box to type in);
// a value the kit refuses is not applied, and its message is shown under the control.
function showFields() {
  const lab = page.lab;
  page.fieldsOf = page.builds;
  const box = $('fields');
  if (box.contains(document.activeElement)) return;  // not while the user is typing there
  box.textContent = '';
  let group = '';
  for (const field of lab.fields()) {
    if (shownElsewhere.has(field.key) || field.type === 'text') continue;
    const dot = field.key.indexOf('.');
    const g = dot < 0 ? 'scene' : field.key.slice(0, dot);
    if (g !== group) {
      group = g;
      const h = document.createElement('div');
      h.className = 'group';
      h.textContent = g;
      box.append(h);
    }
    const row = document.createElement('div');
    row.className = 'field';
    row.dataset.key = field.key;
    row.title = `${field.meaning}${field.allowed ? `\nallowed: ${field.allowed}` : ''}`;
    const name = document.createElement('label');
    name.className = field.type === 'bool' ? 'check' : 'name';
    const error = document.createElement('div');
    error.className = 'error';
    error.hidden = true;
    const apply = text => {
      const message = lab.set(field.key, text);
      error.hidden = !message;
      error.textContent = message ? `not applied: ${message}` : '';
      return !message;
    };
    if (field.type === 'bool') {
      const check = document.createElement('input');
      check.type = 'checkbox';
      check.checked = field.value;
      check.addEventListener('change', () => apply(check.checked ? 'true' : 'false'));
      name.append(check, ` ${field.key}`);
      row.append(name, error);
    } else {
      const unit = field.unit ? ` [${field.unit}]` : '';
      const typed = document.createElement('input');
      typed.type = 'text';
      typed.inputMode = 'decimal';
      typed.value = String(field.value);
      typed.size = 8;
      typed.setAttribute('aria-label', field.key);
      name.append(`${field.key}${unit}`, typed);
      const span = spanOf(field);
      const slider = document.createElement('input');
      slider.type = 'range';
      slider.min = 0;
      slider.max = sliderSteps;
      slider.value = toSlider(span, field.value);
      slider.setAttribute('aria-label', `${field.key} slider`);
      // Reals apply while the slider moves; whole numbers rebuild the grid, so on letting go.
      slider.addEventListener(field.type === 'int' ? 'change' : 'input', () => {
        const text = fromSlider(span, Number(slider.value), field.type === 'int');
        typed.value = text;
        apply(text);
      });
      typed.addEventListener('change', () => {
        if (apply(typed.value.trim())) slider.value = toSlider(span, Number(typed.value));
      });
      row.append(name, slider, error);
    }
    box.append(row);
  }
}

// ---- input ------------------------------------------------------------------------------------

function canvasPoint(event) {
  const canvas = $('scene-canvas');
  const rect = canvas.getBoundingClientRect();
  const dpr = window.devicePixelRatio || 1;
  return [(event.clientX - rect.left) * dpr, (event.clientY - rect.top) * dpr];
}

function pickAt(px, py, reach) {
  const positions = page.lab.positions(false);
  if (!positions) return -1;
  return nearestParticle(page.camera, viewRects().primary, positions, px, py, reach * (window.devicePixelRatio || 1));
}

function pushVelocity() {
  return [Number($('push-x').value) || 0, Number($('push-y').value) || 0];
}

function setUpInput() {
  const canvas = $('scene-canvas');
  const pointers = new Map();
  canvas.addEventListener('contextmenu', e => e.preventDefault());
  canvas.addEventListener('pointerdown', event => {
    canvas.setPointerCapture(event.pointerId);
    const [px, py] = canvasPoint(event);
    pointers.set(event.pointerId, [px, py]);
    if (pointers.size === 2) {  // two fingers: zoom and pan
      if (page.gesture && page.gesture.kind === 'drag') page.lab.release();
      page.gesture = {kind: 'pinch'};
      return;
    }
    const particle = pickAt(px, py, event.pointerType === 'touch' ? 24 : 12);
    if (particle >= 0) {
      page.selected = particle;
      if (event.button === 2 || $('touch-pin').checked) {
        page.lab.togglePin(particle);
      } else if (event.shiftKey) {
        page.lab.push(particle, ...pushVelocity());
      } else {
        page.lab.grab(particle);
        page.gesture = {kind: 'drag'};
      }
    } else {
      page.gesture = {kind: 'pan', x: px, y: py};
    }
    showParticle();
  });
  canvas.addEventListener('pointermove', event => {
    if (!pointers.has(event.pointerId)) return;
    const [px, py] = canvasPoint(event);
    const [ox, oy] = pointers.get(event.pointerId);
    pointers.set(event.pointerId, [px, py]);
    const g = page.gesture;
    if (!g) return;
    if (g.kind === 'drag') {
      page.lab.dragTo(...page.camera.toWorld(px, py, viewRects().primary));
    } else if (g.kind === 'pan') {
      page.camera.cx -= (px - g.x) / page.camera.scale;
      page.camera.cy += (py - g.y) / page.camera.scale;
      g.x = px; g.y = py;
    } else if (g.kind === 'pinch' && pointers.size === 2) {
      const [a, b] = [...pointers.values()];
      const other = a === pointers.get(event.pointerId) ? b : a;
      const before = Math.hypot(ox - other[0], oy - other[1]);
      const after = Math.hypot(px - other[0], py - other[1]);
      if (before > 0) page.camera.zoom(after / before, (px + other[0]) / 2, (py + other[1]) / 2, viewRects().primary);
    }
  });
  const end = event => {
    pointers.delete(event.pointerId);
    if (page.gesture && page.gesture.kind === 'drag') page.lab.release();
    if (pointers.size === 0 || (page.gesture && page.gesture.kind === 'drag')) page.gesture = null;
  };
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
  canvas.addEventListener('wheel', event => {
    event.preventDefault();
    const [px, py] = canvasPoint(event);
    page.camera.zoom(Math.exp(-event.deltaY / 500), px, py, viewRects().primary);
  }, {passive: false});

  document.addEventListener('keydown', event => {
    const tag = document.activeElement && document.activeElement.tagName;
    if (tag === 'INPUT' || tag === 'SELECT' || tag === 'TEXTAREA' || event.ctrlKey || event.metaKey) return;
    const lab = page.lab;
    switch (event.key) {
      case ' ': lab.setRunning(!lab.running()); break;
      case 's': case 'S': case 'ArrowRight': lab.singleStep(); break;
      case 'r': case 'R': lab.reset(); break;
      case 'f': case 'F': fit(); break;
      case 'p': case 'P': if (page.selected >= 0) lab.togglePin(page.selected); break;
      case 'u': case 'U': if (page.selected >= 0) lab.push(page.selected, ...pushVelocity()); break;
      default: return;
    }
    event.preventDefault();
    showPanel(lab.state());
  });

  $('run').addEventListener('click', () => page.lab.setRunning(!page.lab.running()));
  $('step').addEventListener('click', () => page.lab.singleStep());
  $('reset').addEventListener('click', () => page.lab.reset());
  $('banner-reset').addEventListener('click', () => page.lab.reset());
  $('fit').addEventListener('click', fit);
  $('pin').addEventListener('click', () => page.selected >= 0 && page.lab.togglePin(page.selected));
  $('push').addEventListener('click', () => page.selected >= 0 && page.lab.push(page.selected, ...pushVelocity()));
  $('speed').addEventListener('input', () => {
    const factor = Math.pow(10, Number($('speed').value));
    page.lab.setRealTimeFactor(factor);
    $('speed-out').textContent = `${Number(factor.toPrecision(2))}× real time`;
  });
  $('strain-scale').addEventListener('input', () => {
    page.strainScale = Number($('strain-scale').value);
    $('strain-out').textContent = `${Number((100 * page.strainScale).toPrecision(2))} %`;
  });
  $('integrator').addEventListener('change', () => page.lab.set('integrator', $('integrator').value));
  $('h').addEventListener('change', () => {
    const message = page.lab.set('step', $('h').value.trim());
    $('h-error').hidden = !message;
    $('h-error').textContent = message;
  });
  $('scene').addEventListener('change', () => {
    if (!$('scene').selectedOptions[0].dataset.file) loadScene(() => page.lab.load($('scene').value));
  });
  $('scene-file').addEventListener('change', async () => {
    const file = $('scene-file').files[0];
    if (!file) return;
    const text = await file.text();
    loadScene(() => page.lab.loadText(file.name, text));
    $('scene-file').value = '';
  });
  $('code').addEventListener('change', () => page.lab.setCode($('code').value));
  $('compare').addEventListener('change', () => page.lab.setCompare($('compare').value));
  for (const [index, name] of familyNames.entries()) {
    const label = document.createElement('label');
    label.className = 'check';
    const box = document.createElement('input');
    box.type = 'checkbox';
    box.checked = true;
    box.addEventListener('change', () => {
      if (box.checked) page.hidden.delete(index); else page.hidden.add(index);
    });
    label.append(box, `${name} springs`);
    $('families').append(label);
  }
  window.addEventListener('resize', () => { resizeCanvases(); });
}

// The scene list shows what is loaded: a scene file as an entry of its own.
function showSource() {
  const select = $('scene'), source = page.lab.source();
  for (const option of [...select.options]) if (option.dataset.file) option.remove();
  if (page.module.sceneNames().includes(source)) { select.value = source; return; }
  const option = new Option(`${source} (file)`, source);
  option.dataset.file = '1';
  select.add(option);
  select.value = source;
}

function loadScene(load) {
  load();
  showSource();
  page.camera.fitted = false;
  page.freshStarts = -1;
  page.frames = [];
  $('h-error').hidden = true;
  showPanel(draw());
}

// ---- start ------------------------------------------------------------------------------------

async function start(module) {
  page.module = module;
  const scene = query.get('scene') || 'task5';
  for (const name of module.sceneNames()) $('scene').add(new Option(name, name));
  for (const name of module.integratorNames()) $('integrator').add(new Option(name, name));
  page.lab = new module.Lab(scene);
  if (module.sceneNames().includes(scene)) $('scene').value = scene;
  if (query.get('impl') === 'student') {
    $('code-controls').hidden = false;
    $('code').value = 'student';
    page.lab.setCode('student');
    if (module.referenceAvailable()) {
      $('compare').value = 'overlay';
      page.lab.setCompare('overlay');
    }
  }
  // ./lab web my_scene.toml puts the file beside the page, in scenes/.
  const file = query.get('scene-file');
  if (file) {
    const response = await fetch(`scenes/${encodeURIComponent(file)}`);
    page.lab.loadText(file, response.ok ? await response.text() : '');
  }
  showSource();
  if (query.get('paused') === '1') page.lab.setRunning(false);
  setUpInput();
  $('status').textContent = 'the kit’s C++ in WebAssembly, one thread';
  showPanel(draw());
  requestAnimationFrame(tick);
}

// What the browser tests (tests/web/) reach: the binding, the page's own measurements and where a
// particle is on the screen; the tests drive the page through its controls and real input too.
window.springlab = {
  page,
  ready: createSpringlab().then(start).then(() => true),
  frameStats,
  draw,
  resetFrames: () => { page.frames = []; },
  particleOnScreen: i => {
    const positions = page.lab.positions(false);
    const [x, y] = page.camera.toScreen(positions[2 * i], positions[2 * i + 1], viewRects().primary);
    const rect = $('scene-canvas').getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    return {x: rect.left + x / dpr, y: rect.top + y / dpr};
  },
  worldAt: (clientX, clientY) => {
    const rect = $('scene-canvas').getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    return page.camera.toWorld((clientX - rect.left) * dpr, (clientY - rect.top) * dpr, viewRects().primary);
  },
};
