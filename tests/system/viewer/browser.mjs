// Headless Chromium (Debian's `chromium`) driven by puppeteer-core, for the viewer's tests and
// for attaching a browser to a running viewer (attach_browser.mjs).
import { CHROMIUM_FLAGS, imageStats, loadPuppeteer } from '../../../services/viewer/web/headless.mjs';

export { CHROMIUM_FLAGS, imageStats, loadPuppeteer };

/**
 * Starts chromium and opens `url` in a page of `width` x `height`; console errors and page
 * errors are collected in page.errors (the dbus lines chromium prints go to its stderr, not here).
 */
export async function openPage(puppeteer, url, { executable = process.env.CLIMBSIM_CHROMIUM || '/usr/bin/chromium', width = 1400, height = 860 } = {}) {
  const browser = await puppeteer.launch({ executablePath: executable, headless: true, args: CHROMIUM_FLAGS,
    defaultViewport: { width, height } });
  const page = await browser.newPage();
  page.errors = [];
  page.on('console', (message) => {
    if (message.type() === 'error') page.errors.push(`console: ${message.text()}`);
  });
  page.on('pageerror', (error) => page.errors.push(`page: ${error.message}`));
  // A request the page itself cancelled (an image whose src a newer picture replaced before it
  // loaded: net::ERR_ABORTED) is not an error; any other failure is.
  page.on('requestfailed', (request) => {
    const why = request.failure()?.errorText;
    if (why !== 'net::ERR_ABORTED') page.errors.push(`request failed: ${request.url()} ${why}`);
  });
  await page.goto(url, { waitUntil: 'load' });
  return { browser, page };
}


/**
 * Mean absolute difference of two PNG pictures' grey values (0..255), the second scaled to the
 * first's size (the 3D view's resolution follows its render cost: two pictures of it may differ
 * in pixels but not in what they show).
 */
export async function imageDifference(page, a, b) {
  return page.evaluate(async (srcA, srcB) => {
    const decode = async (src) => {
      const img = new Image();
      img.src = src;
      await img.decode();
      return img;
    };
    const [imgA, imgB] = [await decode(srcA), await decode(srcB)];
    const pixels = (img) => {
      const canvas = document.createElement('canvas');
      canvas.width = imgA.width;
      canvas.height = imgA.height;
      canvas.getContext('2d').drawImage(img, 0, 0, imgA.width, imgA.height);
      return canvas.getContext('2d').getImageData(0, 0, imgA.width, imgA.height).data;
    };
    const [da, db] = [pixels(imgA), pixels(imgB)];
    let sum = 0;
    for (let i = 0; i < da.length; i += 4) sum += Math.abs((da[i] + da[i + 1] + da[i + 2]) - (db[i] + db[i + 1] + db[i + 2])) / 3;
    return sum / (da.length / 4);
  }, `data:image/png;base64,${Buffer.from(a).toString("base64")}`, `data:image/png;base64,${Buffer.from(b).toString("base64")}`);
}

/**
 * Clicks a button through the DOM (its click handler runs at once). Mouse input through the
 * browser's input pipeline waits for rendered frames, which software WebGL on a loaded machine
 * makes slow; the handler is the same.
 */
export function click(page, selector) {
  return page.$eval(selector, (el) => el.click());
}

/**
 * The 3D view's picture as the first render after render number `since` drew it with the robot
 * at least `minMove` metres from `from` (a position [x, y, z] in the wall frame; no condition
 * without it): {render, position, png (a PNG Buffer)}. The pixels are read from the canvas's
 * preserved drawing buffer in the same task as the record of what it shows (Scene3D.drawn), so
 * the picture is that render's however slowly the page renders: no screenshot of a canvas the
 * compositor may not have updated yet, no wait for a quiet machine.
 */
export async function drawnCanvas(page, { since = 0, from = null, minMove = 0, timeout = 120000 } = {}) {
  // Polled: a render changes no DOM node, so mutation polling would not see it.
  const handle = await page.waitForFunction((after, origin, distance) => {
    const scene = window.climbsimViewer.scene;
    const drawn = scene?.drawn;
    if (!drawn || drawn.render <= after) return false;
    if (origin && Math.hypot(...drawn.position.map((v, i) => v - origin[i])) < distance) return false;
    return { render: drawn.render, position: drawn.position, png: scene.renderer.domElement.toDataURL('image/png') };
  }, { timeout, polling: 100 }, since, from, minMove)
    .catch((error) => {
      throw new Error(`${error.message}, waiting for a render after render ${since}` +
        (from ? ` with the robot ${minMove} m from [${from.map((v) => v.toFixed(3)).join(', ')}]` : ''));
    });
  const value = await handle.jsonValue();
  await handle.dispose();
  return { render: value.render, position: value.position, png: Buffer.from(value.png.split(',')[1], 'base64') };
}
