// `climbsim-compose view RUN_DIR` in a real headless Chromium: a short run is made, then its
// replay is served, opening at the run's end; the slider at t shows the trace's values at t
// (exactly, from the page's readouts), the 3D canvas is not blank, play advances time, the header
// shows the playback speed ("replay 10.0x", never a real-time factor), no console
// error, and `view --snapshot` writes the page's picture with the 3D view drawn. Bad input:
// a directory without a trace and a port in use are one line and exit 2.
// Screenshots: <build>/test-artifacts/viewer/replay_*.png.
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { click, drawnCanvas, imageStats, openPage } from './browser.mjs';
import { Checks, Child, composeCopy, freePort, freshDir, options, puppeteer, readTrace } from './harness.mjs';

const opts = options();
const checks = new Checks('viewer replay');
const compose = (args, log) => new Child([join(opts.bin, 'climbsim-compose'), '--root', opts.root, '--build', opts.build, ...args],
  log && join(opts.artifacts, log));
const pptr = await puppeteer(opts);

// Bad input first: cheap, and the messages must be one line each.
const empty = freshDir(join(opts.runs, 'viewer-replay-empty'));
mkdirSync(empty, { recursive: true });
const noTrace = compose(['view', empty]);
const noTraceCode = await noTrace.exited;
const noTraceLines = noTrace.lines.filter((l) => l.trim());
checks.check(noTraceCode === 2 && noTraceLines.length === 1 && noTraceLines[0].includes('trace.csv'),
  `view of a directory without a trace: exit ${noTraceCode}, "${noTraceLines.join(' | ')}"`);

// A run made without the viewer: the recorder keeps the wall's depth grids for the replay.
const runDir = freshDir(join(opts.runs, 'viewer-replay'));
const composeFile = composeCopy(opts, 'viewer-replay-test', [['--port, "8765"', `--port, "${await freePort()}", --linger-s, "0"`]]);
const run = compose(['run', 'crack-descent', '-f', composeFile, '--out', runDir, '--set', 'duration_s=3'], 'replay_run.log');
const runCode = await run.exited;
checks.check(runCode === 0, `the run to replay (no viewer) completed (exit ${runCode})`);
const gridLines = existsSync(join(runDir, 'viewer', 'depth_grids.jsonl'))
  ? readFileSync(join(runDir, 'viewer', 'depth_grids.jsonl'), 'utf8').split('\n').filter((l) => l.trim()) : [];
// 3 s at one grid per 0.1 s of simulated time (the last batch may be cut off by the run's end).
checks.check(gridLines.length >= 25 && gridLines.length <= 31,
  `the recorder kept ${gridLines.length} depth grids of the 3 s run (about 30 expected)`);

let browser;
const port = await freePort();
const viewer = compose(['view', runDir, '--port', String(port)], 'replay_viewer.log');
try {
  const [, url] = await viewer.waitForLine(/replay of .* at (http:\/\/\S+)/);
  const busy = compose(['view', runDir, '--port', String(port)]);
  const busyCode = await busy.exited;
  const busyLines = busy.lines.filter((l) => l.trim());
  checks.check(busyCode === 2 && busyLines.length === 1 && busyLines[0].includes(`--port ${port}: already in use`),
    `a second view on the same port: exit ${busyCode}, "${busyLines.join(' | ')}"`);

  const opened = await openPage(pptr, url);
  browser = opened.browser;
  const page = opened.page;
  await page.waitForFunction(() => window.climbsimViewer?.ready, { timeout: 60000, polling: 'mutation' });
  const trace = readTrace(join(runDir, 'trace.csv'));
  const col = (name) => trace.columns.indexOf(name);
  // A finished run opens at its end, with the whole run's plots.
  const opensAt = await page.evaluate(() => Number(document.getElementById('sim-time').dataset.value));
  const lastRowT = Number(trace.cells[trace.cells.length - 1][col('t_s')]);
  checks.check(Math.abs(opensAt - lastRowT) < 1e-9, `the replay opens at the run's end: t = ${opensAt} s (last row ${lastRowT} s)`);
  for (const t of [0.5, 1.5, 2.75]) {
    await page.evaluate((time) => window.climbsimViewer.seek(time), t);
    const shown = await page.evaluate(() => Object.fromEntries(['readout-F', 'readout-pfx', 'readout-pfy', 'readout-x', 'readout-y', 'sim-time']
      .map((id) => [id, document.getElementById(id).dataset.value])));
    // The row shown at t is the last with t_s <= t.
    const row = trace.cells.map((c) => Number(c[col('t_s')])).filter((x) => x <= t + 1e-12).length - 1;
    const expect = { 'readout-F': 'downforce_n', 'readout-pfx': 'pf_x_m', 'readout-pfy': 'pf_y_m', 'readout-x': 'x_m', 'readout-y': 'y_m', 'sim-time': 't_s' };
    const wrong = Object.entries(expect).filter(([id, name]) => Number(shown[id]) !== Number(trace.cells[row][col(name)]));
    checks.check(row >= 0 && wrong.length === 0,
      `slider at ${t} s shows trace row ${row} (t_s ${trace.cells[row]?.[col('t_s')]}): ${wrong.length ? `differs in ${wrong.map(([id]) => id).join(', ')}` : 'F, P_F, x, y, t equal'}`);
  }
  await page.waitForFunction(() => window.climbsimViewer.depths > 0, { timeout: 30000, polling: 'mutation' });
  // Not a flat wall: the grid served at 1.5 s has the concrete's roughness in it.
  const grid = await page.evaluate(async () => (await fetch('api/depth?t=1.5')).json());
  const heights = grid?.heights_mm ?? [];
  const spread = heights.length ? Math.max(...heights) - Math.min(...heights) : 0;
  checks.check(grid?.size === 64 && heights.length === 64 * 64 && spread > 0.1,
    `the replay shows the wall's depth grid kept by the recorder (${grid?.size} cells a side, relief ${spread.toFixed(2)} mm)`);
  // The picture of a render after the click (renders are throttled by their cost: under load
  // seconds apart), read with what it shows.
  const since = await page.evaluate(() => window.climbsimViewer.scene?.renders ?? 0);
  await click(page, '#btn-top');
  const canvas = await drawnCanvas(page, { since });
  writeFileSync(join(opts.artifacts, 'replay_canvas.png'), canvas.png);
  const stats = await imageStats(page, canvas.png);
  checks.check(stats.variance > 100, `the replay's 3D canvas is not blank (variance ${stats.variance.toFixed(0)})`);
  // The header says the replay's speed, not a real-time factor.
  const header = () => page.evaluate(() => document.getElementById('run-panel').innerText);
  const paused = await header();
  checks.check(paused.includes('replay 1.0x, paused') && !paused.includes('real time'),
    `a paused replay's header shows its speed: "${paused.replace(/\s+/g, ' ')}"`);
  await page.evaluate(() => window.climbsimViewer.seek(0.1));
  await page.select('#replay-speed', '10');
  await click(page, '#btn-play');
  // The header of a frame shown while playing (phase and header come from one update; the
  // replay may reach the run's end soon after).
  const playing = await (await page.waitForFunction(() => document.getElementById('phase').dataset.value === 'replaying'
    && document.getElementById('run-panel').innerText, { timeout: 60000, polling: 'mutation' })).jsonValue();
  await page.waitForFunction(() => Number(document.getElementById('sim-time').dataset.value) > 1.0, { timeout: 60000, polling: 'mutation' });
  checks.check(true, 'play at 10x advances the replay past 1 s');
  checks.check(/replay 10\.0x(?!, paused)/.test(playing) && !playing.includes('real time'),
    `a replay playing at 10x says so in the header: "${playing.replace(/\s+/g, ' ')}"`);
  await page.select('#replay-speed', '2');
  const two = await page.evaluate(() => document.getElementById('replay-rate-value').dataset.value);
  checks.check(two === '2.0x' || two === '2.0x, paused', `speed 2x chosen: the header says "${two}"`);
  await page.screenshot({ path: join(opts.artifacts, 'replay_page.png') });
  checks.check(page.errors.length === 0, `no console or page errors (${page.errors.join('; ')})`);
} catch (error) {
  checks.check(false, error.message);
} finally {
  if (browser) await browser.close();
  viewer.kill();
  await viewer.exited;
}

// `view RUN_DIR --snapshot PNG --at T`: a picture of the page for a report, its 3D view drawn.
const snapshotPng = join(opts.artifacts, 'replay_snapshot.png');
const snapshot = spawnSync(join(opts.root, 'deploy', 'climbsim'), ['view', runDir, '--snapshot', snapshotPng, '--at', '2'],
  { encoding: 'utf8', env: { ...process.env, CLIMBSIM_BUILD_DIR: opts.build }, timeout: 300000 });
const snapshotLine = (snapshot.stdout || '').trim().split('\n').pop() || '';
const snapshotVariance = Number((snapshotLine.match(/variance (\d+)/) || [])[1]);
checks.check(snapshot.status === 0 && existsSync(snapshotPng) && snapshotVariance > 100 && snapshotLine.includes('t = 2.000 s'),
  `view --snapshot --at 2: exit ${snapshot.status}, "${snapshotLine}" ${(snapshot.stderr || '').trim()}`);
process.exit(checks.report());
