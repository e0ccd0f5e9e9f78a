// `nodus view`'s pages in a real browser: Debian's Chromium, headless, driven by playwright-core (which never
// downloads a browser of its own). For each page written by test_view's ViewPages.Write it checks that the page
// loads without a console error, draws something (pixels other than the background), draws something else
// when the step slider moves, and reads a fibre node and a contact element when they are clicked; it switches
// to a branch and colours by a measure, and saves screenshots as artefacts.
//
//   node tests/view/browser_test.mjs PAGES_DIR WEB_DIR SCREENSHOT_DIR [NAME ...]
//
// PAGES_DIR holds small.html, contact.html (and big.html, when written) and the example pages, or the pages
// NAME.html named; WEB_DIR is web/, whose node_modules has playwright-core. Prints each page's size and load time; exits 1 on the first failure.

import { createRequire } from 'node:module';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [pagesDir, webDir, shotsDir, ...named] = process.argv.slice(2);
if (!shotsDir) {
  console.error('usage: node browser_test.mjs PAGES_DIR WEB_DIR SCREENSHOT_DIR [NAME ...]  (NAME.html in PAGES_DIR)');
  process.exit(2);
}
const require = createRequire(path.join(path.resolve(webDir), 'package.json'));
const { chromium } = require('playwright-core');

const BACKGROUND = [0xf4, 0xf5, 0xf7];
const VIEWPORT = { width: 1000, height: 700 };
let failures = 0;
function check(condition, message) {
  if (!condition) {
    failures++;
    console.error(`FAIL: ${message}`);
  } else {
    console.log(`ok: ${message}`);
  }
}

/// In a blank page: pixels of PNG `a` that differ from the background, and pixels that differ from PNG `b`.
async function pixelStats(blank, a, b = null) {
  return blank.evaluate(async ([a64, b64, bg]) => {
    const load = async (data) => {
      const img = new Image();
      img.src = `data:image/png;base64,${data}`;
      await img.decode();
      const canvas = document.createElement('canvas');
      canvas.width = img.width;
      canvas.height = img.height;
      const ctx = canvas.getContext('2d');
      ctx.drawImage(img, 0, 0);
      return ctx.getImageData(0, 0, img.width, img.height).data;
    };
    const pa = await load(a64);
    const pb = b64 ? await load(b64) : null;
    let drawn = 0, changed = 0;
    for (let i = 0; i < pa.length; i += 4) {
      if (Math.abs(pa[i] - bg[0]) + Math.abs(pa[i + 1] - bg[1]) + Math.abs(pa[i + 2] - bg[2]) > 24) drawn++;
      if (pb && Math.abs(pa[i] - pb[i]) + Math.abs(pa[i + 1] - pb[i + 1]) + Math.abs(pa[i + 2] - pb[i + 2]) > 24) changed++;
    }
    return { drawn, changed, total: pa.length / 4 };
  }, [a.toString('base64'), b ? b.toString('base64') : null, BACKGROUND]);
}

async function testPage(context, blank, name) {
  const file = path.join(pagesDir, `${name}.html`);
  if (!fs.existsSync(file)) return name === 'big' ? null : check(false, `${file} exists`);
  const bytes = fs.statSync(file).size;
  const page = await context.newPage();
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  const requests = [];
  page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('data:')) requests.push(r.url()); });

  const start = Date.now();
  await page.goto(pathToFileURL(file).href, { timeout: 120000 });
  await page.waitForFunction(() => document.body && document.body.dataset.ready === 'true', null, { timeout: 120000 });
  const loadSeconds = (Date.now() - start) / 1000;
  console.log(`${name}.html: ${(bytes / 1e6).toFixed(2)} MB, loaded and drawn in ${loadSeconds.toFixed(2)} s`);
  const canvas = page.locator('#nodus-viewport canvas');

  const info = await page.evaluate(() => ({
    runs: window.nodusView.runCount, states: window.nodusView.stateCount, index: window.nodusView.stateIndex,
    contacts: window.nodusView.contactCount,
  }));
  check(info.states > 1 && info.index === info.states - 1, `${name}: shows the last of its ${info.states} states`);
  const last = await canvas.screenshot();
  fs.writeFileSync(path.join(shotsDir, `${name}_last.png`), last);
  const drawn = await pixelStats(blank, last);
  check(drawn.drawn > 0.01 * drawn.total, `${name}: the canvas is drawn (${drawn.drawn} of ${drawn.total} pixels not background)`);

  // The slider, moved by the keyboard as a user would: Home goes to the first state.
  await page.focus('#nodus-slider');
  await page.keyboard.press('Home');
  await page.waitForFunction(() => window.nodusView.stateIndex === 0);
  await page.evaluate(() => window.nodusView.render());
  const first = await canvas.screenshot();
  fs.writeFileSync(path.join(shotsDir, `${name}_first.png`), first);
  // A run may end where it started (a beam bent and released comes back straight): the middle state counts too.
  const middleIndex = Math.floor((await page.evaluate(() => window.nodusView.stateCount)) / 2);
  await page.evaluate((i) => window.nodusView.setState(i), middleIndex);
  await page.evaluate(() => window.nodusView.render());
  const middle = await canvas.screenshot();
  await page.keyboard.press('Home');
  await page.waitForFunction(() => window.nodusView.stateIndex === 0);
  await page.evaluate(() => window.nodusView.render());
  const fromLast = await pixelStats(blank, first, last);
  const fromMiddle = await pixelStats(blank, first, middle);
  const changed = Math.max(fromLast.changed, fromMiddle.changed);
  check(changed > 0.002 * fromLast.total,
        `${name}: moving the slider changes the picture (${fromLast.changed} pixels from the last state, ` +
        `${fromMiddle.changed} from the middle one)`);
  const label = await page.textContent('#nodus-step');
  check(/^state 1\//.test(label), `${name}: the step label follows the slider ("${label}")`);
  await page.keyboard.press('End');
  // Frame the fibres of the drawn state: still drawn.
  await page.click('#nodus-frame');
  await page.evaluate(() => window.nodusView.render());
  const framed = await pixelStats(blank, await canvas.screenshot());
  check(framed.drawn > 0.01 * framed.total, `${name}: framed on its fibres (${framed.drawn} pixels drawn)`);

  // Pick the middle node of the first fibre.
  const [x, y] = await page.evaluate(() => window.nodusView.screenPointOfNode(0, 10));
  await page.mouse.click(x, y);
  const pickKind = await page.getAttribute('#nodus-pick', 'data-kind');
  const pickText = await page.textContent('#nodus-pick');
  check(pickKind === 'beam' && /fibre/.test(pickText), `${name}: clicking a fibre reads its node ("${pickText.slice(0, 60)}")`);

  // Colour by axial strain: the legend says so with its unit.
  await page.selectOption('#nodus-color', 'e33');
  await page.evaluate(() => window.nodusView.render());
  const legend = await page.textContent('#nodus-legend');
  check(/axial strain e33 \[-\]/.test(legend), `${name}: colouring by e33 shows its legend`);
  fs.writeFileSync(path.join(shotsDir, `${name}_e33.png`), await canvas.screenshot());

  if (info.contacts > 0) {
    await page.check('#nodus-see-through');
    const [cx, cy] = await page.evaluate(() => window.nodusView.screenPointOfContact(0));
    await page.mouse.click(cx, cy);
    const kind = await page.getAttribute('#nodus-pick', 'data-kind');
    const text = await page.textContent('#nodus-pick');
    check(kind === 'contact' && /normal force/.test(text), `${name}: clicking a contact element reads it ("${text.slice(0, 60)}")`);
    await page.selectOption('#nodus-contact-color', 'state');
    check(/stick.*slip.*open/.test(await page.textContent('#nodus-legend')), `${name}: contact states in the legend`);
  }
  if (info.runs > 1) {
    await page.selectOption('#nodus-run', '1');
    const branch = await page.evaluate(() => ({ states: window.nodusView.stateCount, index: window.nodusView.stateIndex }));
    const marks = await page.textContent('#nodus-stages');
    check(branch.states > 1 && marks.includes('release'), `${name}: the branch selector shows the branch (${branch.states} states, stages "${marks}")`);
    await page.evaluate(() => window.nodusView.render());
    fs.writeFileSync(path.join(shotsDir, `${name}_branch.png`), await page.screenshot());
  }
  // Play through every state to the end (on small pages; on a big one, the time a state takes to draw).
  if (info.runs > 1) await page.selectOption('#nodus-run', '0');
  if (info.states <= 40) {
    await page.focus('#nodus-slider');
    await page.keyboard.press('Home');
    const playStart = Date.now();
    await page.click('#nodus-play');
    await page.waitForFunction(() => window.nodusView.stateIndex === window.nodusView.stateCount - 1, null, { timeout: 120000 });
    console.log(`${name}.html: played ${info.states} states in ${((Date.now() - playStart) / 1000).toFixed(2)} s`);
  }
  const perState = await page.evaluate(() => window.nodusView.timeStates(5));
  console.log(`${name}.html: ${perState.toFixed(0)} ms to draw a state (software WebGL)`);
  fs.writeFileSync(path.join(shotsDir, `${name}.png`), await page.screenshot());

  check(errors.length === 0, `${name}: no console error${errors.length ? `: ${errors.join(' | ')}` : ''}`);
  check(requests.length === 0, `${name}: no network request${requests.length ? `: ${requests.join(' ')}` : ''}`);
  await page.close();
  return { bytes, loadSeconds };
}

const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'nodus-chromium-'));
fs.mkdirSync(shotsDir, { recursive: true });
// A fresh profile (--user-data-dir, which playwright passes for a persistent context), removed afterwards.
const context = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.NODUS_CHROMIUM || '/usr/bin/chromium',
  headless: true,
  viewport: VIEWPORT,
  args: [
    '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync',
    '--enable-unsafe-swiftshader',  // WebGL on the CPU (SwiftShader), the only GL without a GPU
  ],
});
try {
  const blank = await context.newPage();
  const names = named.length > 0 ? named : ['small', 'contact', 'big', 'example_bend_and_release', 'example_tool_drag'];
  for (const name of names) await testPage(context, blank, name);
} finally {
  await context.close();
  fs.rmSync(profile, { recursive: true, force: true });
}
if (failures) {
  console.error(`${failures} check(s) failed`);
  process.exit(1);
}
