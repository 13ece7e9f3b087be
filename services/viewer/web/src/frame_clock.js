// One clock for everything the page draws (3D view, plots, panels): each part asks to be
// drawn, and the parts that are due run together in one animation frame. Every animation
// frame makes Chromium lay out, paint and composite the page (in software on a machine without
// a GPU, several ms each), so parts drawn in frames of their own would cost that several times
// over. Each part has its own pace: at most `fps` draws a second, and fewer when a draw costs
// more than `budget` of one core (its measured draw time / budget between two draws).

const ALIGN_MS = 60;  // a part due within this much of a frame is drawn in it

export class FrameClock {
  constructor() {
    this.parts = new Map();
    this.timer = null;
    this.frames = 0;  // animation frames the clock asked for (tests, diagnostics)
  }

  /** Asks for `draw` of part `key` in a coming frame, no sooner than its pace allows. */
  request(key, draw, { fps, budget }) {
    const part = this.parts.get(key) ?? { costMs: undefined, last: -1e9 };
    Object.assign(part, { draw, fps, budget, pending: true });
    this.parts.set(key, part);
    this.schedule();
  }

  /** When part may next be drawn [ms, performance.now() time]. */
  static due(part) {
    return part.last + Math.max(1000 / part.fps, (part.costMs ?? 0) / part.budget);
  }

  schedule() {
    if (this.timer !== null) return;
    let next = Infinity;
    for (const part of this.parts.values()) if (part.pending) next = Math.min(next, FrameClock.due(part));
    if (next === Infinity) return;
    // A timer, then one animation frame: a chain of animation frames while waiting would make
    // Chromium produce a frame 60 times a second.
    this.timer = setTimeout(() => requestAnimationFrame(() => this.frame()), Math.max(0, next - performance.now()));
  }

  frame() {
    this.timer = null;
    this.frames += 1;
    const now = performance.now();
    for (const part of this.parts.values()) {
      if (!part.pending || FrameClock.due(part) > now + ALIGN_MS) continue;
      part.pending = false;
      const start = performance.now();
      part.draw();
      const ms = performance.now() - start;
      part.last = start;
      part.costMs = part.costMs === undefined ? ms : part.costMs * 0.8 + ms * 0.2;
    }
    this.schedule();
  }
}

/** The page's one clock. */
export const frameClock = new FrameClock();
