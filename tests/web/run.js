#!/usr/bin/env node
// The page in a real browser (viewer/web/README.md, "How it is tested"): Debian's Chromium,
// headless, driven by puppeteer-core, loads the page from a server on 127.0.0.1 and is checked
// against springlab-run, the native runner, on the same scenes:
//   - every task scene runs in the page, picked from its scene list;
//   - after N steps every position and velocity is the runner's CSV value, to the bit, for each
//     task scene and for every integrator (the fabric in the wind to 1e-9 m: the browser's sine
//     is not glibc's vector sine, the bound tests/lab/portable.sh gives for two sines);
//   - dragging a particle with the mouse moves it to the point under the mouse, a right click
//     pins it, shift+click pushes it, a finger on a touch screen drags it too;
//   - a run past the critical step stops with the runner's words for why;
//   - a malformed scene file and an h out of range give the runner's error text;
//   - screenshots (a laptop's and a tablet's size) are not blank: distinct colours counted.
// No verdict waits on the clock: the page is stepped a given number of steps, or waited on until
// a condition holds (the waits' time limits only end a hung browser).
// With --measure, figures (not verdicts): the 100x100 fabric's frame times as the page measures
// them, and one step of it in WebAssembly beside the same step in springlab-run, ns a spring.
//   node tests/web/run.js --site DIR --runner PATH --out DIR [--chromium PATH] [--measure]
'use strict';

const childProcess = require('child_process');
const fs = require('fs');
const http = require('http');
const os = require('os');
const path = require('path');
const puppeteer = require('puppeteer-core');

function options() {
  const out = {chromium: '/usr/bin/chromium', measure: false};
  const args = process.argv.slice(2);
  for (let i = 0; i < args.length; ++i) {
    const take = () => {
      if (i + 1 >= args.length) usage(`${args[i]} needs a value`);
      return args[++i];
    };
    if (args[i] === '--site') out.site = take();
    else if (args[i] === '--runner') out.runner = take();
    else if (args[i] === '--out') out.out = take();
    else if (args[i] === '--chromium') out.chromium = take();
    else if (args[i] === '--measure') out.measure = true;
    else usage(`unknown argument '${args[i]}'`);
  }
  for (const key of ['site', 'runner', 'out']) if (!out[key]) usage(`--${key} is missing`);
  out.runner = path.resolve(out.runner);  // it runs in scratch folders
  if (!fs.existsSync(path.join(out.site, 'springlab-web.wasm')))
    usage(`--site ${out.site}: no springlab-web.wasm there (build it: ./lab web --out DIR, or cmake --build build/web)`);
  if (!fs.existsSync(out.runner)) usage(`--runner ${out.runner}: no such program (./lab run --help builds it)`);
  if (!fs.existsSync(out.chromium)) usage(`--chromium ${out.chromium}: no such program (./lab setup --web installs chromium)`);
  return out;
}

function usage(message) {
  console.error(`tests/web/run.js: ${message}\nusage: node tests/web/run.js --site DIR --runner PATH --out DIR [--chromium PATH] [--measure]`);
  process.exit(2);
}

// ---- verdicts ---------------------------------------------------------------------------------

let failures = 0;
function ok(text) { console.log(`web: ok: ${text}`); }
function fail(text) { console.log(`web: FAIL: ${text}`); ++failures; }
function check(condition, text, why) { if (condition) ok(text); else fail(`${text}: ${why}`); }

// ---- the server: the site's files, on 127.0.0.1 only ------------------------------------------

const types = {'.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css',
               '.wasm': 'application/wasm', '.png': 'image/png'};
function serve(root) {
  const server = http.createServer((request, response) => {
    const url = new URL(request.url, 'http://127.0.0.1');
    const file = path.join(root, path.normalize(decodeURIComponent(url.pathname)).replace(/^(\.\.[/\\])+/, ''));
    const name = url.pathname.endsWith('/') ? path.join(file, 'index.html') : file;
    fs.readFile(name, (error, data) => {
      if (error) { response.writeHead(404); response.end('not found'); return; }
      response.writeHead(200, {'Content-Type': types[path.extname(name)] || 'application/octet-stream'});
      response.end(data);
    });
  });
  return new Promise(resolve => server.listen(0, '127.0.0.1', () => resolve(server)));
}

// ---- the runner -------------------------------------------------------------------------------

// springlab-run ARGS in `cwd`: its exit code and its messages, without the "springlab-run: " of
// each line.
function runner(program, args, cwd, env) {
  const result = childProcess.spawnSync(program, args, {cwd, encoding: 'utf8', env: {...process.env, ...env}});
  if (result.error) throw new Error(`${program} could not run: ${result.error.message}`);
  const strip = text => text.split('\n').filter(l => l).map(l => l.replace(/^springlab-run: /, '')).join('\n');
  return {status: result.status, stderr: strip(result.stderr), stdout: result.stdout};
}

// The CSV's rows as numbers: [t, x0, y0, vx0, vy0, ..., kinetic, potential, px, py].
function csvRows(file) {
  return fs.readFileSync(file, 'utf8').trim().split('\n').slice(1).map(line => line.split(',').map(Number));
}

// ---- checks -----------------------------------------------------------------------------------

async function runsInThePage(page, scene) {
  await page.select('#scene', scene);
  const start = await page.evaluate(() => springlab.page.lab.state().steps);
  await page.evaluate(() => springlab.page.lab.setRunning(true));
  // Ten frames that each took steps, or a problem: whichever comes first.
  await page.waitForFunction(s => {
    const lab = springlab.page.lab;
    return lab.problem().kind !== 'none' || lab.state().steps >= s + 10;
  }, {timeout: 120000, polling: 'raf'}, start);
  const result = await page.evaluate(() => ({problem: springlab.page.lab.problem(), state: springlab.page.lab.state(),
                                             shown: document.getElementById('time').textContent}));
  check(result.problem.kind === 'none' && result.state.steps > start && result.state.name === scene,
        `${scene} runs in the page (picked from the scene list): ${result.state.steps} steps, t = ${result.state.time.toFixed(3)} s, ${result.state.particles} particles`,
        `problem ${JSON.stringify(result.problem)}, state ${JSON.stringify(result.state)}`);
}

// The page's state after `steps` steps of scene with sets ("key=value"), against the runner's CSV
// of the same run; tolerance 0 asks for the same bits.
async function sameAsRunner(page, opts, scratch, name, scene, sets, duration, tolerance, why) {
  const csv = path.join(scratch, 'run.csv');
  const args = ['--quiet', '--scene', scene, '--duration', duration, '--csv', csv];
  for (const s of sets) args.push('--set', s);
  const native = runner(opts.runner, args, scratch);
  if (native.status !== 0) { fail(`${name}: springlab-run exited ${native.status}: ${native.stderr}`); return; }
  const rows = csvRows(csv);
  const last = rows[rows.length - 1];
  const steps = rows.length - 1;
  if (typeof tolerance === 'function') tolerance = tolerance(rows);
  const web = await page.evaluate((scene, sets, steps) => {
    const lab = springlab.page.lab;
    lab.load(scene);
    const refused = sets.map(s => lab.set(s.slice(0, s.indexOf('=')), s.slice(s.indexOf('=') + 1))).filter(m => m);
    lab.reset();
    lab.setRunning(false);
    lab.advance(steps);
    return {refused, problem: lab.problem(), state: lab.state(), r: Array.from(lab.positions(false)),
            v: Array.from(lab.velocities(false))};
  }, scene, sets, steps);
  if (web.refused.length || web.problem.kind !== 'none') {
    fail(`${name}: the page refused or stopped: ${web.refused.join('; ')} ${web.problem.headline} ${web.problem.detail}`);
    return;
  }
  const n = web.r.length / 2;
  let differing = 0, largest = 0;
  for (let i = 0; i < n; ++i) {
    const mine = [web.r[2 * i], web.r[2 * i + 1], web.v[2 * i], web.v[2 * i + 1]];
    const theirs = last.slice(1 + 4 * i, 5 + 4 * i);
    for (let k = 0; k < 4; ++k) {
      if (Object.is(mine[k], theirs[k])) continue;
      ++differing;
      largest = Math.max(largest, k < 2 ? Math.abs(mine[k] - theirs[k]) : 0);
      if (!Number.isFinite(mine[k] - theirs[k])) largest = Infinity;
    }
  }
  const what = `${name}: ${steps} steps, ${n} particles (${4 * n} values)`;
  const timeMatches = Math.abs(web.state.time - last[0]) <= 1e-12 * Math.max(1, last[0]) && web.state.steps === steps;
  if (!timeMatches) { fail(`${what}: the page is at t = ${web.state.time} s after ${web.state.steps} steps, the runner at t = ${last[0]} s`); return; }
  if (tolerance === 0)
    check(differing === 0, `${what}, the same bits as springlab-run's CSV`,
          `${differing} values differ, positions by up to ${largest} m`);
  else
    check(largest <= tolerance, `${what}, positions within ${tolerance.toPrecision(2)} m of springlab-run's CSV (${why}): ` +
          `${differing} values differ, positions by at most ${largest.toPrecision(3)} m`,
          `${differing} values differ, positions by up to ${largest} m`);
}

// Implicit Euler's bound (integrator.hpp, implicit_euler.cpp): each step solves A dv = b by
// conjugate gradients until the residual is 1e-12 of b (implicit_euler_tolerance). Natively
// Eigen sums the dot products two lanes at a time (SSE2), here one at a time: the iterations
// round differently, and each run's dv is within about 1e-12 |dv| of the exact one (A = M + hC +
// h^2 K is near M at the lab's values: condition near 1), so the two differ by at most
// 2e-12 |dv| a step. Over N steps of h the positions then differ by at most
// sum_n h sum_{m<=n} 2e-12 |dv|max = 2e-12 |dv|max h N(N+1)/2, taken 10 times for the condition
// number and the motion's own growth. |dv|max is read from the runner's CSV, step by step.
function cgBound(rows) {
  const h = rows[1][0] - rows[0][0], n = rows.length - 1;
  const particles = (rows[0].length - 5) / 4;
  let dv = 0;
  for (let k = 1; k < rows.length; ++k)
    for (let i = 0; i < particles; ++i)
      dv = Math.max(dv, Math.hypot(rows[k][3 + 4 * i] - rows[k - 1][3 + 4 * i], rows[k][4 + 4 * i] - rows[k - 1][4 + 4 * i]));
  return 10 * 2e-12 * dv * h * n * (n + 1) / 2;
}

// Waits until particle i is at the world point under (x, y) of the page, as a drag puts it; the
// browser hands moves to the page at its next frame. Returns where it is and that point.
async function heldAt(page, i, x, y) {
  try {
    await page.waitForFunction((i, x, y) => {
      const r = springlab.page.lab.positions(false), w = springlab.worldAt(x, y);
      return Math.hypot(r[2 * i] - w[0], r[2 * i + 1] - w[1]) < 1e-9;
    }, {polling: 'raf', timeout: 20000}, i, x, y);
  } catch (error) {
    // not there: the verdict below says how far
  }
  return page.evaluate((i, x, y) => ({r: Array.from(springlab.page.lab.positions(false)).slice(2 * i, 2 * i + 2),
                                      at: springlab.worldAt(x, y), grabbed: springlab.page.lab.state().grabbed}), i, x, y);
}

async function dragging(page) {
  await page.evaluate(() => {
    const lab = springlab.page.lab;
    document.getElementById('scene').value = 'task2';
    document.getElementById('scene').dispatchEvent(new Event('change'));
    lab.setRunning(false);
  });
  await page.waitForFunction(() => springlab.page.lab.state().name === 'task2');
  const before = await page.evaluate(() => ({screen: springlab.particleOnScreen(0), r: Array.from(springlab.page.lab.positions(false)).slice(0, 2)}));
  await page.mouse.move(before.screen.x, before.screen.y);
  await page.mouse.down();
  for (let k = 1; k <= 5; ++k) await page.mouse.move(before.screen.x + 12 * k, before.screen.y + 8 * k);
  const held = await heldAt(page, 0, before.screen.x + 60, before.screen.y + 40);
  const moved = Math.hypot(held.r[0] - before.r[0], held.r[1] - before.r[1]);
  const off = Math.hypot(held.r[0] - held.at[0], held.r[1] - held.at[1]);
  check(held.grabbed === 0 && moved > 0.05 && off < 1e-9,
        `dragging particle 0 with the mouse moves it to the point under the mouse (${moved.toFixed(3)} m, ${off.toExponential(1)} m from it)`,
        `grabbed ${held.grabbed}, moved ${moved} m, ${off} m from the mouse`);
  await page.mouse.up();
  const released = await page.evaluate(() => { springlab.page.lab.advance(5); return springlab.page.lab.state().grabbed; });
  check(released === -1, 'letting go releases the particle', `still grabbed: ${released}`);

  const spot = await page.evaluate(() => springlab.particleOnScreen(1));
  await page.mouse.click(spot.x, spot.y, {button: 'right'});
  const pinned = await page.evaluate(() => springlab.page.lab.pinned()[1]);
  await page.mouse.click(spot.x, spot.y, {button: 'right'});
  const unpinned = await page.evaluate(() => springlab.page.lab.pinned()[1]);
  check(pinned === 1 && unpinned === 0, 'a right click pins particle 1, a second one unpins it', `pinned ${pinned}, then ${unpinned}`);

  const v0 = await page.evaluate(() => Array.from(springlab.page.lab.velocities(false)).slice(2, 4));
  const now = await page.evaluate(() => springlab.particleOnScreen(1));
  await page.keyboard.down('Shift');
  await page.mouse.click(now.x, now.y);
  await page.keyboard.up('Shift');
  const v1 = await page.evaluate(() => Array.from(springlab.page.lab.velocities(false)).slice(2, 4));
  check(Math.abs(v1[0] - v0[0]) < 1e-12 && Math.abs(v1[1] - v0[1] - 2) < 1e-12,
        'shift+click pushes particle 1 by the panel\'s (0, 2) m/s', `velocity ${v0} -> ${v1}`);

  // The keys: S steps once, Space runs and pauses, R resets (the desktop viewer's).
  await page.evaluate(() => { document.activeElement.blur(); springlab.page.lab.setRunning(false); });
  const k0 = await page.evaluate(() => springlab.page.lab.state().steps);
  await page.keyboard.press('s');
  const k1 = await page.evaluate(() => springlab.page.lab.state().steps);
  await page.keyboard.press('Space');
  const running = await page.evaluate(() => springlab.page.lab.running());
  await page.keyboard.press('Space');
  const paused = await page.evaluate(() => !springlab.page.lab.running());
  const starts = await page.evaluate(() => springlab.page.lab.state().freshStarts);
  await page.keyboard.press('r');
  const reset = await page.evaluate(() => springlab.page.lab.state());
  check(k1 === k0 + 1 && running && paused && reset.freshStarts === starts + 1 && reset.steps < k1 && reset.running,
        'the keys: S takes one step, Space runs and pauses, R resets',
        `steps ${k0} -> ${k1}, running ${running}, paused ${paused}, after R ${JSON.stringify(reset)}`);
}

async function divergence(page, opts, scratch) {
  const scene = 'task4', h = '0.5';
  const native = runner(opts.runner, ['--quiet', '--scene', scene, '--dt', h], scratch);
  if (native.status !== 3) { fail(`springlab-run --scene ${scene} --dt ${h} exited ${native.status}, not 3 (diverged): ${native.stderr}`); return; }
  await page.select('#scene', scene);
  await page.evaluate(() => springlab.page.lab.setRunning(false));
  await page.click('#h', {clickCount: 3});
  await page.keyboard.type(h);
  await page.keyboard.press('Enter');
  const warning = await page.waitForFunction(() => {
    const w = document.getElementById('h-warning');
    return !w.hidden && w.textContent;
  }, {polling: 'raf'});
  const warned = await warning.jsonValue();
  check(/critical step/.test(warned), `h = ${h} s typed into the panel on ${scene}: "${warned}"`, 'no warning');
  await page.click('#reset');  // from t = 0 with this h, as the runner starts (Reset runs it)
  await page.waitForFunction(() => !document.getElementById('banner').hidden, {timeout: 120000, polling: 'raf'});
  const banner = await page.evaluate(() => ({headline: document.getElementById('banner-headline').textContent,
                                              detail: document.getElementById('banner-detail').textContent,
                                              problem: springlab.page.lab.problem(), running: springlab.page.lab.running()}));
  // The runner says "<what ran away>: <quantity>: <why>"; the banner the same why, capitalised.
  const message = native.stderr;
  const at = message.indexOf(`${banner.problem.quantity}: `);
  let why = at >= 0 ? message.slice(at + banner.problem.quantity.length + 2) : '';
  why = why.charAt(0).toUpperCase() + why.slice(1);
  check(banner.problem.kind === 'diverged' && !banner.running && why !== '' && banner.problem.detail === why &&
        message.includes(`t = ${banner.problem.time} s`),
        `${scene} at h = ${h} s stops in the page with springlab-run's diagnosis: "${banner.headline}: ${banner.detail}"`,
        `page: ${JSON.stringify(banner)}\nrunner: ${message}`);
}

async function badInput(page, opts, scratch) {
  const files = {
    'broken.toml': 'name = "broken"\nrows = 3\ncols = [1, 2\nintegrator = "verlet"\n',
    'heavy.toml': 'name = "heavy"\nrows = 2\ncols = 2\nmass = -1.0\n',
  };
  for (const [name, text] of Object.entries(files)) {
    fs.writeFileSync(path.join(scratch, name), text);
    const native = runner(opts.runner, ['--quiet', '--scene', name], scratch);
    const input = await page.$('#scene-file');
    await input.uploadFile(path.join(scratch, name));
    await page.waitForFunction(n => springlab.page.lab.source() === n && !document.getElementById('banner').hidden,
                               {polling: 'raf'}, name);
    const shown = await page.evaluate(() => ({detail: document.getElementById('banner-detail').textContent,
                                               headline: document.getElementById('banner-headline').textContent}));
    check(native.status === 2 && shown.detail === native.stderr,
          `the scene file ${name} opened in the page: "${shown.headline}: ${shown.detail}", springlab-run's words`,
          `page: ${shown.detail}\nrunner (exit ${native.status}): ${native.stderr}`);
  }
  await page.select('#scene', 'task1');
  for (const h of ['0', '-0.01', '20', 'abc']) {
    const native = runner(opts.runner, ['--quiet', '--scene', 'task1', '--set', `step=${h}`], scratch);
    await page.click('#h', {clickCount: 3});
    await page.keyboard.type(h);
    await page.keyboard.press('Enter');
    const shown = await page.evaluate(() => { const e = document.getElementById('h-error'); return e.hidden ? '' : e.textContent; });
    check(native.status === 2 && shown !== '' && shown === native.stderr,
          `h = ${h} typed into the panel: "${shown}", springlab-run --set step=${h}'s words`,
          `page: ${shown}\nrunner (exit ${native.status}): ${native.stderr}`);
  }
}

// Distinct colours of a PNG, counted by the browser itself.
async function distinctColours(page, png) {
  return page.evaluate(async data => {
    const image = new Image();
    image.src = `data:image/png;base64,${data}`;
    await image.decode();
    const canvas = document.createElement('canvas');
    canvas.width = image.width; canvas.height = image.height;
    const ctx = canvas.getContext('2d');
    ctx.drawImage(image, 0, 0);
    const pixels = new Uint32Array(ctx.getImageData(0, 0, image.width, image.height).data.buffer);
    return new Set(pixels).size;
  }, png.toString('base64'));
}

async function screenshots(browser, base, opts) {
  const sizes = [
    {name: 'desktop', viewport: {width: 1280, height: 800}},
    {name: 'tablet', viewport: {width: 820, height: 1180, isMobile: true, hasTouch: true, deviceScaleFactor: 2}},
  ];
  for (const size of sizes) {
    const page = await browser.newPage();
    await page.setViewport(size.viewport);
    await page.goto(`${base}/index.html?scene=task5`);
    await page.evaluate(() => springlab.ready);
    await page.evaluate(() => springlab.resetFrames());
    await page.waitForFunction(() => springlab.page.frames.length >= 120, {timeout: 120000, polling: 'raf'});
    if (size.name === 'tablet') await touchDrag(page);
    const file = path.join(opts.out, `web-${size.name}-task5.png`);
    const png = await page.screenshot({path: file});
    const colours = await distinctColours(page, png);
    check(colours >= 50, `a screenshot at ${size.name} size (${size.viewport.width}x${size.viewport.height}) has ${colours} distinct colours, kept as ${file}`,
          `only ${colours} distinct colours: blank?`);
    await page.close();
  }
}

async function touchDrag(page) {
  await page.evaluate(() => springlab.page.lab.setRunning(false));
  // Whole CSS pixels: a touch point has no fractions.
  const spot = await page.evaluate(() => {
    const p = springlab.particleOnScreen(399);
    return {x: Math.round(p.x), y: Math.round(p.y)};
  });
  const before = await page.evaluate(() => Array.from(springlab.page.lab.positions(false)).slice(798, 800));
  await page.touchscreen.touchStart(spot.x, spot.y);
  for (let k = 1; k <= 4; ++k) await page.touchscreen.touchMove(spot.x - 10 * k, spot.y + 15 * k);
  const held = await heldAt(page, 399, spot.x - 40, spot.y + 60);
  await page.touchscreen.touchEnd();
  const off = Math.hypot(held.r[0] - held.at[0], held.r[1] - held.at[1]);
  const moved = Math.hypot(held.r[0] - before[0], held.r[1] - before[1]);
  check(moved > 0.05 && off < 1e-9, `a finger on a touch screen drags particle 399 of the fabric (${moved.toFixed(3)} m)`,
        `moved ${moved} m, ${off} m from the finger`);
  await page.evaluate(() => springlab.page.lab.setRunning(true));
  await page.evaluate(() => springlab.resetFrames());
  await page.waitForFunction(() => springlab.page.frames.length >= 30, {timeout: 120000, polling: 'raf'});
}

// ---- measurements (figures, not verdicts) -----------------------------------------------------

async function measure(browser, base, opts) {
  const page = await browser.newPage();
  await page.setViewport({width: 1280, height: 800});
  await page.goto(`${base}/index.html?scene=task5`);
  await page.evaluate(() => springlab.ready);
  const frames = 300;
  const shape = await page.evaluate(() => {
    const lab = springlab.page.lab;
    const refused = [lab.set('rows', '100'), lab.set('cols', '100')].filter(m => m);
    lab.reset();
    return {refused, state: lab.state()};
  });
  await page.waitForFunction(() => springlab.page.frames.length >= 30, {timeout: 120000, polling: 'raf'});
  await page.evaluate(() => springlab.resetFrames());
  await page.waitForFunction(n => springlab.page.frames.length >= n, {timeout: 300000, polling: 'raf'}, frames);
  const stats = await page.evaluate(() => springlab.frameStats());
  const f = x => x.toFixed(1);
  console.log(`web: figure: 100x100 fabric (${shape.state.springs} springs, ${shape.state.integrator}, h = ${shape.state.step} s), ` +
              `${stats.frames} frames measured by the page: interval p50 ${f(stats.interval.p50)} ms, p95 ${f(stats.interval.p95)} ms, ` +
              `p99 ${f(stats.interval.p99)} ms; the page's work a frame (steps and drawing) p50 ${f(stats.work.p50)} ms, ` +
              `p95 ${f(stats.work.p95)} ms, of which stepping p50 ${f(stats.stepping.p50)} ms; ` +
              `${stats.realTime.toFixed(3)} x real time, ${stats.dropped} steps dropped`);
  await page.screenshot({path: path.join(opts.out, 'web-desktop-fabric-100x100.png')});

  // One step of the same scene: WebAssembly in this page, then springlab-run, five times each,
  // alternating; the native runner on one thread, as the page runs. The fastest run of each is
  // the one least disturbed by other programs; the medians are given too. Without the wind as
  // well: its sines are glibc's vector sines natively (four at a time with AVX2), one at a time
  // here.
  const steps = 200, rounds = 5;
  const scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'springlab-web-'));
  for (const [what, sets] of [['in the wind (task5)', []], ['without wind', ['wind.enabled=false']]]) {
    const wasm = [], native = [];
    for (let round = 0; round < rounds; ++round) {
      const timed = await page.evaluate((n, sets) => springlab.page.module.timeSteps('task5', sets, n), steps,
                                        ['rows=100', 'cols=100', ...sets].join('\n'));
      if (timed.error) { console.log(`web: figure: the WebAssembly step could not be timed: ${timed.error}`); return; }
      wasm.push(1e9 * timed.seconds / (timed.steps * timed.springs));
      const args = ['--scene', 'task5', '--set', 'rows=100', '--set', 'cols=100', '--duration', String(steps / 100)];
      for (const set of sets) args.push('--set', set);
      const run = runner(opts.runner, args, scratch, {OMP_NUM_THREADS: '1'});
      const m = /(\d+) force evaluations in ([0-9.e+-]+) s of wall time/.exec(run.stdout);
      if (!m) { console.log(`web: figure: springlab-run printed no time: ${run.stdout} ${run.stderr}`); return; }
      native.push(1e9 * Number(m[2]) / (steps * timed.springs));
    }
    const least = a => Math.min(...a);
    const median = a => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
    const list = a => a.map(x => x.toFixed(1)).join(' ');
    console.log(`web: figure: one Verlet step of the 100x100 fabric ${what}, ns a spring (${rounds} runs of ${steps} steps, ` +
                `alternating): WebAssembly ${list(wasm)}; native springlab-run, one thread, ${list(native)}; ` +
                `fastest ${least(wasm).toFixed(1)} / ${least(native).toFixed(1)} = ${(least(wasm) / least(native)).toFixed(2)} x, ` +
                `medians ${median(wasm).toFixed(1)} / ${median(native).toFixed(1)} = ${(median(wasm) / median(native)).toFixed(2)} x`);
  }
  fs.rmSync(scratch, {recursive: true, force: true});
  await page.close();
}

// ---- main -------------------------------------------------------------------------------------

async function main() {
  const opts = options();
  fs.mkdirSync(opts.out, {recursive: true});
  const server = await serve(opts.site);
  const base = `http://127.0.0.1:${server.address().port}`;
  console.log(`web: the page at ${base}/index.html, Chromium ${opts.chromium}`);
  const args = ['--no-first-run', '--disable-gpu'];
  if (process.getuid && process.getuid() === 0) args.push('--no-sandbox');  // Chromium refuses root otherwise
  const browser = await puppeteer.launch({executablePath: opts.chromium, headless: true, args});
  console.log(`web: ${await browser.version()}`);
  const scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'springlab-web-'));
  try {
    const page = await browser.newPage();
    await page.setViewport({width: 1280, height: 800});
    const errors = [];
    page.on('pageerror', error => errors.push(String(error)));
    await page.goto(`${base}/index.html?scene=task1&paused=1`);
    await page.evaluate(() => springlab.ready);
    const scenes = await page.evaluate(() => Array.from(document.getElementById('scene').options).map(o => o.value));
    check(['task1', 'task2', 'task3', 'task4', 'task5', 'task4-damped'].every(s => scenes.includes(s)),
          `the page loads the kit (${scenes.join(', ')})`, `scenes ${scenes}`);

    for (const scene of ['task1', 'task2', 'task3', 'task4', 'task5', 'task4-damped']) await runsInThePage(page, scene);

    const sines = 'the browser\'s std::sin against glibc\'s vector sine, tests/lab/portable.sh\'s bound';
    for (const [scene, duration] of [['task1', '1'], ['task2', '1'], ['task3', '1'], ['task4', '1'], ['task4-damped', '8.5']])
      await sameAsRunner(page, opts, scratch, `${scene}, its own integrator`, scene, [], duration, 0);
    await sameAsRunner(page, opts, scratch, 'task5 without wind', 'task5', ['wind.enabled=false'], '1', 0);
    await sameAsRunner(page, opts, scratch, 'task5 in the wind', 'task5', [], '1', 1e-9, sines);
    const integrators = await page.evaluate(() => springlab.page.module.integratorNames());
    const cg = 'conjugate gradients with Eigen\'s SSE2 sums natively, scalar sums here; the residual 1e-12 of each step\'s right-hand side carried over the steps (cgBound)';
    const bound = integrator => integrator === 'implicit-euler' ? cgBound : 0;
    for (const integrator of integrators)
      await sameAsRunner(page, opts, scratch, `task3 with ${integrator}`, 'task3', [`integrator=${integrator}`], '1',
                         bound(integrator), cg);
    const fabric = ['rows=24', 'cols=24', 'wind.enabled=false'];
    for (const integrator of ['verlet', 'xpbd', 'rk4', 'implicit-euler'])
      await sameAsRunner(page, opts, scratch, `a 24x24 fabric with ${integrator}`, 'task5', [...fabric, `integrator=${integrator}`],
                         '1', bound(integrator), cg);

    await dragging(page);
    await divergence(page, opts, scratch);
    await badInput(page, opts, scratch);
    check(errors.length === 0, 'no error in the page\'s console', errors.join('\n'));
    await page.close();
    await screenshots(browser, base, opts);
    if (opts.measure) await measure(browser, base, opts);
  } catch (error) {
    fail(`the browser tests stopped: ${error.stack || error}`);
  } finally {
    await browser.close();
    server.close();
    fs.rmSync(scratch, {recursive: true, force: true});
  }
  console.log(failures === 0 ? 'web: all passed' : `web: ${failures} FAILED`);
  process.exit(failures === 0 ? 0 : 1);
}

main();
