// Replay of a finished run: trace.csv as columns from the viewer, a time slider and play/pause
// at any speed. Everything happens in the page; the viewer only serves the files.

/** Samples (one per trace row) from {columns, values}, in the page's common shape. */
export function samplesFromTrace(trace, setpoint, segmentNames, wheels, chambers = 7, hasReservoir = true) {
  const col = (name) => {
    const i = trace.columns.indexOf(name);
    return i < 0 ? null : trace.values[i];
  };
  const t = col('t_s');
  const need = (name) => {
    const c = col(name);
    if (!c) throw new Error(`trace.csv has no column ${name}`);
    return c;
  };
  const F = need('downforce_n');
  const pfx = need('pf_x_m');
  const pfy = need('pf_y_m');
  // p1..pN, then pR; valves only with a reservoir (docs/robot-files.md).
  const p = [...Array(chambers).keys()].map((i) => need(`p${i + 1}_pa`)).concat(hasReservoir ? [need('pr_pa')] : []);
  const v = hasReservoir ? [...Array(chambers).keys()].map((i) => need(`valve${i + 1}`)) : [];
  const pos = ['x_m', 'y_m', 'z_m'].map(need);
  const rpy = ['roll_rad', 'pitch_rad', 'yaw_rad'].map(need);
  const normal = [...Array(wheels).keys()].map((i) => need(`wheel${i + 1}_normal_n`));
  const slip = [...Array(wheels).keys()].map((i) => need(`wheel${i + 1}_slip_mps`));
  // The set-point in force at each row, as the controller published it (0: none).
  const setpoints = col('downforce_setpoint_n');
  const leak = segmentNames.map((name) => [name, col(`leak_area_m2_${name}`)]).filter(([, c]) => c);
  const samples = new Array(t.length);
  for (let k = 0; k < t.length; ++k) {
    samples[k] = {
      t: t[k], row: k, F: F[k], setpoint: setpoints ? (setpoints[k] > 0 ? setpoints[k] : NaN) : setpoint, pfx: pfx[k], pfy: pfy[k],
      pressures: p.map((c) => c[k]), valves: v.map((c) => c[k]),
      normal: normal.map((c) => c[k]), slip: slip.map((c) => c[k]),
      pose: { position: pos.map((c) => c[k]), rpy: rpy.map((c) => c[k]) },
      leak: Object.fromEntries(leak.map(([name, c]) => [name, c[k]])),
    };
  }
  return samples;
}

/** Index of the last sample with t <= time (0 if none). */
export function indexAt(samples, time) {
  let lo = 0;
  let hi = samples.length - 1;
  if (hi < 0 || time < samples[0].t) return 0;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (samples[mid].t <= time) lo = mid; else hi = mid - 1;
  }
  return lo;
}

/** Plays and seeks: calls show(index) when the time changes. */
export class ReplayClock {
  constructor(samples, show) {
    this.samples = samples;
    this.show = show;
    this.time = samples.length ? samples[0].t : 0;
    this.end = samples.length ? samples[samples.length - 1].t : 0;
    this.speed = 1;
    this.playing = false;
  }

  seek(time) {
    this.time = Math.min(this.end, Math.max(0, time));
    this.show(indexAt(this.samples, this.time), this.time);
  }

  play() {
    if (this.time >= this.end) this.time = 0;
    this.playing = true;
    let last = performance.now();
    const tick = (now) => {
      if (!this.playing) return;
      this.seek(this.time + ((now - last) / 1000) * this.speed);
      last = now;
      if (this.time >= this.end) this.playing = false; else requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }

  pause() {
    this.playing = false;
  }
}
