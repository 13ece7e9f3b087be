// The run panel (time, real-time factor, state, controls), the roster, the readouts under the
// 3D view and the sealing panel (depth image and sealing pictures).
import { heightColor } from './colors.js';
import { HEIGHT_RANGE_M } from './scene3d.js';

const $ = (id) => document.getElementById(id);

/** Text and exact value (data-value, for tests and copy) of a readout. */
function setValue(id, value, digits) {
  const el = $(id);
  if (!Number.isFinite(value)) {
    el.textContent = '–';
    el.dataset.value = '';
    return;
  }
  el.textContent = value.toFixed(digits);
  el.dataset.value = String(value);
}

export function showRun(run) {
  setValue('sim-time', run.t_s, 3);
  $('rtf-measured').textContent = Number.isFinite(run.rtf_measured) ? run.rtf_measured.toFixed(2) : '–';
  $('rtf-target').textContent = run.rtf_target === 0 ? 'as fast as possible' : `${run.rtf_target}x`;
  $('phase').textContent = run.phase;
  $('phase').dataset.value = run.phase;
  $('reason').textContent = run.reason ? `(${run.reason})` : '';
  const body = document.querySelector('#roster tbody');
  const rows = run.roster.map((m) => `<tr><td>${escape(m.name)}</td><td>${escape(m.host || '?')}</td><td>${m.period}/${m.offset}</td></tr>`).join('');
  if (body.dataset.rows !== rows) {
    body.innerHTML = rows;
    body.dataset.rows = rows;
  }
}

/** A replay's header: the playback speed (simulated s per wall s) in place of the real-time factor. */
export function showReplayRate(speed, playing) {
  $('rtf-live').hidden = true;
  $('replay-rate').hidden = false;
  // 2.0x, 10.0x; 0.25x with the decimals it has.
  const value = Number(speed);
  const text = `${Number.isInteger(value * 10) ? value.toFixed(1) : String(value)}x${playing ? '' : ', paused'}`;
  $('replay-rate-value').textContent = text;
  $('replay-rate-value').dataset.value = text;
}

export function showReadouts(sample) {
  setValue('readout-F', sample.F, 1);
  setValue('readout-pfx', sample.pfx * 1e3, 1);
  setValue('readout-pfy', sample.pfy * 1e3, 1);
  // The exact trace values, not the mm: tests compare them with trace.csv.
  $('readout-pfx').dataset.value = Number.isFinite(sample.pfx) ? String(sample.pfx) : '';
  $('readout-pfy').dataset.value = Number.isFinite(sample.pfy) ? String(sample.pfy) : '';
  setValue('readout-x', sample.pose?.position[0], 3);
  setValue('readout-y', sample.pose?.position[1], 3);
}

/** The depth grid in the sealing panel, grey by height over [-5, +5] mm. */
export function showDepth(depth) {
  const canvas = $('depth-canvas');
  const n = depth.size;
  if (canvas.width !== n) {
    canvas.width = n;
    canvas.height = n;
  }
  const ctx = canvas.getContext('2d');
  const image = ctx.createImageData(n, n);
  for (let i = 0; i < n * n; ++i) {
    const [r, g, b] = heightColor(depth.heights_mm[i] * 1e-3, HEIGHT_RANGE_M);
    image.data.set([r * 255, g * 255, b * 255, 255], 4 * i);
  }
  ctx.putImageData(image, 0, 0);
  $('depth-time').textContent = `(t ${depth.t_s.toFixed(2)} s)`;
}

/** A sealing picture (kind 'gaps' or 'edges') from `url`, taken at t_s. */
/** The sealing picture of `kind` from `url`, or none (null: hidden, e.g. a replay before the first). */
export function showSealingPicture(kind, url, t_s) {
  const img = $(`sealing-${kind}`);
  if ((img.dataset.url ?? '') === (url ?? '')) return;
  img.dataset.url = url ?? '';
  img.style.display = url ? '' : 'none';  // no broken-image icon (the page's CSS overrides hidden)
  if (url) img.src = url; else img.removeAttribute('src');
  if (kind === 'gaps') $('gaps-time').textContent = url && Number.isFinite(t_s) ? `(t ${t_s.toFixed(2)} s)` : '';
}

function escape(text) {
  return String(text).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);
}
