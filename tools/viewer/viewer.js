// The plan viewer (written into the page by `earc-plan view`; sources in
// tools/viewer/, embedded by tools/viewer/embed.sh). It animates the
// embedded solution on a canvas and, with a trace, shows conflicts and
// subproblems. World y points up, the canvas's down: y is flipped.
//
// The page runs viewer.js, viewer_draw.js and viewer_ui.js, in this order,
// as the body of one function (viewer.html), so they share its names:
// this file holds the plan's data, kinematics, trails, trace, page
// elements, state and view transform.
//
// Speed with 128 robots x 5,000 steps comes from doing per frame only what
// changes: the workspace, obstacles, goals and faint full paths sit in an
// offscreen layer drawn once per resize; trails are cut from polylines
// decimated once at load (a few vertices per robot and frame); frames are
// drawn only when something changed.
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
