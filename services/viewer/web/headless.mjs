// Headless Chromium (Debian's `chromium`) driven by puppeteer-core from the build's node_modules:
// for `view RUN_DIR --snapshot` (snapshot.mjs) and the viewer's browser tests.
import { createRequire } from 'node:module';
import { join, resolve } from 'node:path';

/** Loads puppeteer-core from the build's node_modules (npm ci at build time). */
export async function loadPuppeteer(nodeModules) {
  const require = createRequire(join(resolve(nodeModules), 'noop.js'));
  return require('puppeteer-core');
}

// No GPU here: WebGL runs on SwiftShader. Compositing and 2D canvases (the plots) stay on the
// CPU rasteriser: through SwiftShader they cost a page watching a run 0.9 of a core instead of
// 0.2 (measured with the page's features switched off in turn).
export const CHROMIUM_FLAGS = ['--headless', '--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
  '--disable-gpu-sandbox', '--disable-gpu-compositing', '--disable-accelerated-2d-canvas', '--no-first-run',
  '--no-default-browser-check', '--disable-dev-shm-usage'];

/** Variance of the grey values of a PNG screenshot's pixels, read back in the page itself. */
export async function imageStats(page, pngBuffer) {
  const dataUrl = `data:image/png;base64,${Buffer.from(pngBuffer).toString("base64")}`;
  return page.evaluate(async (src) => {
    const img = new Image();
    img.src = src;
    await img.decode();
    const canvas = document.createElement('canvas');
    canvas.width = img.width;
    canvas.height = img.height;
    const ctx = canvas.getContext('2d');
    ctx.drawImage(img, 0, 0);
    const data = ctx.getImageData(0, 0, img.width, img.height).data;
    let sum = 0;
    let sum2 = 0;
    const n = data.length / 4;
    for (let i = 0; i < data.length; i += 4) {
      const grey = (data[i] + data[i + 1] + data[i + 2]) / 3;
      sum += grey;
      sum2 += grey * grey;
    }
    const mean = sum / n;
    return { mean, variance: sum2 / n - mean * mean, width: img.width, height: img.height };
  }, dataUrl);
}
