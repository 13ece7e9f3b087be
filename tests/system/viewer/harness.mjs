// What the viewer's browser tests share: the build's paths, a compose copy, a free port, the
// launcher as a child process whose output lines can be awaited, trace.csv, and checks that
// collect failures with the screenshots kept in <build>/test-artifacts/viewer.
import { spawn } from 'node:child_process';
import { mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:net';
import { join } from 'node:path';
import { loadPuppeteer } from './browser.mjs';

export function options() {
  const args = process.argv.slice(2);
  const value = (name) => {
    const at = args.indexOf(name);
    if (at < 0 || at + 1 >= args.length) throw new Error(`missing ${name}`);
    return args[at + 1];
  };
  const build = value('--build');
  const root = value('--root');
  return { build, root, bin: join(build, 'bin'), runs: join(build, 'test-runs'), artifacts: join(build, 'test-artifacts', 'viewer'),
    nodeModules: join(build, 'viewer', 'npm', 'node_modules') };
}

export async function puppeteer(opts) {
  mkdirSync(opts.artifacts, { recursive: true });
  return loadPuppeteer(opts.nodeModules);
}

/** A TCP port free on 127.0.0.1 now. */
export function freePort() {
  return new Promise((resolve, reject) => {
    const server = createServer();
    server.once('error', reject);
    server.listen(0, '127.0.0.1', () => {
      const { port } = server.address();
      server.close(() => resolve(port));
    });
  });
}

/** deploy/compose.yaml renamed `name`, scenario path absolute, each [from, to] replaced once. */
export function composeCopy(opts, name, replacements) {
  let text = readFileSync(join(opts.root, 'deploy', 'compose.yaml'), 'utf8');
  const all = [['scenario: scenarios/', `scenario: ${opts.root}/deploy/scenarios/`], ...replacements];
  text = text.replace(/^name: .*$/m, `name: ${name}`);
  for (const [from, to] of all) {
    if (!text.includes(from)) throw new Error(`'${from}' is not in deploy/compose.yaml`);
    text = text.replace(from, to);
  }
  mkdirSync(opts.runs, { recursive: true });
  const file = join(opts.runs, `compose.${name}.yaml`);
  writeFileSync(file, text);
  return file;
}

/** A child process whose output lines can be awaited (and are kept in `log`). */
export class Child {
  constructor(argv, logFile) {
    this.lines = [];
    this.waiters = [];
    this.logFile = logFile;
    this.process = spawn(argv[0], argv.slice(1), { stdio: ['ignore', 'pipe', 'pipe'] });
    this.exited = new Promise((resolve) => this.process.on('exit', (code, signal) => resolve(code ?? 128 + (signal ? 15 : 0))));
    let rest = '';
    const onData = (chunk) => {
      rest += chunk.toString();
      const parts = rest.split('\n');
      rest = parts.pop();
      for (const line of parts) this.onLine(line);
    };
    this.process.stdout.on('data', onData);
    this.process.stderr.on('data', onData);
    this.exited.then(() => this.flush());
  }

  onLine(line) {
    this.lines.push(line);
    this.waiters = this.waiters.filter(({ pattern, resolve }) => {
      const match = line.match(pattern);
      if (match) resolve(match);
      return !match;
    });
  }

  flush() {
    if (this.logFile) writeFileSync(this.logFile, this.lines.join('\n') + '\n');
  }

  /** The first output line (earlier or later) that matches `pattern`; rejects after timeout_s or at exit. */
  waitForLine(pattern, timeout_s = 120) {
    for (const line of this.lines) {
      const match = line.match(pattern);
      if (match) return Promise.resolve(match);
    }
    return new Promise((resolve, reject) => {
      const timer = setTimeout(() => reject(new Error(`no output line matching ${pattern} within ${timeout_s} s`)), timeout_s * 1000);
      this.waiters.push({ pattern, resolve: (m) => { clearTimeout(timer); resolve(m); } });
      this.exited.then((code) => { clearTimeout(timer); reject(new Error(`exited (${code}) before a line matching ${pattern}`)); });
    });
  }

  kill() {
    if (this.process.exitCode === null) this.process.kill('SIGTERM');
  }
}

/** trace.csv as {columns, rows (arrays of numbers), text cells (for exact comparison)}. */
export function readTrace(file) {
  const lines = readFileSync(file, 'utf8').trim().split('\n');
  const columns = lines[0].split(',');
  const cells = lines.slice(1).map((line) => line.split(','));
  return { columns, cells, column: (name) => cells.map((row) => Number(row[columns.indexOf(name)])) };
}

/** Failures collected by check(); report() prints them and sets the exit code. */
export class Checks {
  constructor(name) {
    this.name = name;
    this.failures = [];
    this.passed = 0;
  }

  check(ok, what) {
    if (ok) {
      this.passed += 1;
      console.log(`  ok: ${what}`);
    } else {
      this.failures.push(what);
      console.log(`  FAILED: ${what}`);
    }
    return ok;
  }

  report() {
    console.log(`${this.name}: ${this.passed} passed, ${this.failures.length} failed`);
    for (const failure of this.failures) console.log(`  FAILED: ${failure}`);
    return this.failures.length === 0 ? 0 : 1;
  }
}

export function freshDir(dir) {
  rmSync(dir, { recursive: true, force: true });
  return dir;
}
