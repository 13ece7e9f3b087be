// The live viewer in a real headless Chromium, on a real run through the launcher
// (`climbsim-compose run crack-descent --viewer`, every service a process, the clock started
// paused): the page loads with no console error; the 3D canvas is not blank and changes as the
// robot moves; single step, pause and resume act on simulated time; a client that sends
// garbage is disconnected and the run goes on; the last plotted F equals trace.csv's F at that
// time. Screenshots: <build>/test-artifacts/viewer/live_*.png.
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { click, imageDifference, imageStats, openPage } from './browser.mjs';
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
  '-f', compose, '--viewer', '--out', runDir, '--set', 'duration_s=8'], join(opts.artifacts, 'live_launcher.log'));
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
  // A render throttled by its cost (software WebGL under load: seconds apart) may come well
  // after the click: wait for a render after it before each screenshot of the canvas.
  const rendered = () => page.evaluate(() => window.climbsimViewer.scene?.renders ?? 0);
  const topViewRendered = async () => {
    const renders = await rendered();
    await click(page, '#btn-top');
    // Polled: a render changes no DOM node, so mutation polling would not see it.
    await page.waitForFunction((n) => (window.climbsimViewer.scene?.renders ?? 0) > n, { timeout: 120000, polling: 100 }, renders);
  };
  await topViewRendered();
  const blank = await imageStats(page, await (await page.$('#view3d canvas')).screenshot({ path: join(opts.artifacts, 'live_start_canvas.png') }));
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

  // Paced at real time so that pause and resume are seen while it runs.
  await page.$eval('#rtf-value', (el) => { el.value = '1'; });
  await click(page, '#btn-rtf');
  await waitFor(() => window.climbsimViewer.run.rtf_target === 1);
  await click(page, '#btn-resume');
  await waitFor(() => window.climbsimViewer.run.phase === 'running' && window.climbsimViewer.run.t_s > 3.6);
  checks.check(true, 'resume: simulated time goes on (t > 3.6 s, the robot drives from 2 s)');
  await click(page, '#btn-pause');
  await waitFor(() => window.climbsimViewer.run.phase === 'paused');
  const paused = (await state());
  // While paused the clock repeats SimTime: five more frames, and time must not have moved.
  await waitFor((frames) => window.climbsimViewer.frames >= frames + 5, paused.frames);
  const still = (await state()).run;
  checks.check(still.t_s === paused.run.t_s && still.phase === 'paused', `pause: t stays at ${paused.run.t_s} s over 5 frames`);
  const lastWhilePaused = await page.evaluate(() => window.climbsimViewer.lastPlotted());
  await waitFor(() => window.climbsimViewer.depths > 0);
  await topViewRendered();
  const moved = await (await page.$('#view3d canvas')).screenshot({ path: join(opts.artifacts, 'live_moved_canvas.png') });
  const difference = await imageDifference(page, readFileSync(join(opts.artifacts, 'live_start_canvas.png')), moved);
  checks.check(difference > 1, `the 3D canvas changed as the robot moved (mean grey difference ${difference.toFixed(2)} > 1)`);
  const movedStats = await imageStats(page, moved);
  checks.check(movedStats.variance > 100, `the 3D canvas is not blank after moving (variance ${movedStats.variance.toFixed(0)})`);
  await page.screenshot({ path: join(opts.artifacts, 'live_page.png') });

  // To the end as fast as possible; the last plotted F is the trace's F at that time.
  await page.$eval('#rtf-value', (el) => { el.value = '0'; });
  await click(page, '#btn-rtf');
  await click(page, '#btn-resume');
  await waitFor(() => window.climbsimViewer.run.phase === 'completed', undefined, 300000);
  const plotted = await page.evaluate(() => ({ t: window.climbsimViewer.plots.columns[0][0], F: window.climbsimViewer.plots.columns[0][1] }));
  await page.screenshot({ path: join(opts.artifacts, 'live_completed.png') });
  checks.check(page.errors.length === 0, `no console or page errors (${page.errors.join('; ')})`);
  const code = await launcher.exited;
  checks.check(code === 0, `the run completed (launcher exit ${code})`);
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
