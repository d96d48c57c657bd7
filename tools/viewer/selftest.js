// Runs in <head>, before the viewer's script, so that it records every error
// of that script, a syntax error included, and can still report when the
// viewer never started.
//
// Self-test for the browser tests (tests/cli/view_browser.sh): loaded with
// "#selftest=T1,T2,..." the page, once loaded, sets each time T and writes
// every robot's pose at T (earcViewer.robotPose) as JSON into
// <pre id="selftest-poses">; the test compares them with poses it computes
// from the solution file itself, so the page never grades its own numbers.
// It also checks that nothing threw, that keyboard and play/pause work, that
// the canvas shows something and, with a trace, that clicking a conflict
// mark shows its details, and it times drawing a frame; then it writes
// "PASS ..." or "FAIL ..." into <pre id="selftest">.
'use strict';
window.earcErrors = [];
window.addEventListener('error', function (e) {
  const where = e.lineno ? ' (line ' + e.lineno + ')' : '';
  window.earcErrors.push(String(e.message || e.error || 'unknown error') + where);
});
window.addEventListener('unhandledrejection', function (e) {
  window.earcErrors.push('unhandled rejection: ' + e.reason);
});

window.addEventListener('load', function () {
  const m = /[#&]selftest=([^&]*)/.exec(location.hash);
  if (!m) return;
  const times = decodeURIComponent(m[1]).split(',').filter(function (s) { return s !== ''; }).map(Number);
  const frameMs = earcFrameCost();
  // Let the viewer settle and draw by itself before the checks.
  setTimeout(function () { earcSelftest(times, frameMs); }, 100);
});

// Milliseconds to draw one frame, over frames at times spread across the
// plan; measured in the load event, since under the tests' virtual time a
// timer's callback sees a clock that stands still. 0 if there is no viewer.
function earcFrameCost() {
  const v = window.earcViewer;
  if (!v) return 0;
  const FRAMES = 30;
  const t0 = performance.now();
  for (let k = 0; k < FRAMES; ++k) {
    v.setStep(v.makespan * k / FRAMES);
    v.drawNow();
  }
  const ms = (performance.now() - t0) / FRAMES;
  v.setStep(0);
  return ms;
}

function earcSelftest(times, frameMs) {
  const problems = [];
  const notes = [];
  const verdict = document.getElementById('selftest');
  function finish() {
    if (window.earcErrors.length) problems.push('script errors: ' + window.earcErrors.join(' | '));
    verdict.textContent = problems.length ? 'FAIL ' + problems.join('; ') : 'PASS ' + notes.join('; ');
    verdict.hidden = false;
  }
  const v = window.earcViewer;
  if (!v) {
    problems.push('window.earcViewer is missing: the viewer script did not run');
    finish();
    return;
  }
  function key(k, shift) {
    document.dispatchEvent(new KeyboardEvent('keydown', { key: k, shiftKey: !!shift, bubbles: true, cancelable: true }));
  }
  function expect(cond, what) {
    if (!cond) problems.push(what);
  }
  try {
    const last = v.makespan;
    expect(v.errors === window.earcErrors, 'earcViewer.errors is not the page\'s error list');
    const poses = {};
    for (const t of times) {
      v.setStep(t);
      const want = Math.min(Math.max(t, 0), last);
      expect(Math.abs(v.step() - want) < 1e-9, 'setStep(' + t + ') left step() at ' + v.step());
      const list = [];
      for (let i = 0; i < v.robotCount; ++i) list.push(v.robotPose(i));
      poses[String(t)] = list;
    }
    document.getElementById('selftest-poses').textContent = JSON.stringify(poses);
    notes.push(v.robotCount + ' robots posed at ' + times.length + ' times');

    v.setStep(0);
    key('End');
    expect(v.step() === last, 'End did not go to the last step');
    key('Home');
    expect(v.step() === 0, 'Home did not go to step 0');
    if (last >= 11) {
      key('ArrowRight');
      expect(v.step() === 1, 'ArrowRight did not step forward');
      key('ArrowRight', true);
      expect(v.step() === 11, 'shift+ArrowRight did not step 10 forward');
      key('ArrowLeft');
      expect(v.step() === 10, 'ArrowLeft did not step back');
    }
    const speed = v.speed();
    key('+');
    expect(v.speed() > speed || speed === v.maxSpeed, '+ did not speed up');
    key('-');
    expect(v.speed() === speed, '- did not slow down again');

    if (v.conflictCount > 0) {
      const c = v.conflict(0);
      v.setStep(c.t);
      const at = v.toClient(c.place);
      v.canvas.dispatchEvent(new MouseEvent('click', { clientX: at.x, clientY: at.y, bubbles: true }));
      const shown = document.getElementById('details').textContent;
      expect(shown.indexOf('Conflict ' + c.id) >= 0, 'clicking conflict ' + c.id + '\'s mark did not show its details');
      notes.push('clicked conflict ' + c.id);
    }

    notes.push('frame_ms=' + frameMs.toFixed(2));

    v.setStep(0);
    key(' ');
    expect(v.isPlaying() === (last > 0), 'space did not start playing');
    v.pause();
    v.play();
    expect(v.isPlaying() === (last > 0), 'play() did not start playing');
    setTimeout(function () {
      try {
        const reached = v.step();
        v.pause();
        expect(!v.isPlaying(), 'pause() did not stop playing');
        if (last > 0) expect(reached > 0, 'half a second of playing did not advance time');
        notes.push('played to ' + reached.toFixed(2));
        expect(v.drawnFrames() > 0, 'no frame was drawn');
        expect(v.canvasColours() >= 4, 'the canvas looks blank');
      } catch (e) {
        problems.push('self-test threw: ' + e);
      }
      finish();
    }, 500);
  } catch (e) {
    problems.push('self-test threw: ' + e);
    finish();
  }
}
