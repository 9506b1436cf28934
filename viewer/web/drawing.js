// Drawing for the page (viewer/web/): the scene on a 2D canvas, springs coloured by their strain
// as the desktop viewer colours them (viewer/gui/scene_drawing.cpp), and the plots. Only what is
// drawn is computed here; the state comes from the kit's C++ through the binding.
'use strict';

const colours = {
  background: 'rgb(24, 26, 33)',
  particle: 'rgb(255, 196, 0)',
  pinned: 'rgb(235, 235, 245)',
  ghost: 'rgba(90, 200, 255, 0.6)',
  highlight: 'rgb(255, 60, 200)',
  compressed: [60, 120, 255],
  atRest: [150, 150, 160],
  stretched: [255, 70, 50],
};

// Strains are drawn in 2 * strainSteps + 1 colours, one canvas path each.
const strainSteps = 16;
const strainColours = (() => {
  const mix = (a, b, t) => a.map((x, i) => Math.round(x + (b[i] - x) * t));
  const out = [];
  for (let k = -strainSteps; k <= strainSteps; ++k) {
    const t = k / strainSteps;
    const c = t >= 0 ? mix(colours.atRest, colours.stretched, t) : mix(colours.atRest, colours.compressed, -t);
    out.push(`rgb(${c[0]}, ${c[1]}, ${c[2]})`);
  }
  return out;
})();

// The same colours packed as the pixels of an ImageData (bytes r, g, b, a: little-endian words).
const pack = ([r, g, b], a = 255) => ((a << 24) | (b << 16) | (g << 8) | r) >>> 0;
const strainPixels = (() => {
  const out = new Uint32Array(2 * strainSteps + 1);
  strainColours.forEach((c, k) => { out[k] = pack(c.match(/\d+/g).map(Number)); });
  return out;
})();
const ghostPixel = pack([70, 150, 200]);
const backgroundPixel = pack([24, 26, 33]);

// Above this many springs they are drawn as one-pixel lines written into an image, as the desktop
// viewer's pixel canvas does: a canvas path of 59,000 antialiased segments (the 100x100 fabric)
// took about 18 ms a frame in headless Chromium, these lines a few.
const pixelSprings = 8000;

// World (m, y up) to canvas pixels for one view: a centre and a scale, pixels a metre.
class Camera {
  constructor() { this.cx = 0; this.cy = 0; this.scale = 100; this.fitted = false; }
  // The scene as it is, with room to move: half its size around it, and below it too when it
  // hangs in gravity (`falls`), which stretches a fabric down from its pins.
  fit(positions, width, height, falls) {
    let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
    for (let i = 0; i < positions.length; i += 2) {
      const x = positions[i], y = positions[i + 1];
      if (!Number.isFinite(x) || !Number.isFinite(y)) continue;
      minX = Math.min(minX, x); maxX = Math.max(maxX, x);
      minY = Math.min(minY, y); maxY = Math.max(maxY, y);
    }
    if (!Number.isFinite(minX)) return;
    const span = Math.max(maxX - minX, maxY - minY, 0.5);
    this.scale = Math.min(width, height) / (span * (falls ? 2.0 : 1.6));
    this.cx = (minX + maxX) / 2;
    this.cy = (minY + maxY) / 2 - (falls ? 0.4 * span : 0);
    this.fitted = true;
  }
  toScreen(x, y, view) {
    return [view.x + view.width / 2 + (x - this.cx) * this.scale,
            view.y + view.height / 2 - (y - this.cy) * this.scale];
  }
  toWorld(px, py, view) {
    return [this.cx + (px - view.x - view.width / 2) / this.scale,
            this.cy - (py - view.y - view.height / 2) / this.scale];
  }
  zoom(factor, px, py, view) {
    const [wx, wy] = this.toWorld(px, py, view);
    this.scale *= factor;
    const [nx, ny] = this.toWorld(px, py, view);
    this.cx += wx - nx;
    this.cy += wy - ny;
  }
}

// Springs as one-pixel lines (Bresenham's) in `image`, the whole canvas, clipped to `view`.
function pixelSpringLines(image, camera, view, run, options) {
  const data = new Uint32Array(image.data.buffer);
  const width = image.width;
  const r = run.positions, ends = run.springs.ends, rest = run.springs.rest, family = run.springs.family;
  const x0 = view.x, y0 = view.y, x1 = view.x + view.width, y1 = view.y + view.height;
  const ox = view.x + view.width / 2 - camera.cx * camera.scale;
  const oy = view.y + view.height / 2 + camera.cy * camera.scale;
  const n = r.length / 2;
  const sx = new Int32Array(n), sy = new Int32Array(n);
  for (let i = 0; i < n; ++i) {
    const x = ox + r[2 * i] * camera.scale, y = oy - r[2 * i + 1] * camera.scale;
    // Far off the canvas (a run blowing up) is clamped: its lines are clipped anyway.
    sx[i] = Math.round(Math.max(-1e6, Math.min(1e6, Number.isFinite(x) ? x : 1e6)));
    sy[i] = Math.round(Math.max(-1e6, Math.min(1e6, Number.isFinite(y) ? y : 1e6)));
  }
  const scale = options.strainScale;
  for (let s = 0; s < rest.length; ++s) {
    if (options.hidden.has(family[s])) continue;
    const p = ends[2 * s], q = ends[2 * s + 1];
    let colour = ghostPixel;
    if (!options.ghost) {
      const dx = r[2 * p] - r[2 * q], dy = r[2 * p + 1] - r[2 * q + 1];
      const strain = (Math.sqrt(dx * dx + dy * dy) - rest[s]) / rest[s];
      const k = Math.round(Math.max(-1, Math.min(1, strain / scale)) * strainSteps);
      colour = strainPixels[Number.isFinite(k) ? k + strainSteps : 2 * strainSteps];
    }
    let x = sx[p], y = sy[p];
    const xe = sx[q], ye = sy[q];
    if ((x < x0 && xe < x0) || (x >= x1 && xe >= x1) || (y < y0 && ye < y0) || (y >= y1 && ye >= y1)) continue;
    const ax = Math.abs(xe - x), ay = -Math.abs(ye - y);
    if (ax - ay > 4000) continue;  // a line thousands of pixels long: a run that blew up
    const stepX = x < xe ? 1 : -1, stepY = y < ye ? 1 : -1;
    let error = ax + ay;
    for (;;) {
      if (x >= x0 && x < x1 && y >= y0 && y < y1) data[y * width + x] = colour;
      if (x === xe && y === ye) break;
      const e2 = 2 * error;
      if (e2 >= ay) { error += ay; x += stepX; }
      if (e2 <= ax) { error += ax; y += stepY; }
    }
  }
}

// One run drawn into `view` (a rectangle of the canvas): springs by strain (unless options.pixels
// has drawn them already), then particles.
function drawRun(ctx, camera, view, run, options) {
  const r = run.positions, ends = run.springs.ends, rest = run.springs.rest;
  const family = run.springs.family;
  const paths = [];
  const scale = options.strainScale;
  const sx = new Float64Array(r.length / 2), sy = new Float64Array(r.length / 2);
  const ox = view.x + view.width / 2 - camera.cx * camera.scale;
  const oy = view.y + view.height / 2 + camera.cy * camera.scale;
  for (let i = 0; i < sx.length; ++i) {
    sx[i] = ox + r[2 * i] * camera.scale;
    sy[i] = oy - r[2 * i + 1] * camera.scale;
  }
  if (options.pixels) {
    // drawn by pixelSpringLines
  } else if (options.ghost) {
    const path = new Path2D();
    for (let s = 0; s < rest.length; ++s) {
      if (options.hidden.has(family[s])) continue;
      const p = ends[2 * s], q = ends[2 * s + 1];
      path.moveTo(sx[p], sy[p]);
      path.lineTo(sx[q], sy[q]);
    }
    ctx.strokeStyle = colours.ghost;
    ctx.lineWidth = 1;
    ctx.stroke(path);
  } else {
    for (let k = 0; k <= 2 * strainSteps; ++k) paths.push(null);
    for (let s = 0; s < rest.length; ++s) {
      if (options.hidden.has(family[s])) continue;
      const p = ends[2 * s], q = ends[2 * s + 1];
      const dx = r[2 * p] - r[2 * q], dy = r[2 * p + 1] - r[2 * q + 1];
      const strain = (Math.sqrt(dx * dx + dy * dy) - rest[s]) / rest[s];
      let k = Math.round(Math.max(-1, Math.min(1, strain / scale)) * strainSteps);
      if (!Number.isFinite(k)) k = strainSteps;
      const path = paths[k + strainSteps] || (paths[k + strainSteps] = new Path2D());
      path.moveTo(sx[p], sy[p]);
      path.lineTo(sx[q], sy[q]);
    }
    ctx.lineWidth = rest.length > 20000 ? 1 : 2;
    paths.forEach((path, k) => {
      if (!path) return;
      ctx.strokeStyle = strainColours[k];
      ctx.stroke(path);
    });
  }
  const n = sx.length;
  const radius = Math.max(1.5, Math.min(8, 0.12 * (options.spacing || 1) * camera.scale));
  const dots = new Path2D(), pins = new Path2D();
  for (let i = 0; i < n; ++i) {
    if (run.pinned && run.pinned[i]) {
      const a = radius + 1.5;
      pins.rect(sx[i] - a, sy[i] - a, 2 * a, 2 * a);
    } else if (n <= 2500) {
      dots.moveTo(sx[i] + radius, sy[i]);
      dots.arc(sx[i], sy[i], radius, 0, 2 * Math.PI);
    }
  }
  ctx.fillStyle = options.ghost ? colours.ghost : colours.particle;
  ctx.fill(dots);
  ctx.fillStyle = options.ghost ? colours.ghost : colours.pinned;
  ctx.fill(pins);
  for (const i of options.rings || []) {
    if (i < 0 || i >= n) continue;
    ctx.strokeStyle = colours.highlight;
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.arc(sx[i], sy[i], radius + 5, 0, 2 * Math.PI);
    ctx.stroke();
  }
}

// The particle nearest to a point of the canvas, within `reach` pixels; -1 for none.
function nearestParticle(camera, view, positions, px, py, reach) {
  let best = -1, bestDistance = reach * reach;
  for (let i = 0; i < positions.length / 2; ++i) {
    const [x, y] = camera.toScreen(positions[2 * i], positions[2 * i + 1], view);
    const d = (x - px) * (x - px) + (y - py) * (y - py);
    if (d <= bestDistance) { best = i; bestDistance = d; }
  }
  return best;
}

// A plot of series over time: [{values, colour}], scaled to fit, with its range written in.
function drawPlot(canvas, time, series) {
  const ctx = canvas.getContext('2d');
  const w = canvas.width, h = canvas.height;
  ctx.clearRect(0, 0, w, h);
  if (time.length < 2) return;
  let low = Infinity, high = -Infinity;
  for (const s of series)
    for (const v of s.values) if (Number.isFinite(v)) { low = Math.min(low, v); high = Math.max(high, v); }
  if (!Number.isFinite(low)) return;
  if (high - low < 1e-9 * Math.max(1, Math.abs(high))) { high += 0.5; low -= 0.5; }
  const t0 = time[0], t1 = time[time.length - 1];
  const pad = 4 * (window.devicePixelRatio || 1);
  const x = t => pad + (w - 2 * pad) * (t - t0) / Math.max(t1 - t0, 1e-9);
  const y = v => h - pad - (h - 2 * pad) * (v - low) / (high - low);
  if (low < 0 && high > 0) {
    ctx.strokeStyle = 'rgb(60, 64, 78)';
    ctx.beginPath(); ctx.moveTo(0, y(0)); ctx.lineTo(w, y(0)); ctx.stroke();
  }
  ctx.lineWidth = window.devicePixelRatio || 1;
  for (const s of series) {
    ctx.strokeStyle = s.colour;
    ctx.beginPath();
    for (let i = 0; i < time.length; ++i) {
      const v = Math.max(low, Math.min(high, s.values[i]));
      if (i === 0) ctx.moveTo(x(time[i]), y(v)); else ctx.lineTo(x(time[i]), y(v));
    }
    ctx.stroke();
  }
  ctx.fillStyle = 'rgb(150, 155, 170)';
  ctx.font = `${11 * (window.devicePixelRatio || 1)}px system-ui, sans-serif`;
  ctx.fillText(high.toPrecision(4), pad, pad + 10 * (window.devicePixelRatio || 1));
  ctx.fillText(low.toPrecision(4), pad, h - pad);
  ctx.fillText(`t = ${t1.toFixed(2)} s`, w - 80 * (window.devicePixelRatio || 1), h - pad);
}
