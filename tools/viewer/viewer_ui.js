// The plan viewer's controls: playback, selection and the details pane,
// the header, banner and legend, and the start. Part of one function
// with viewer.js and viewer_draw.js (before): see viewer.js.

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
