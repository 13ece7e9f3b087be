// Attaches a headless Chromium to a running viewer and stays until the run ends (for the e2e
// benchmark: the real-time factor with one connected viewer).
//   node tests/system/viewer/attach_browser.mjs --build BUILD [--url http://127.0.0.1:8765/]
//        [--wait-s 120] [--max-s 3600] [--resume]
// --resume: for a run whose clock starts paused (clock: {start_paused: true}), press the page's
// resume button once the page is loaded and shows the run held before step 0, so that the
// browser's own start-up (several seconds of CPU) is not part of the run it watches.
// Waits up to --wait-s for the viewer to answer, then until the page shows the run completed,
// stopped or failed (or --max-s). Prints one line:
//   attach: frames=N depths=M errors=K phase=P
// Exit 0 when it saw the run end with no page error, 1 otherwise. browser_cpu_s is the CPU
// time of the whole Chromium process tree from the start of the watched run (the resume with
// --resume) to its end, read from /proc (Chromium's children are not reaped by node, so
// node's own rusage would miss them).
//   attach: frames=N depths=M errors=K phase=P browser_cpu_s=S by_type=renderer:S,gpu-process:S,...
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { loadPuppeteer, openPage } from './browser.mjs';

const args = process.argv.slice(2);
const value = (name, fallback) => {
  const at = args.indexOf(name);
  return at >= 0 && at + 1 < args.length ? args[at + 1] : fallback;
};
const build = value('--build');
if (!build) {
  console.error('attach_browser.mjs: --build BUILD is required');
  process.exit(2);
}
const url = value('--url', 'http://127.0.0.1:8765/');
const waitS = Number(value('--wait-s', '120'));
const maxS = Number(value('--max-s', '3600'));

// The viewer starts with the run: its port answers a little later.
const deadline = Date.now() + waitS * 1000;
for (;;) {
  try {
    const response = await fetch(new URL('api/hello', url));
    if (response.ok) break;
  } catch {
    // not listening yet
  }
  if (Date.now() > deadline) {
    console.error(`attach_browser.mjs: no viewer at ${url} within ${waitS} s`);
    process.exit(1);
  }
  await new Promise((resolve) => setTimeout(resolve, 100));
}
/** CPU seconds (user + system) of `root` and every process below it, from /proc; `byType`
 *  (if given) gets them per Chromium process type (--type=renderer, gpu-process, ...). */
function treeCpuSeconds(root, byType) {
  const tick = 100;  // USER_HZ on Linux
  const children = new Map();
  const cpu = new Map();
  for (const entry of readdirSync('/proc')) {
    if (!/^\d+$/.test(entry)) continue;
    try {
      const stat = readFileSync(`/proc/${entry}/stat`, 'utf8');
      const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
      const ppid = Number(fields[1]);
      cpu.set(Number(entry), (Number(fields[11]) + Number(fields[12])) / tick);
      if (!children.has(ppid)) children.set(ppid, []);
      children.get(ppid).push(Number(entry));
    } catch {
      // the process ended meanwhile
    }
  }
  let total = 0;
  const stack = [root];
  while (stack.length) {
    const pid = stack.pop();
    total += cpu.get(pid) ?? 0;
    if (byType) {
      let type = 'browser';
      try {
        type = /--type=([a-z-]+)/.exec(readFileSync(`/proc/${pid}/cmdline`, 'utf8'))?.[1] ?? 'browser';
      } catch {
        // ended meanwhile
      }
      byType.set(type, (byType.get(type) ?? 0) + (cpu.get(pid) ?? 0));
    }
    stack.push(...(children.get(pid) ?? []));
  }
  return total;
}

const puppeteer = await loadPuppeteer(join(build, 'viewer', 'npm', 'node_modules'));
const { browser, page } = await openPage(puppeteer, url);
let phase = 'unknown';
const browserPid = browser.process()?.pid;
if (args.includes('--resume')) {
  await page.waitForFunction(() => window.climbsimViewer?.run?.phase === 'paused', { timeout: waitS * 1000, polling: 100 });
  await page.click('#btn-resume');
}
const typeAtStart = new Map();
const cpuAtStart = browserPid ? treeCpuSeconds(browserPid, typeAtStart) : 0;
try {
  await page.waitForFunction(() => ['completed', 'stopped', 'failed'].includes(window.climbsimViewer?.run?.phase),
    { timeout: maxS * 1000, polling: 500 });
} catch (error) {
  console.error(`attach_browser.mjs: ${error.message}`);
}
// What fails once the run has ended does not count, nor a connection the viewer reset: it
// leaves after its linger, and a picture the page was fetching as the run ended is cut off
// (net::ERR_CONNECTION_RESET or _REFUSED, also seen before the page's 500 ms poll saw the end;
// a reset can come at a run's start too: counted out here, the system tests stay strict).
const errorsAtEnd = page.errors.length;
const cutOff = (error) => /ERR_CONNECTION_(RESET|REFUSED)/.test(error);
const seen = await page.evaluate(() => ({ frames: window.climbsimViewer.frames, depths: window.climbsimViewer.depths,
  phase: window.climbsimViewer.run?.phase }));
phase = seen.phase ?? phase;
const typeAtEnd = new Map();
const browserCpuS = browserPid ? treeCpuSeconds(browserPid, typeAtEnd) - cpuAtStart : NaN;
// Where the browser's CPU went: the page (renderer), WebGL in software (gpu-process), the rest.
const byType = [...typeAtEnd].map(([type, s]) => `${type}:${(s - (typeAtStart.get(type) ?? 0)).toFixed(2)}`).join(',');
const counted = page.errors.filter((error, k) => k < errorsAtEnd && !cutOff(error));
page.errors.forEach((error, k) => console.error(`attach_browser.mjs: page error${k >= errorsAtEnd || cutOff(error) ? ' (a cut-off or after the run ended, not counted)' : ''}: ${error}`));
page.errors.splice(0, page.errors.length, ...counted);
console.log(`attach: frames=${seen.frames} depths=${seen.depths} errors=${page.errors.length} phase=${phase} browser_cpu_s=${browserCpuS.toFixed(2)} by_type=${byType}`);
await browser.close();
process.exit(['completed', 'stopped', 'failed'].includes(phase) && page.errors.length === 0 ? 0 : 1);
