// The live viewer in a real headless Chromium, on a real run through the launcher
// (`climbsim-compose run crack-descent --viewer`, every service a process, the clock started
// paused): the page loads with no console error; the 3D canvas is not blank and changes as the
// robot moves (a render that draws it moved, read from the canvas with the pose it shows);
// single steps (one, and many), pause and resume act on simulated time; a client that sends
// garbage is disconnected and the run goes on; every plotted F equals trace.csv's F at its
// time. Every wait is for an event, none for a quiet machine. Pictures of the 3D view:
// <build>/test-artifacts/viewer/live_*.png.
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { click, drawnCanvas, imageDifference, imageStats, openPage } from './browser.mjs';
import { Checks, Child, composeCopy, freePort, freshDir, options, puppeteer, readTrace } from './harness.mjs';

const opts = options();
const checks = new Checks('viewer live');
const port = await freePort();
const compose = composeCopy(opts, 'viewer-live-test', [
  ['clock: {rtf: 0,', 'clock: {rtf: 0, start_paused: true,'],
  ['--port, "8765"', `--port, "${port}", --linger-s, "10"`],
]);
const runDir = freshDir(join(opts.runs, 'viewer-live'));
const launcher = new Child([join(opts.bin, 'climbsim-compose'), '--root', opts.root, '--build', opts.build, 'run', 'crack-descent',
  '-f', compose, '--viewer', '--out', runDir, '--set', 'duration_s=12'], join(opts.artifacts, 'live_launcher.log'));
let browser;
const pptr = await puppeteer(opts);
try {
  const [, url] = await launcher.waitForLine(/open (http:\/\/\S+)/);
  const opened = await openPage(pptr, url);
  browser = opened.browser;
  const page = opened.page;
  const state = () => page.evaluate(() => ({ run: window.climbsimViewer.run, frames: window.climbsimViewer.frames }));
  // A wait that times out names what it waited for.
  const waitFor = (fn, arg, timeout = 120000) => page.waitForFunction(fn, { timeout, polling: 'mutation' }, arg)
    .catch((error) => { throw new Error(`${error.message}, waiting for ${fn.toString()}`); });

  // Started paused: the whole roster is up when the first frame says so.
  // (Hosts come from ParticipantReady, the roster from RunStart: no order across topics.)
  await waitFor(() => window.climbsimViewer.run?.phase === 'paused' && window.climbsimViewer.run.roster.length > 0 &&
    window.climbsimViewer.run.roster.every((m) => m.host));
  const roster = (await state()).run.roster;
  checks.check(roster.some((m) => m.name === 'thermo') && !roster.some((m) => m.name === 'viewer'),
    `the roster has the services and not the viewer (${roster.map((m) => m.name).join(', ')})`);
  checks.check(roster.every((m) => m.host), `every roster member shows its host (${roster.map((m) => `${m.name}@${m.host}`).join(', ')})`);
  // The top view as a render after the click drew it (with `from`: with the robot at least
  // `minMove` m from there). A render throttled by its cost (software WebGL under load: seconds
  // apart) may come well after the click, and the page applies the latest state at most a few
  // times a second: the picture is taken when the render awaited has happened, read from the
  // canvas with the pose it shows (drawnCanvas).
  const rendered = () => page.evaluate(() => window.climbsimViewer.scene?.renders ?? 0);
  const topView = async (file, from = null, minMove = 0) => {
    const since = await rendered();
    await click(page, '#btn-top');
    const picture = await drawnCanvas(page, { since, from, minMove });
    writeFileSync(join(opts.artifacts, file), picture.png);
    return picture;
  };
  const start = await topView('live_start_canvas.png');
  const blank = await imageStats(page, start.png);
  checks.check(blank.variance > 100, `the 3D canvas is not blank (grey variance ${blank.variance.toFixed(0)} > 100)`);

  // Single step: exactly one step of simulated time.
  const before = (await state()).run;
  await page.$eval('#step-count', (el) => { el.value = '1'; });
  await click(page, '#btn-step');
  await waitFor((step) => window.climbsimViewer.run.step > step, before.step);
  const stepped = (await state()).run;
  checks.check(stepped.step === before.step + 1 && Math.abs(stepped.t_s - before.t_s - before.dt_s) < 1e-9,
    `single step: step ${before.step} -> ${stepped.step}, t ${before.t_s} -> ${stepped.t_s} s`);

  // A client that sends garbage is disconnected; the run goes on (below).
  const closed = await page.evaluate(() => new Promise((resolve) => {
    const socket = new WebSocket(`ws://${location.host}/ws`);
    socket.onopen = () => socket.send('this is not a command');
    socket.onclose = () => resolve(true);
  }));
  checks.check(closed, 'a WebSocket client sending garbage is disconnected');

  // Many steps at once: 740 (3.7 s) as fast as the machine goes, then held again. The robot,
  // held until 2 s, drives at 5 cm/s: it ends 8.5 cm from the start.
  const DRIVE_STEPS = 740;
  await page.$eval('#step-count', (el, n) => { el.value = String(n); }, DRIVE_STEPS);
  await click(page, '#btn-step');
  await waitFor((step) => window.climbsimViewer.run.step >= step && window.climbsimViewer.run.phase === 'paused',
    stepped.step + DRIVE_STEPS);
  const driven = (await state()).run;
  checks.check(driven.step === stepped.step + DRIVE_STEPS,
    `${DRIVE_STEPS} single steps: step ${stepped.step} -> ${driven.step}, t ${stepped.t_s} -> ${driven.t_s} s`);
  await waitFor(() => window.climbsimViewer.depths > 0);
  // The first render that draws the robot at least 5 cm from where the first picture had it.
  const moved = await topView('live_moved_canvas.png', start.position, 0.05);
  const movedBy = Math.hypot(...moved.position.map((v, i) => v - start.position[i]));
  const difference = await imageDifference(page, start.png, moved.png);
  checks.check(difference > 1, `the 3D canvas changed as the robot moved ${(movedBy * 100).toFixed(1)} cm ` +
    `(renders ${start.render} and ${moved.render}: mean grey difference ${difference.toFixed(2)} > 1)`);
  const movedStats = await imageStats(page, moved.png);
  checks.check(movedStats.variance > 100, `the 3D canvas is not blank after moving (variance ${movedStats.variance.toFixed(0)})`);

  // Resume and pause while it runs, paced at a tenth of real time. The page learns of the run
  // a few times a second at most, and seconds late on a loaded machine (the viewer yields the
  // CPU to the run; the page applies the latest frame as often as its cost allows); at this
  // pace the run's end is over a minute away, so the pause comes while it runs however late
  // the page sees that it does.
  await page.$eval('#rtf-value', (el) => { el.value = '0.1'; });
  await click(page, '#btn-rtf');
  await waitFor(() => window.climbsimViewer.run.rtf_target === 0.1);
  await click(page, '#btn-resume');
  await waitFor((t) => window.climbsimViewer.run.phase === 'running' && window.climbsimViewer.run.t_s > t, driven.t_s);
  const running = (await state()).run;
  checks.check(true, `resume: simulated time goes on (t ${driven.t_s} -> ${running.t_s} s)`);
  const lagMs = await page.evaluate(() => window.climbsimViewer.lagMs);
  await click(page, '#btn-pause');
  await waitFor(() => ['paused', 'completed', 'stopped', 'failed'].includes(window.climbsimViewer.run.phase));
  const pausedPhase = (await state()).run.phase;
  if (!checks.check(pausedPhase === 'paused', `pause: the run paused (phase ${pausedPhase}; the page was ${lagMs} ms behind the run)`)) {
    throw new Error('the run was not paused: the remaining checks need a paused run');
  }
  const paused = (await state());
  // While paused the clock repeats SimTime: five more frames, and time must not have moved.
  await waitFor((frames) => window.climbsimViewer.frames >= frames + 5, paused.frames);
  const still = (await state()).run;
  checks.check(still.t_s === paused.run.t_s && still.phase === 'paused', `pause: t stays at ${paused.run.t_s} s over 5 frames`);
  const lastWhilePaused = await page.evaluate(() => window.climbsimViewer.lastPlotted());
  await page.screenshot({ path: join(opts.artifacts, 'live_page.png') });

  // To the end as fast as possible; every plotted F is the trace's F at its time. The launcher
  // ends the viewer a few seconds after the clock (an observer never holds a run up), and on a
  // loaded machine a viewer yielding the CPU may not have sent the page the run's last frames by
  // then: the plots are checked as far as they go, once the viewer has left and the page's
  // connection has closed (every message sent before has been handled then).
  await page.$eval('#rtf-value', (el) => { el.value = '0'; });
  await click(page, '#btn-rtf');
  await click(page, '#btn-resume');
  const code = await launcher.exited;
  checks.check(code === 0, `the run completed (launcher exit ${code})`);
  await waitFor(() => ['ended', 'disconnected'].includes(document.getElementById('mode').textContent));
  const plotted = await page.evaluate(() => ({ t: window.climbsimViewer.plots.columns[0][0], F: window.climbsimViewer.plots.columns[0][1],
    told: document.getElementById('mode').textContent === 'ended' }));
  await page.screenshot({ path: join(opts.artifacts, 'live_completed.png') });
  // A page the viewer left without the end of the run tries to reconnect: Chromium logs each refused attempt.
  const errors = page.errors.filter((e) => plotted.told || !/WebSocket connection to .* failed/.test(e));
  checks.check(errors.length === 0,
    `no console or page errors (${errors.map((e) => `${e}; `).join('')}the page was ${plotted.told ? '' : 'not '}told of the end)`);
  // A value stamped with step k holds at (k + 1) dt: trace.csv has it in the row of that time.
  const trace = readTrace(join(runDir, 'trace.csv'));
  const traceF = new Map(trace.column('t_s').map((t, i) => [Math.round(t * 1e6), trace.column('downforce_n')[i]]));
  const atTrace = (t) => traceF.get(Math.round(t * 1e6));
  checks.check(lastWhilePaused && atTrace(lastWhilePaused.t) === lastWhilePaused.F,
    `the last plotted F while paused, ${lastWhilePaused?.F} N at t ${lastWhilePaused?.t} s, equals the trace's ${atTrace(lastWhilePaused?.t)}`);
  const inTrace = plotted.t.map((t, i) => [t, plotted.F[i]]).filter(([t]) => atTrace(t) !== undefined);
  const wrong = inTrace.filter(([t, f]) => atTrace(t) !== f);
  checks.check(inTrace.length > 20 && wrong.length === 0,
    `all ${inTrace.length} plotted F values equal the trace's at their times (${wrong.length} differ${wrong.length ? `, e.g. t ${wrong[0][0]}` : ''})`);
} catch (error) {
  checks.check(false, `${error.message}`);
} finally {
  if (browser) await browser.close();
  launcher.kill();
  await launcher.exited;
}
process.exit(checks.report());
