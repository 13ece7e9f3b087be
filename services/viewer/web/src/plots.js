// Live plots (uPlot): F with its set-point, P_F, pressures, valves, wheel loads and slip.
// Columns are appended as samples come (live) or set at once (replay); the x range is a rolling
// window ending at the latest time, or the whole run.
import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import { frameClock } from './frame_clock.js';

const PLOT_FPS = 5;  // most redraws per second of the plots (each redraws the ones on screen)
const PLOT_BUDGET = 0.05;  // share of one core the redraws may take (slower redraws: fewer of them)
const PALETTE = ['#e6194b', '#3cb44b', '#ffe119', '#4363d8', '#f58231', '#911eb4', '#46f0f0', '#f0f0f0'];

// A colour per chamber or wheel; beyond the palette, hues around the circle.
function colour(i) {
  return i < PALETTE.length ? PALETTE[i] : `hsl(${(i * 137.5) % 360}, 80%, 60%)`;
}

// Each plot: title, its series (label and how a sample gives the value), y unit.
function plotSpecs(wheels, chambers, hasReservoir) {
  const range = (n) => [...Array(n).keys()];
  return [
    { title: 'downforce F [N]', series: [
      { label: 'F', value: (s) => s.F, color: '#ff5a4f' },
      { label: 'set-point', value: (s) => s.setpoint, color: '#999', dash: [6, 4] }] },
    { title: 'P_F in the robot frame [mm]', series: [
      { label: 'x', value: (s) => s.pfx * 1e3, color: '#4fd8ff' },
      { label: 'y', value: (s) => s.pfy * 1e3, color: '#ffd84a' }] },
    { title: 'pressures [kPa]', series: [
      ...range(chambers).map((i) => ({ label: `p${i + 1}`, value: (s) => s.pressures?.[i] * 1e-3, color: colour(i) })),
      ...(hasReservoir ? [{ label: 'pR', value: (s) => s.pressures?.[chambers] * 1e-3, color: '#ffffff', dash: [3, 3] }] : [])] },
    ...(hasReservoir ? [{ title: 'valve openings [0..1]', series:
      range(chambers).map((i) => ({ label: `v${i + 1}`, value: (s) => s.valves?.[i], color: colour(i) })) }] : []),
    { title: 'wheel normal loads [N]', series:
      range(wheels).map((i) => ({ label: `wheel ${i + 1}`, value: (s) => s.normal?.[i], color: colour(i * 2) })) },
    { title: 'wheel slip [m/s]', series:
      range(wheels).map((i) => ({ label: `wheel ${i + 1}`, value: (s) => s.slip?.[i], color: colour(i * 2) })) },
  ];
}

export class Plots {
  /** wheels, chambers: the robot's counts; hasReservoir: pR and the valves are plotted. */
  constructor(container, wheels, chambers = 7, hasReservoir = true) {
    this.container = container;
    this.specs = plotSpecs(wheels, chambers, hasReservoir);
    this.columns = this.specs.map((spec) => [[], ...spec.series.map(() => [])]);
    this.windowS = 30;
    this.cursorT = null;
    this.last = null;
    this.plots = this.specs.map((spec, k) => new uPlot({
      title: spec.title,
      width: 400,
      height: 150,
      scales: { x: { time: false } },
      axes: [{ stroke: '#9aa6b2', grid: { stroke: '#2b323c' }, values: tickLabels },
        { stroke: '#9aa6b2', grid: { stroke: '#2b323c' }, size: 55, values: tickLabels }],
      series: [{ label: 't [s]' }, ...spec.series.map((s) => ({ label: s.label, stroke: s.color, width: 1.2, dash: s.dash }))],
      legend: { live: true },
    }, this.columns[k], container));
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
    // Only the plots on screen are redrawn (each redraw rasterises its canvas in software on a
    // machine without a GPU); one scrolled into view is drawn at once.
    this.visible = this.plots.map(() => true);
    const seen = new IntersectionObserver((entries) => {
      for (const entry of entries) {
        const k = this.plots.findIndex((plot) => plot.root === entry.target);
        if (k < 0) continue;
        this.visible[k] = entry.isIntersecting;
        if (entry.isIntersecting) this.schedule();
      }
    });
    for (const plot of this.plots) seen.observe(plot.root);
  }

  resize() {
    const width = Math.max(300, this.container.clientWidth - 4);
    for (const plot of this.plots) plot.setSize({ width, height: 150 });
  }

  /** Appends a sample {t, F, setpoint, pfx, pfy, pressures, valves, normal, slip} if it is newer. */
  push(sample) {
    if (this.last && sample.t <= this.last.t) return;
    this.specs.forEach((spec, k) => {
      const cols = this.columns[k];
      cols[0].push(sample.t);
      spec.series.forEach((s, i) => cols[i + 1].push(finite(s.value(sample))));
    });
    this.last = sample;
    this.schedule();
  }

  /** Replaces every column by `samples` (replay). */
  setAll(samples) {
    this.columns = this.specs.map((spec) => [samples.map((s) => s.t), ...spec.series.map((s) => samples.map((x) => finite(s.value(x))))]);
    this.last = samples.length ? samples[samples.length - 1] : null;
    this.schedule();
  }

  /** The x range ends at `t` (replay: the slider's time; live: the latest sample). */
  setCursor(t) {
    this.cursorT = t;
    this.schedule();
  }

  setWindow(seconds) {
    this.windowS = seconds;
    this.schedule();
  }

  /** Redraws in the page's next frame (frame_clock.js), at most PLOT_FPS times a second. */
  schedule() {
    frameClock.request('plots', () => this.draw(), { fps: PLOT_FPS, budget: PLOT_BUDGET });
  }

  draw() {
    const end = this.cursorT ?? this.last?.t ?? 1;
    const first = this.columns[0][0][0] ?? 0;
    const start = this.windowS > 0 ? Math.max(first, end - this.windowS) : first;
    this.plots.forEach((plot, k) => {
      if (!this.visible[k]) return;
      plot.setData(this.columns[k], false);
      plot.setScale('x', { min: start, max: Math.max(end, start + 1e-3) });
    });
  }
}

const finite = (v) => (Number.isFinite(v) ? v : null);

/** Tick labels with the fewest decimals that write every tick exactly (no two read the same). */
function tickLabels(u, splits) {
  const ticks = splits.filter((v) => v != null);
  const step = ticks.length > 1 ? Math.abs(ticks[1] - ticks[0]) : Math.abs(ticks[0] ?? 1) || 1;
  if (step < 1e-5) return splits.map((v) => (v == null ? '' : v.toExponential(1)));  // a range of rounding noise
  let decimals = 0;
  while (decimals < 6 && ticks.some((v) => Math.abs(v - Number(v.toFixed(decimals))) > step * 1e-6)) decimals += 1;
  return splits.map((v) => (v == null ? '' : v.toLocaleString('en-US', { minimumFractionDigits: decimals, maximumFractionDigits: decimals })));
}
