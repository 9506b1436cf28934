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

// One run drawn into `view` (a rectangle of the canvas): springs by strain, then particles.
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
  if (options.ghost) {
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
