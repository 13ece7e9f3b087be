// `./deploy/climbsim view RUN_DIR --snapshot PNG [--at T]`: a picture of the replay page for a
// report, the 3D view drawn (docs/deployment.md#the-viewer). Opens the page of a serving
// `climbsim-viewer --replay` in headless Chromium (SwiftShader WebGL), shows the run at T
// (default: its end), waits for the 3D view's first render of that time and the wall's depth
// grid if the run has one, and writes the page's screenshot. Prints one line: the file and the
// 3D view's grey-level variance (0: an empty view, which is an error, exit 1).
//
//   node snapshot.mjs --url URL --out PNG [--at T] --modules NODE_MODULES

import { parseArgs } from 'node:util';
import { CHROMIUM_FLAGS, imageStats, loadPuppeteer } from './headless.mjs';

const { values: args } = parseArgs({
  options: { url: { type: 'string' }, out: { type: 'string' }, at: { type: 'string' }, modules: { type: 'string' } },
});
const puppeteer = await loadPuppeteer(args.modules);
const browser = await puppeteer.launch({ executablePath: process.env.CLIMBSIM_CHROMIUM || '/usr/bin/chromium',
  headless: true, args: CHROMIUM_FLAGS, defaultViewport: { width: 1400, height: 860 } });
let code = 0;
try {
  const page = await browser.newPage();
  await page.goto(args.url, { waitUntil: 'load' });
  await page.waitForFunction(() => window.climbsimViewer?.ready, { timeout: 120000, polling: 'mutation' });
  // The time, then the wall's depth grid of that time (the page fetches one within 0.1 s of the
  // time shown; a run without grids has none).
  const target = await page.evaluate((at) => {
    const viewer = window.climbsimViewer;
    const t = at === null ? viewer.replay.end : Math.min(viewer.replay.end, Math.max(0, at));
    viewer.seek(t);
    return t;
  }, args.at === undefined ? null : Number(args.at));
  await page.waitForFunction((t) => {
    const d = window.climbsimViewer.depth;
    return d.none || (!d.busy && Math.abs(d.t - t) < 0.1 && window.climbsimViewer.depths > 0);
  }, { timeout: 120000, polling: 100 }, target);
  // A render of all of it (renders are throttled: the one asked for now comes after the grid).
  const renders = await page.evaluate(() => {
    const scene = window.climbsimViewer.scene;
    const n = scene.drawn?.render ?? 0;
    scene.requestRender();
    return n;
  });
  await page.waitForFunction((n) => (window.climbsimViewer.scene.drawn?.render ?? 0) > n,
    { timeout: 120000, polling: 100 }, renders);
  const png = await page.evaluate(() => window.climbsimViewer.scene.renderer.domElement.toDataURL('image/png'));
  const { variance } = await imageStats(page, Buffer.from(png.split(',')[1], 'base64'));
  await page.screenshot({ path: args.out });
  const t = await page.evaluate(() => window.climbsimViewer.replay.time);
  console.log(`snapshot: ${args.out} at t = ${t.toFixed(3)} s (3D view grey variance ${variance.toFixed(0)})`);
  if (!(variance > 0)) {
    console.error(`snapshot: ${args.out}: the 3D view is empty`);
    code = 1;
  }
} finally {
  await browser.close();
}
process.exit(code);
