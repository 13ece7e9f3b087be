// Colour scales of the 3D view and the sealing panel, with their legends.

// Piecewise-linear scales: [position, r, g, b] with components 0..1.
const SUCTION = [[0, 0.95, 0.95, 0.95], [0.25, 0.55, 0.8, 0.95], [0.5, 0.2, 0.5, 0.9], [0.75, 0.3, 0.2, 0.7], [1, 0.25, 0.0, 0.35]];
const GAP = [[0, 0.2, 0.75, 0.3], [0.35, 0.95, 0.85, 0.2], [0.7, 0.95, 0.45, 0.1], [1, 0.9, 0.1, 0.1]];
const HEIGHT = [[0, 0.1, 0.1, 0.35], [0.35, 0.35, 0.35, 0.45], [0.5, 0.6, 0.6, 0.58], [0.65, 0.75, 0.72, 0.62], [1, 0.98, 0.95, 0.85]];

function sample(scale, x) {
  const v = Math.min(1, Math.max(0, Number.isFinite(x) ? x : 0));
  for (let i = 1; i < scale.length; ++i) {
    if (v <= scale[i][0]) {
      const [a, b] = [scale[i - 1], scale[i]];
      const f = (v - a[0]) / (b[0] - a[0]);
      return [a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2]), a[3] + f * (b[3] - a[3])];
    }
  }
  const last = scale[scale.length - 1];
  return [last[1], last[2], last[3]];
}

/** Chamber colour for suction (p_o - p) over [0, max] Pa. */
export const suctionColor = (suction_pa, max_pa) => sample(SUCTION, suction_pa / max_pa);
/** Sealing colour for an effective gap (leak area / length) over [0, max] m. */
export const gapColor = (gap_m, max_m) => sample(GAP, Math.sqrt(Math.max(0, gap_m) / max_m));
/** Wall colour for a height over [-range, range] m. */
export const heightColor = (h_m, range_m) => sample(HEIGHT, 0.5 + 0.5 * h_m / range_m);

/** Draws a scale (f: x in 0..1 -> rgb) into a legend canvas. */
export function drawLegend(canvas, f) {
  const ctx = canvas.getContext('2d');
  for (let x = 0; x < canvas.width; ++x) {
    const [r, g, b] = f(x / (canvas.width - 1));
    ctx.fillStyle = `rgb(${r * 255 | 0},${g * 255 | 0},${b * 255 | 0})`;
    ctx.fillRect(x, 0, 1, canvas.height);
  }
}

export const scales = { suction: (x) => sample(SUCTION, x), gap: (x) => sample(GAP, Math.sqrt(x)), height: (x) => sample(HEIGHT, x) };
