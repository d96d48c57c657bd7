// The plan viewer (written into the page by `earc-plan view`; sources in
// tools/viewer/, embedded by tools/viewer/embed.sh). It animates the
// embedded solution on a canvas and, with a trace, shows conflicts and
// subproblems. World y points up, the canvas's down: y is flipped.
//
// Speed with 128 robots x 5,000 steps comes from doing per frame only what
// changes: the workspace, obstacles, goals and faint full paths sit in an
// offscreen layer drawn once per resize; trails are cut from polylines
// decimated once at load (a few vertices per robot and frame); frames are
// drawn only when something changed.
'use strict';
(function () {
  // How each subproblem was solved (the trace's "solved_by"), by colour.
  const OUTCOME_COLOURS = {
    database: '#2e7d32', repair: '#1565c0', decoupled: '#7b1fa2',
    coupled: '#ef6c00', merged: '#8d6e63', failed: '#c62828',
  };
  const OTHER_OUTCOME_COLOUR = '#546e7a';
  const OUTCOME_NOTES = {
    database: 'stored experience',
    repair: 'stored experience, repaired',
    decoupled: 'prioritized, in the window',
    coupled: 'composite RRT-Connect',
    merged: 'left to merge a robot',
    failed: 'no solver succeeded',
  };
  const SPEEDS = [0.5, 1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000];  // steps per second
  const PLAYBACK_SECONDS = 20;  // default speed: the whole plan in about this long
  const TRAIL_CHUNKS = 4;       // a trail fades in this many bands
  const MARK_RADIUS_PX = 7;
  const CLICK_SLACK_PX = 5;
  const LABEL_PX = 11;
  const MARGIN_PX = 14;

  const data = JSON.parse(document.getElementById('earc-data').textContent);
  const sc = data.scenario;
  const sol = data.solution;
  const trace = data.trace;
  const robots = sc.robots;
  const ws = { x0: sc.workspace.min[0], y0: sc.workspace.min[1], x1: sc.workspace.max[0], y1: sc.workspace.max[1] };
  const makespan = sol.makespan;

  // ---- Kinematics ---------------------------------------------------------

  function isMobile(r) { return r.type === 'mobile'; }
  function dimOf(r) { return isMobile(r) ? 3 : r.links.length; }
  function wrapAngle(a) {
    let r = (a + Math.PI) % (2 * Math.PI);
    if (r < 0) r += 2 * Math.PI;
    return r - Math.PI;
  }

  // The page gets each path as integers in units of `quantum`: the first
  // state, then differences. Running sums of integers are exact.
  function decodePath(ints, d, quantum) {
    const per = Math.round(1 / quantum);
    const out = new Float64Array(ints.length);
    const sum = new Array(d).fill(0);
    for (let k = 0; k < ints.length; ++k) {
      const j = k % d;
      sum[j] += ints[k];
      out[k] = sum[j] / per;
    }
    return out;
  }
  const paths = robots.map(function (r, i) {
    return sol.paths.length ? decodePath(sol.paths[i], dimOf(r), sol.quantum) : null;
  });

  // Configuration of robot i at (fractional) time s: between steps, joints
  // and positions linearly, headings along the shortest arc, as the
  // contract checks midpoints. Past its last state a robot waits there.
  function configAt(i, s, out) {
    const r = robots[i];
    const p = paths[i];
    const d = out.length;
    if (!p) {
      for (let j = 0; j < d; ++j) out[j] = r.start[j];
      return out;
    }
    const n = p.length / d;
    let t = Math.floor(s);
    let f = s - t;
    if (t >= n - 1) { t = n - 1; f = 0; }
    if (t < 0) { t = 0; f = 0; }
    const a = t * d;
    for (let j = 0; j < d; ++j) out[j] = p[a + j];
    if (f > 0) {
      for (let j = 0; j < d; ++j) out[j] += (p[a + d + j] - p[a + j]) * f;
      if (isMobile(r)) out[2] = p[a + 2] + wrapAngle(p[a + d + 2] - p[a + 2]) * f;
    }
    return out;
  }

  // Joint positions of an arm, the base first (n + 1 points, flat x, y).
  function armPoints(r, q, out) {
    let x = r.base[0], y = r.base[1], a = r.base[2];
    out[0] = x; out[1] = y;
    for (let k = 0; k < r.links.length; ++k) {
      a += q[k];
      x += r.links[k] * Math.cos(a);
      y += r.links[k] * Math.sin(a);
      out[2 * k + 2] = x; out[2 * k + 3] = y;
    }
    return out;
  }

  // ---- Precomputed trails -------------------------------------------------

  // The point a trail follows: a mobile robot's centre, an arm's tip.
  const tracks = robots.map(function (r, i) {
    const p = paths[i];
    if (!p) return null;
    const d = dimOf(r);
    const n = p.length / d;
    const pts = new Float64Array(2 * n);
    const joints = new Float64Array(2 * (d + 1));
    for (let t = 0; t < n; ++t) {
      if (isMobile(r)) {
        pts[2 * t] = p[t * d]; pts[2 * t + 1] = p[t * d + 1];
      } else {
        armPoints(r, p.subarray(t * d, t * d + d), joints);
        pts[2 * t] = joints[2 * d]; pts[2 * t + 1] = joints[2 * d + 1];
      }
    }
    return { pts: pts, n: n, keep: null };
  });

  // Douglas-Peucker: the steps whose points a polyline needs so that no
  // dropped point is farther than tol from it.
  function decimate(pts, n, tol) {
    const keep = new Uint8Array(n);
    keep[0] = 1; keep[n - 1] = 1;
    const stack = [0, n - 1];
    while (stack.length) {
      const b = stack.pop(), a = stack.pop();
      const ax = pts[2 * a], ay = pts[2 * a + 1];
      const dx = pts[2 * b] - ax, dy = pts[2 * b + 1] - ay;
      const dd = dx * dx + dy * dy;
      let worst = -1, at = -1;
      for (let k = a + 1; k < b; ++k) {
        const px = pts[2 * k] - ax, py = pts[2 * k + 1] - ay;
        let u = dd > 0 ? (px * dx + py * dy) / dd : 0;
        u = u < 0 ? 0 : u > 1 ? 1 : u;
        const ex = px - u * dx, ey = py - u * dy;
        const e = ex * ex + ey * ey;
        if (e > worst) { worst = e; at = k; }
      }
      if (at >= 0 && worst > tol * tol) {
        keep[at] = 1;
        stack.push(a, at, at, b);
      }
    }
    const steps = [];
    for (let k = 0; k < n; ++k) if (keep[k]) steps.push(k);
    return Uint32Array.from(steps);
  }
  // A quarter pixel on a 2,000-pixel view: invisible, and few vertices.
  const DECIMATE_TOL = Math.max(ws.x1 - ws.x0, ws.y1 - ws.y0) / 8000;
  for (const tr of tracks) if (tr && tr.n > 0) tr.keep = decimate(tr.pts, tr.n, DECIMATE_TOL);
  const TRAIL_STEPS = Math.max(10, Math.min(400, makespan / 8));

  // ---- Trace --------------------------------------------------------------

  const conflicts = trace ? trace.conflicts.slice() : [];
  const subproblems = trace ? trace.subproblems.slice() : [];
  const subsOf = new Map();  // conflict id -> its subproblems, in trace order
  for (const s of subproblems) {
    if (!subsOf.has(s.conflict)) subsOf.set(s.conflict, []);
    subsOf.get(s.conflict).push(s);
  }
  function outcomeOf(c) {
    const list = subsOf.get(c.id);
    return list && list.length ? list[list.length - 1].solved_by : 'unresolved';
  }
  function outcomeColour(o) { return OUTCOME_COLOURS[o] || OTHER_OUTCOME_COLOUR; }
  // A mark shows for MARK_SPAN steps either side of its step, fading.
  const MARK_SPAN = Math.max(4, makespan / 60);

  // ---- Page elements ------------------------------------------------------

  const byId = document.getElementById.bind(document);
  const canvas = byId('view'), stage = byId('stage'), details = byId('details');
  const ctx = canvas.getContext('2d');
  const playButton = byId('play'), slider = byId('time'), counter = byId('counter'), speedSelect = byId('speed');
  const showNames = byId('show-names'), showTrails = byId('show-trails'), showTrace = byId('show-trace');
  const bg = document.createElement('canvas');
  const bgCtx = bg.getContext('2d');

  function el(tag, text, cls) {
    const e = document.createElement(tag);
    if (text !== undefined) e.textContent = text;
    if (cls) e.className = cls;
    return e;
  }
  // The list of src/render/svg.cpp's robotColour: the same robot has the
  // same colour in the viewer and in earc-plan render.
  const PALETTE = ['#d62728', '#0000ff', '#00b400', '#ff00c3', '#0069e1', '#c39600', '#0fb487', '#961e5a',
    '#3c5a00', '#00a5e1', '#7800b4', '#783c0f', '#d287e1', '#f08787', '#ff0078', '#ff7800', '#5a4b87', '#e100ff',
    '#87a500', '#b4965a'];
  function robotColour(i) { return PALETTE[i % PALETTE.length]; }
  function fmt(v, digits) { return Number(v.toFixed(digits === undefined ? 3 : digits)).toString(); }
  function stepText(t) {
    return t % 1 ? fmt(t, 1) + ' (midpoint of ' + Math.floor(t) + ' and ' + (Math.floor(t) + 1) + ')' : String(t);
  }
  function names(list) { return list.map(function (i) { return robots[i].name; }).join(', '); }

  // ---- State --------------------------------------------------------------

  // While playing, time follows the clock from where playback (re)started,
  // so step() is right between frames and however rarely frames come.
  let time = 0;
  let playing = false;
  let playFromTime = 0, playFromClock = 0;
  let dirty = true;
  let frames = 0;
  let selected = null;  // {kind: 'conflict'|'subproblem', item}
  let speedIndex = 0;
  while (speedIndex + 1 < SPEEDS.length && SPEEDS[speedIndex] < makespan / PLAYBACK_SECONDS) ++speedIndex;

  // ---- View transform -----------------------------------------------------

  let dpr = 1, scale = 1, ox = 0, oy = 0;
  function px(x) { return ox + (x - ws.x0) * scale; }
  function py(y) { return oy + (ws.y1 - y) * scale; }

  function layout() {
    const rect = stage.getBoundingClientRect();
    dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(rect.width * dpr)), h = Math.max(1, Math.round(rect.height * dpr));
    canvas.width = bg.width = w;
    canvas.height = bg.height = h;
    const m = MARGIN_PX * dpr;
    const ww = ws.x1 - ws.x0, wh = ws.y1 - ws.y0;
    scale = Math.max(1e-9, Math.min((w - 2 * m) / ww, (h - 2 * m) / wh));
    ox = (w - ww * scale) / 2;
    oy = (h - wh * scale) / 2;
    drawBackground();
    // Resizing clears the canvas: redraw now rather than on the next
    // animation frame, so no frame (or self-test reading it) sees it blank.
    draw();
  }

  // ---- Drawing ------------------------------------------------------------

  function bodyPath(c, r, q) {
    c.beginPath();
    if (r.shape.type === 'disc') {
      c.arc(px(q[0]), py(q[1]), r.shape.radius * scale, 0, 2 * Math.PI);
    } else {
      const hl = r.shape.size[0] / 2, hw = r.shape.size[1] / 2;
      const cs = Math.cos(q[2]), sn = Math.sin(q[2]);
      const corners = [[hl, hw], [-hl, hw], [-hl, -hw], [hl, -hw]];
      corners.forEach(function (k, n) {
        const x = px(q[0] + k[0] * cs - k[1] * sn), y = py(q[1] + k[0] * sn + k[1] * cs);
        if (n) c.lineTo(x, y); else c.moveTo(x, y);
      });
      c.closePath();
    }
  }
  function reach(r) { return r.shape.type === 'disc' ? r.shape.radius : r.shape.size[0] / 2; }

  const scratchJoints = robots.map(function (r) { return isMobile(r) ? null : new Float64Array(2 * (r.links.length + 1)); });
  const scratchQ = robots.map(function (r) { return new Float64Array(dimOf(r)); });

  // An arm: every link a capsule (a thick line with round caps), outlined.
  function drawArm(c, r, pts, colour, goal) {
    const n = r.links.length;
    const w = 2 * r.link_radius * scale;
    c.lineCap = 'round';
    c.lineJoin = 'round';
    const links = function () {
      c.beginPath();
      c.moveTo(px(pts[0]), py(pts[1]));
      for (let k = 1; k <= n; ++k) c.lineTo(px(pts[2 * k]), py(pts[2 * k + 1]));
    };
    if (goal) {
      c.setLineDash([4 * dpr, 3 * dpr]);
      c.strokeStyle = colour;
      c.lineWidth = 1.2 * dpr;
      links();
      c.stroke();
      c.setLineDash([]);
      return;
    }
    links();
    c.strokeStyle = '#222';
    c.lineWidth = w + 2 * dpr;
    c.stroke();
    // Each link on its own, so that a folded arm shows every capsule.
    c.strokeStyle = colour;
    c.lineWidth = w;
    for (let k = 0; k < n; ++k) {
      c.beginPath();
      c.moveTo(px(pts[2 * k]), py(pts[2 * k + 1]));
      c.lineTo(px(pts[2 * k + 2]), py(pts[2 * k + 3]));
      c.stroke();
    }
    c.fillStyle = '#222';
    const jr = Math.max(1.5 * dpr, 0.45 * w);
    for (let k = 1; k <= n; ++k) {
      c.beginPath();
      c.arc(px(pts[2 * k]), py(pts[2 * k + 1]), k === n ? jr * 0.7 : jr, 0, 2 * Math.PI);
      c.fill();
    }
    const b = Math.max(4 * dpr, 1.6 * w);
    c.fillRect(px(pts[0]) - b / 2, py(pts[1]) - b / 2, b, b);
  }

  function drawMobile(c, r, q, colour, goal) {
    bodyPath(c, r, q);
    if (goal) {
      c.setLineDash([4 * dpr, 3 * dpr]);
      c.strokeStyle = colour;
      c.lineWidth = 1.2 * dpr;
      c.stroke();
      c.setLineDash([]);
      return;
    }
    c.fillStyle = colour;
    c.fill();
    c.strokeStyle = '#222';
    c.lineWidth = 1 * dpr;
    c.stroke();
    const l = reach(r);
    c.beginPath();
    c.moveTo(px(q[0]), py(q[1]));
    c.lineTo(px(q[0] + l * Math.cos(q[2])), py(q[1] + l * Math.sin(q[2])));
    c.lineWidth = 1.5 * dpr;
    c.stroke();
  }

  function drawBackground() {
    const c = bgCtx;
    c.setTransform(1, 0, 0, 1, 0, 0);
    c.fillStyle = '#eef0f2';
    c.fillRect(0, 0, bg.width, bg.height);
    c.fillStyle = '#fcfcfc';
    c.fillRect(px(ws.x0), py(ws.y1), (ws.x1 - ws.x0) * scale, (ws.y1 - ws.y0) * scale);
    // A light grid at a round spacing at least 24 px apart.
    let g = 1e-3;
    for (let k = 0; g * scale < 24 * dpr; ++k) g = [1, 2, 5][k % 3] * Math.pow(10, Math.floor(k / 3) - 3);
    c.strokeStyle = '#e6e8eb';
    c.lineWidth = 1;
    c.beginPath();
    for (let x = Math.ceil(ws.x0 / g) * g; x <= ws.x1; x += g) { c.moveTo(px(x), py(ws.y0)); c.lineTo(px(x), py(ws.y1)); }
    for (let y = Math.ceil(ws.y0 / g) * g; y <= ws.y1; y += g) { c.moveTo(px(ws.x0), py(y)); c.lineTo(px(ws.x1), py(y)); }
    c.stroke();
    c.strokeStyle = '#333';
    c.lineWidth = 1.5 * dpr;
    c.strokeRect(px(ws.x0), py(ws.y1), (ws.x1 - ws.x0) * scale, (ws.y1 - ws.y0) * scale);
    c.fillStyle = '#6b6f75';
    for (const o of sc.obstacles) {
      c.beginPath();
      if (o.type === 'circle') {
        c.arc(px(o.center[0]), py(o.center[1]), o.radius * scale, 0, 2 * Math.PI);
      } else {
        const hx = o.size[0] / 2, hy = o.size[1] / 2, a = o.angle || 0;
        const cs = Math.cos(a), sn = Math.sin(a);
        [[hx, hy], [-hx, hy], [-hx, -hy], [hx, -hy]].forEach(function (k, n) {
          const x = px(o.center[0] + k[0] * cs - k[1] * sn), y = py(o.center[1] + k[0] * sn + k[1] * cs);
          if (n) c.lineTo(x, y); else c.moveTo(x, y);
        });
        c.closePath();
      }
      c.fill();
    }
    robots.forEach(function (r, i) {
      const colour = robotColour(i);
      if (isMobile(r)) drawMobile(c, r, r.goal, colour, true);
      else drawArm(c, r, armPoints(r, r.goal, scratchJoints[i]), colour, true);
    });
    if (showTrails.checked) {
      c.globalAlpha = 0.22;
      c.lineWidth = 1 * dpr;
      c.lineJoin = 'round';
      tracks.forEach(function (tr, i) {
        if (!tr) return;
        c.strokeStyle = robotColour(i);
        c.beginPath();
        for (let k = 0; k < tr.keep.length; ++k) {
          const t = tr.keep[k];
          if (k) c.lineTo(px(tr.pts[2 * t]), py(tr.pts[2 * t + 1]));
          else c.moveTo(px(tr.pts[2 * t]), py(tr.pts[2 * t + 1]));
        }
        c.stroke();
      });
      c.globalAlpha = 1;
    }
  }

  // Trail point at fractional time s (linear between steps).
  function trackPoint(tr, s) {
    const t = Math.min(Math.floor(s), tr.n - 1);
    const f = t < tr.n - 1 ? s - t : 0;
    const x = tr.pts[2 * t] + (f ? (tr.pts[2 * t + 2] - tr.pts[2 * t]) * f : 0);
    const y = tr.pts[2 * t + 1] + (f ? (tr.pts[2 * t + 3] - tr.pts[2 * t + 1]) * f : 0);
    return [x, y];
  }
  // First index of keep with a step > s.
  function upper(keep, s) {
    let lo = 0, hi = keep.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (keep[mid] <= s) lo = mid + 1; else hi = mid;
    }
    return lo;
  }
  function drawTrail(tr, colour) {
    const from = Math.max(0, time - TRAIL_STEPS);
    if (time <= from) return;
    ctx.strokeStyle = colour;
    ctx.lineWidth = 2.5 * dpr;
    ctx.lineJoin = 'round';
    ctx.lineCap = 'round';
    for (let b = 0; b < TRAIL_CHUNKS; ++b) {
      const s0 = from + (time - from) * b / TRAIL_CHUNKS, s1 = from + (time - from) * (b + 1) / TRAIL_CHUNKS;
      ctx.globalAlpha = 0.12 + 0.68 * (b + 1) / TRAIL_CHUNKS;
      ctx.beginPath();
      let p = trackPoint(tr, s0);
      ctx.moveTo(px(p[0]), py(p[1]));
      for (let k = upper(tr.keep, s0); k < tr.keep.length && tr.keep[k] < s1; ++k) {
        const t = tr.keep[k];
        ctx.lineTo(px(tr.pts[2 * t]), py(tr.pts[2 * t + 1]));
      }
      p = trackPoint(tr, s1);
      ctx.lineTo(px(p[0]), py(p[1]));
      ctx.stroke();
    }
    ctx.globalAlpha = 1;
  }

  function activeSubproblems() {
    return subproblems.filter(function (s) { return s.window[0] <= time && time <= s.window[1]; });
  }
  function visibleConflicts() {
    return conflicts.filter(function (c) { return Math.abs(c.t - time) <= MARK_SPAN; });
  }

  // Region labels placed this frame, so that regions sharing a corner do
  // not print their labels on top of each other.
  let regionLabels = [];
  function drawRegion(s, strong) {
    const colour = outcomeColour(s.solved_by);
    const x = px(s.region[0][0]), y = py(s.region[1][1]);
    const w = (s.region[1][0] - s.region[0][0]) * scale, h = (s.region[1][1] - s.region[0][1]) * scale;
    ctx.globalAlpha = 0.08;
    ctx.fillStyle = colour;
    ctx.fillRect(x, y, w, h);
    ctx.globalAlpha = 1;
    ctx.setLineDash([6 * dpr, 4 * dpr]);
    ctx.strokeStyle = strong ? '#111' : colour;
    ctx.lineWidth = (strong ? 3 : 2) * dpr;
    ctx.strokeRect(x, y, w, h);
    ctx.setLineDash([]);
    ctx.font = (LABEL_PX - 1) * dpr + 'px sans-serif';
    ctx.fillStyle = colour;
    ctx.textBaseline = 'top';
    const text = '#' + s.id + ' ' + s.solved_by, tw = ctx.measureText(text).width, lh = LABEL_PX * dpr;
    let ly = y + 3 * dpr;
    const clash = function (b) { return b.x < x + 3 * dpr + tw && x + 3 * dpr < b.x + b.w && Math.abs(b.y - ly) < lh; };
    while (regionLabels.some(clash)) ly += lh;
    regionLabels.push({ x: x + 3 * dpr, y: ly, w: tw });
    ctx.lineWidth = 3 * dpr;
    ctx.strokeStyle = 'rgba(255,255,255,0.8)';
    ctx.strokeText(text, x + 3 * dpr, ly);
    ctx.fillText(text, x + 3 * dpr, ly);
  }

  function drawMark(c, strong) {
    const x = px(c.place[0]), y = py(c.place[1]);
    const fade = Math.min(1, Math.abs(c.t - time) / MARK_SPAN);
    const r = MARK_RADIUS_PX * dpr;
    ctx.globalAlpha = strong ? 1 : 1 - 0.7 * fade;
    ctx.lineWidth = 4.5 * dpr;
    ctx.strokeStyle = '#fff';
    ctx.beginPath();
    ctx.arc(x, y, r, 0, 2 * Math.PI);
    ctx.stroke();
    ctx.lineWidth = (strong ? 3.5 : 2.5) * dpr;
    ctx.strokeStyle = strong ? '#111' : outcomeColour(outcomeOf(c));
    ctx.stroke();
    ctx.beginPath();
    const k = r * 0.55;
    ctx.moveTo(x - k, y - k); ctx.lineTo(x + k, y + k);
    ctx.moveTo(x - k, y + k); ctx.lineTo(x + k, y - k);
    ctx.lineWidth = 2 * dpr;
    ctx.stroke();
    ctx.globalAlpha = 1;
  }

  function draw() {
    ++frames;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.drawImage(bg, 0, 0);
    const traceOn = trace && showTrace.checked;
    if (traceOn) {
      regionLabels = [];
      for (const s of activeSubproblems()) drawRegion(s, false);
      if (selected && selected.kind === 'subproblem') drawRegion(selected.item, true);
    }
    if (showTrails.checked)
      tracks.forEach(function (tr, i) { if (tr) drawTrail(tr, robotColour(i)); });
    const labels = [];
    robots.forEach(function (r, i) {
      const q = configAt(i, time, scratchQ[i]);
      const colour = robotColour(i);
      if (isMobile(r)) {
        drawMobile(ctx, r, q, colour, false);
        labels.push([r.name, px(q[0]), py(q[1]) - reach(r) * scale - 3 * dpr]);
      } else {
        const pts = armPoints(r, q, scratchJoints[i]);
        drawArm(ctx, r, pts, colour, false);
        labels.push([r.name, px(pts[0]), py(pts[1]) + Math.max(6 * dpr, 1.5 * r.link_radius * scale) + LABEL_PX * dpr]);
      }
    });
    if (showNames.checked) {
      ctx.font = 'bold ' + LABEL_PX * dpr + 'px sans-serif';
      ctx.textAlign = 'center';
      ctx.textBaseline = 'alphabetic';
      ctx.lineWidth = 3 * dpr;
      ctx.strokeStyle = 'rgba(255,255,255,0.85)';
      ctx.fillStyle = '#111';
      for (const l of labels) { ctx.strokeText(l[0], l[1], l[2]); ctx.fillText(l[0], l[1], l[2]); }
      ctx.textAlign = 'start';
    }
    if (traceOn) {
      for (const c of visibleConflicts()) drawMark(c, false);
      if (selected && selected.kind === 'conflict') drawMark(selected.item, true);
    }
  }

  // ---- Controls -----------------------------------------------------------

  function updateControls() {
    if (document.activeElement !== slider || playing) slider.value = String(Math.floor(time));
    counter.textContent = 'step ' + fmt(time, 1) + ' / ' + makespan;
    playButton.innerHTML = playing ? '&#10074;&#10074;' : '&#9654;';
    speedSelect.value = String(speedIndex);
  }
  function now() {
    if (playing) {
      time = Math.min(makespan, playFromTime + (performance.now() - playFromClock) / 1000 * SPEEDS[speedIndex]);
      if (time >= makespan) playing = false;
    }
    return time;
  }
  function restartClock() {
    playFromTime = time;
    playFromClock = performance.now();
  }
  function setStep(t) {
    t = Number(t);
    if (!isFinite(t)) throw new Error('setStep: not a number: ' + t);
    time = Math.min(Math.max(t, 0), makespan);
    restartClock();
    dirty = true;
  }
  function play() {
    if (makespan <= 0) return;
    if (now() >= makespan) time = 0;
    playing = true;
    restartClock();
    dirty = true;
  }
  function pause() {
    now();
    playing = false;
    dirty = true;
  }
  function stepBy(k) {
    pause();
    setStep(k > 0 ? Math.floor(time) + k : Math.ceil(time) + k);
  }
  function setSpeed(i) {
    now();
    speedIndex = Math.min(Math.max(i, 0), SPEEDS.length - 1);
    restartClock();
    dirty = true;
  }

  function tick() {
    if (playing) {
      now();
      dirty = true;
    }
    if (dirty) {
      dirty = false;
      draw();
      updateControls();
    }
    requestAnimationFrame(tick);
  }

  SPEEDS.forEach(function (s, i) {
    const o = el('option', s + ' steps/s');
    o.value = String(i);
    speedSelect.appendChild(o);
  });
  speedSelect.addEventListener('change', function () { setSpeed(Number(speedSelect.value)); });
  playButton.addEventListener('click', function () { if (playing) pause(); else play(); });
  slider.max = String(makespan);
  slider.addEventListener('input', function () { pause(); setStep(Number(slider.value)); });
  [showNames, showTrace].forEach(function (b) { b.addEventListener('change', function () { dirty = true; }); });
  showTrails.addEventListener('change', function () { drawBackground(); dirty = true; });

  document.addEventListener('keydown', function (e) {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    let handled = true;
    switch (e.key) {
      case ' ': if (playing) pause(); else play(); break;
      case 'ArrowRight': stepBy(e.shiftKey ? 10 : 1); break;
      case 'ArrowLeft': stepBy(e.shiftKey ? -10 : -1); break;
      case '+': case '=': setSpeed(speedIndex + 1); break;
      case '-': case '_': setSpeed(speedIndex - 1); break;
      case 'Home': pause(); setStep(0); break;
      case 'End': pause(); setStep(makespan); break;
      default: handled = false;
    }
    if (handled) e.preventDefault();  // no scrolling, no second step from a focused slider
  }, true);
  // A focused button would also "click" on the space's keyup.
  document.addEventListener('keyup', function (e) { if (e.key === ' ') e.preventDefault(); }, true);

  // ---- Selection and details ----------------------------------------------

  function table(rows) {
    const t = el('table');
    for (const row of rows) {
      if (row[1] === undefined || row[1] === null) continue;
      const tr = el('tr');
      tr.appendChild(el('th', row[0]));
      const td = el('td');
      if (row[1] instanceof Node) td.appendChild(row[1]); else td.textContent = String(row[1]);
      tr.appendChild(td);
      t.appendChild(tr);
    }
    return t;
  }
  function attemptsList(s) {
    if (!s.attempts.length) return 'none';
    const box = el('span');
    s.attempts.forEach(function (a, k) {
      if (k) box.appendChild(document.createTextNode(', '));
      const item = el('span', a.solver + ' ' + (a.ok ? 'ok' : 'failed') + ' ' + fmt(a.time_s * 1000, 2) + ' ms',
                      a.ok ? 'ok' : 'bad');
      if (a.detail) item.title = a.detail;  // why a solver failed, on hover
      box.appendChild(item);
    });
    return box;
  }
  function subproblemBlock(s, strong) {
    const box = el('div', undefined, 'sub');
    const h = el('div');
    h.appendChild(el('b', 'Subproblem ' + s.id + ': '));
    const o = el('span', s.solved_by);
    o.style.color = outcomeColour(s.solved_by);
    o.style.fontWeight = 'bold';
    h.appendChild(o);
    if (strong) h.appendChild(el('span', '  (selected)', 'hint'));
    box.appendChild(h);
    box.appendChild(table([
      ['robots', names(s.robots)],
      ['window', 'steps ' + fmt(s.window[0], 1) + ' to ' + fmt(s.window[1], 1)],
      ['region', '(' + fmt(s.region[0][0]) + ', ' + fmt(s.region[0][1]) + ') to (' +
                 fmt(s.region[1][0]) + ', ' + fmt(s.region[1][1]) + ')'],
      ['expansions', s.expansions],
      ['merged', s.merged ? s.merged + ' robot(s)' : 'none'],
      ['merge cap', s.merge_cap === undefined ? undefined
        : s.merge_cap + ' robots (raised: the conflict kept coming back)'],
      ['others', s.ignore_others ? 'ignored: planned as if alone' : undefined],
      ['db entry', s.entry],
      ['length', s.length === undefined ? undefined : s.length + ' steps'],
      ['attempts', attemptsList(s)],
    ]));
    return box;
  }
  function goButton(t) {
    const b = el('button', 'go to step ' + fmt(t, 1));
    b.type = 'button';
    b.addEventListener('click', function () { pause(); setStep(t); b.blur(); });
    return b;
  }
  function showDetails() {
    details.textContent = '';
    if (!selected) {
      details.appendChild(el('p', 'Click a conflict mark or a subproblem region for its details.', 'hint'));
      return;
    }
    const c = selected.kind === 'conflict' ? selected.item
      : conflicts.find(function (k) { return k.id === selected.item.conflict; });
    if (c) {
      details.appendChild(el('h2', 'Conflict ' + c.id));
      details.appendChild(table([
        ['robots', names(c.robots)],
        ['found at step', stepText(c.t)],
        ['place', '(' + fmt(c.place[0]) + ', ' + fmt(c.place[1]) + ')'],
        ['found after', c.at_s === undefined ? undefined : fmt(c.at_s, 4) + ' s of planning'],
        ['outcome', outcomeOf(c)],
      ]));
      details.appendChild(goButton(c.t));
    }
    const subs = c ? subsOf.get(c.id) || [] : [selected.item];
    for (const s of subs) details.appendChild(subproblemBlock(s, selected.item === s));
    if (selected.kind === 'subproblem') details.appendChild(goButton(selected.item.window[0]));
  }
  function select(kind, item) {
    selected = item ? { kind: kind, item: item } : null;
    showDetails();
    dirty = true;
  }

  function toClient(p) {
    const rect = canvas.getBoundingClientRect();
    return { x: rect.left + px(p[0]) / dpr, y: rect.top + py(p[1]) / dpr };
  }
  function hit(e) {
    if (!trace || !showTrace.checked) return null;
    const rect = canvas.getBoundingClientRect();
    const x = (e.clientX - rect.left) * dpr, y = (e.clientY - rect.top) * dpr;
    let best = null, bestD = (MARK_RADIUS_PX + CLICK_SLACK_PX) * dpr;
    for (const c of visibleConflicts()) {
      const d = Math.hypot(px(c.place[0]) - x, py(c.place[1]) - y);
      if (d <= bestD) { best = c; bestD = d; }
    }
    if (best) return ['conflict', best];
    const wx = ws.x0 + (x - ox) / scale, wy = ws.y1 - (y - oy) / scale;
    let region = null, area = Infinity;
    for (const s of activeSubproblems()) {
      const a = (s.region[1][0] - s.region[0][0]) * (s.region[1][1] - s.region[0][1]);
      if (wx >= s.region[0][0] && wx <= s.region[1][0] && wy >= s.region[0][1] && wy <= s.region[1][1] && a < area) {
        region = s; area = a;
      }
    }
    return region ? ['subproblem', region] : null;
  }
  canvas.addEventListener('click', function (e) {
    const h = hit(e);
    select(h ? h[0] : null, h ? h[1] : null);
  });
  canvas.addEventListener('mousemove', function (e) { canvas.style.cursor = hit(e) ? 'pointer' : 'default'; });

  // ---- Header, banner, legend ---------------------------------------------

  function fillHeader() {
    document.title = 'earc plan: ' + sc.name;
    byId('title').textContent = sc.name;
    const st = sol.stats || {};
    const parts = [robots.length + ' robots', sc.obstacles.length + ' obstacles'];
    if (sol.paths.length) parts.push('makespan ' + makespan + ' steps');
    if (sol.method) parts.push('method ' + sol.method);
    if (typeof st.planning_time_s === 'number') parts.push('planned in ' + fmt(st.planning_time_s, 3) + ' s');
    // earc-plan plan --compact: what the plan was before, or why it was kept as planned.
    const compact = st.compact && typeof st.compact === 'object' ? st.compact : null;
    if (compact && compact.rejected !== undefined) parts.push('compaction undone: ' + String(compact.rejected));
    else if (compact && Number.isInteger(compact.makespan_before) && Number.isInteger(compact.sum_of_costs_before))
      parts.push('before --compact: makespan ' + compact.makespan_before + ', sum of costs ' + compact.sum_of_costs_before);
    if (trace) parts.push(conflicts.length + ' conflicts, ' + subproblems.length + ' subproblems');
    byId('summary').textContent = parts.join(' \u00b7 ');
    if (!sol.solved) {
      const banner = byId('banner');
      let why = st.failure !== undefined ? st.failure : st.reason;
      why = Array.isArray(why) ? why.join(', ') : why === undefined ? '' : String(why);
      banner.textContent = 'Not solved' + (why ? ' (' + why + ')' : '') + ': ' +
        (sol.paths.length ? 'showing the paths the solution holds.' : 'the solution has no paths; robots are shown at their starts.');
      banner.hidden = false;
    }
  }

  function fillLegend() {
    const box = byId('legend');
    box.appendChild(el('h2', 'Drawing'));
    box.appendChild(el('div', 'Filled shape: a robot now (line: heading; arms link by link, joints dark). ' +
      'Dashed outline: its goal. Thin line: its whole path; bold fading line: its recent trail ' +
      '(mobile: centre, arm: tip).', 'note'));
    if (!trace) {
      byId('show-trace-label').hidden = true;
      box.appendChild(el('div', 'No trace: plan with `earc-plan plan --trace T.json` and pass ' +
        '`--trace T.json` to `earc-plan view` to see conflicts and subproblems.', 'note'));
      return;
    }
    box.appendChild(el('h2', 'Trace'));
    box.appendChild(el('div', 'Circled \u00d7: a conflict, shown around the step where and when it was found, ' +
      'in the plan\u2019s timeline at that moment (later repairs shift time, so a mark may sit off the final ' +
      'paths). Dashed box: a subproblem\u2019s region, drawn during its window. Colour: how it was solved ' +
      '(a conflict: its last subproblem).', 'note'));
    const counts = {};
    for (const s of subproblems) counts[s.solved_by] = (counts[s.solved_by] || 0) + 1;
    const kinds = Object.keys(OUTCOME_COLOURS).concat(Object.keys(counts).filter(function (k) { return !(k in OUTCOME_COLOURS); }));
    for (const k of kinds) {
      const row = el('div', undefined, 'row');
      const sw = el('span', undefined, 'swatch');
      sw.style.borderColor = outcomeColour(k);
      sw.style.background = outcomeColour(k) + '22';
      row.appendChild(sw);
      row.appendChild(el('span', k + ' (' + (counts[k] || 0) + ')' + (OUTCOME_NOTES[k] ? ': ' + OUTCOME_NOTES[k] : '')));
      box.appendChild(row);
    }
  }

  // ---- Start --------------------------------------------------------------

  fillHeader();
  fillLegend();
  layout();
  if (typeof ResizeObserver === 'function') new ResizeObserver(layout).observe(stage);
  else window.addEventListener('resize', layout);

  // Distinct colours in a coarse sample of the canvas (the self-test's
  // check that something was drawn).
  function canvasColours() {
    const seen = new Set();
    const img = ctx.getImageData(0, 0, canvas.width, canvas.height).data;
    const stride = Math.max(1, Math.floor(canvas.width * canvas.height / 20000));
    for (let k = 0; k < img.length / 4; k += stride) seen.add((img[4 * k] << 16) | (img[4 * k + 1] << 8) | img[4 * k + 2]);
    return seen.size;
  }

  window.earcViewer = {
    step: now,
    setStep: setStep,
    play: play,
    pause: pause,
    isPlaying: function () { now(); return playing; },
    // The world pose drawn for robot i now: mobile [x, y, theta]; an arm's
    // joint positions [[x, y], ...], the base first.
    robotPose: function (i) {
      const r = robots[i];
      const q = configAt(i, now(), new Float64Array(dimOf(r)));
      if (isMobile(r)) return [q[0], q[1], q[2]];
      const pts = armPoints(r, q, new Float64Array(2 * (r.links.length + 1)));
      const out = [];
      for (let k = 0; k < pts.length; k += 2) out.push([pts[k], pts[k + 1]]);
      return out;
    },
    errors: window.earcErrors || [],
    robotCount: robots.length,
    makespan: makespan,
    speed: function () { return SPEEDS[speedIndex]; },
    maxSpeed: SPEEDS[SPEEDS.length - 1],
    conflictCount: conflicts.length,
    conflict: function (k) { return conflicts[k]; },
    select: function (kind, id) {
      const list = kind === 'conflict' ? conflicts : subproblems;
      select(kind, list.find(function (x) { return x.id === id; }) || null);
    },
    toClient: toClient,
    canvas: canvas,
    drawnFrames: function () { return frames; },
    // Draws the current frame now (tests and timing; frames normally come
    // with the display's refresh).
    drawNow: function () { now(); draw(); updateControls(); },
    canvasColours: canvasColours,
  };
  // "#t=STEP" opens the page at a step, "#conflict=ID" with that conflict
  // selected (links in notes, screenshots).
  const fromHash = /[#&]t=([0-9.]+)/.exec(location.hash), pick = /[#&]conflict=(\d+)/.exec(location.hash);
  if (pick) {
    const c = conflicts.find(function (k) { return k.id === Number(pick[1]); });
    if (c) { select('conflict', c); setStep(c.t); }
  }
  if (fromHash) setStep(Number(fromHash[1]));
  requestAnimationFrame(tick);
})();
