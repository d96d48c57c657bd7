// The plan viewer's drawing: robots, the background layer, trails,
// subproblem regions, conflict marks and the frame. Part of one function
// with viewer.js (before) and viewer_ui.js (after): see viewer.js.

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
