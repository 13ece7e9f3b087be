// Dynamic resolution of the 3D view. On a machine without a GPU, WebGL runs in software
// (SwiftShader), where a render and the read-back that puts it on the page cost in proportion
// to the canvas's pixels: a full-size view took 50-60 ms a render on a loaded 2-core machine,
// a view at half the resolution a quarter of that. A render slower than SLOW_MS lowers the
// resolution a step, one faster than FAST_MS raises it back (a GPU stays at full resolution).

const SLOW_MS = 20;     // mean render time above which the resolution goes down a step
const FAST_MS = 6;      // and below which it goes back up (a step changes the cost about 1.8x)
const STEP = 0.75;      // pixel ratio factor of one step
const MIN_SCALE = 0.5;  // never below half the resolution
const SAMPLES = 3;      // renders at a resolution before it is judged

export class RenderScale {
  /** `max`: the pixel ratio with cheap renders (1: one canvas pixel per CSS pixel). */
  constructor(max = 1) {
    this.max = max;
    this.scale = max;
    this.reset();
  }

  reset() {
    this.costMs = 0;
    this.count = 0;
  }

  /** Adds the time of one render [ms]; returns true if the pixel ratio `scale` changed. */
  add(ms) {
    this.count += 1;
    this.costMs = this.count === 1 ? ms : this.costMs * 0.7 + ms * 0.3;
    if (this.count < SAMPLES) return false;
    const old = this.scale;
    if (this.costMs > SLOW_MS) this.scale = Math.max(MIN_SCALE, this.scale * STEP);
    else if (this.costMs < FAST_MS) this.scale = Math.min(this.max, this.scale / STEP);
    if (this.scale === old) return false;
    this.reset();
    return true;
  }
}
