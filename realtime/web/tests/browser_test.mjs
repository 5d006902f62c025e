// The headless browser test of `tmlab realtime --serve` (docs/realtime.md), run by
// apps/tmlab/tests/test_cli_realtime_serve.cpp (ctest label `browser`) against a running server:
//   node browser_test.mjs URL SCREENSHOT.png NPM_DIR CHROMIUM
// Debian's Chromium, driven by playwright-core (npm, installed at set-up in NPM_DIR): the page
// loads, frames arrive, the probe dragged with the mouse 15 mm into the liver makes the reported
// force grow; the screenshot is taken while the probe is held in. Then depth: R puts the probe back
// (the force returns to 0), the wheel turned forward while the probe is held presses it into the
// liver along the view direction (the force grows again; second screenshot, NAME_depth.png), and
// Shift+wheel backward pulls it out (the force returns to 0). Prints one JSON line with the
// measurements; exit status 1 with the reason on any failure.
import { pathToFileURL } from 'node:url';
import path from 'node:path';

const [url, screenshot, npmDir, chromiumPath] = process.argv.slice(2);
if (!url || !screenshot || !npmDir || !chromiumPath) {
  console.error('usage: node browser_test.mjs URL SCREENSHOT.png NPM_DIR CHROMIUM');
  process.exit(2);
}
const { chromium } = await import(pathToFileURL(path.join(npmDir, 'node_modules', 'playwright-core', 'index.mjs')).href);

const timeout = 180_000;  // a busy machine: bounds a hang, asserts no speed
const norm = (v) => Math.hypot(v[0], v[1], v[2]);
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

/// Waits until the force the page shows is (nearly) zero with the probe back at its start.
async function probeBackAtStart(page) {
  await page.waitForFunction(() => {
    const s = window.tmlab, d = s.probe.map((v, i) => v - s.hello.probe[i]);
    return Math.hypot(...s.force) < 0.01 && Math.hypot(...d) < 1e-4;
  }, null, { timeout, polling: 50 });
}

/// The depth controls: R, the wheel during a drag (in), Shift+wheel (out). Throws on a failure.
async function pressInDepth(page, shot) {
  const notches = 8;
  await page.keyboard.press('r');
  await probeBackAtStart(page);
  const start = await page.evaluate(() => ({ p: window.tmlab.probe, r: window.tmlab.hello.probe_radius,
                                             dir: window.tmlab.viewDirection(), s: window.tmlab.probeScreen() }));
  // Hold the probe without moving the mouse and turn the wheel forward: only the depth changes.
  await page.mouse.move(start.s.x, start.s.y);
  await page.mouse.down();
  for (let i = 0; i < notches; ++i) {
    await page.mouse.wheel(0, -100);
    await page.waitForTimeout(40);
  }
  // Until the frames show the probe at the target the page asked for, pressing the liver.
  await page.waitForFunction(() => {
    const s = window.tmlab, d = s.probe.map((v, i) => v - s.target[i]);
    return Math.hypot(...s.force) > 0.05 && Math.hypot(...d) < 1e-5;
  }, null, { timeout, polling: 50 });
  const held = await page.evaluate(() => ({ f: window.tmlab.force, p: window.tmlab.probe, target: window.tmlab.target }));
  await page.screenshot({ path: shot });
  await page.mouse.up();
  // The target went a tenth of the probe radius per notch along the view direction, and the probe
  // the page is shown (from the server's frames) with it.
  const moved = sub(held.target, start.p), along = dot(moved, start.dir);
  const expected = notches * 0.1 * start.r;
  if (Math.abs(along - expected) > 1e-6 || norm(sub(moved, start.dir.map((v) => along * v))) > 1e-6)
    throw new Error(`wheel: target moved ${JSON.stringify(moved)}, not ${expected} m along ${JSON.stringify(start.dir)}`);
  // Shift+wheel backward, mouse released: the probe comes back out and the force returns to 0.
  await page.keyboard.down('Shift');
  for (let i = 0; i < notches; ++i) {
    await page.mouse.wheel(0, 100);
    await page.waitForTimeout(40);
  }
  await page.keyboard.up('Shift');
  await probeBackAtStart(page);
  return { notches, along_view_m: along, force_pressed_N: norm(held.f), force_pressed: held.f, probe_pressed: held.p,
           view_direction: start.dir, screenshot: shot };
}
const browser = await chromium.launch({
  executablePath: chromiumPath,
  headless: true,
  // WebGL through SwiftShader (no GPU in a headless test); no sandbox when run as root.
  args: ['--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--ignore-gpu-blocklist',
         ...(process.getuid && process.getuid() === 0 ? ['--no-sandbox'] : [])],
});
let result = {};
try {
  const page = await browser.newPage({ viewport: { width: 1000, height: 720 } });
  const consoleErrors = [];
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(String(e)));
  await page.goto(url, { timeout });
  await page.waitForFunction(() => window.tmlab && (window.tmlab.error || (window.tmlab.frames >= 10 && window.tmlab.rendered > 0)),
                             null, { timeout });
  const error = await page.evaluate(() => window.tmlab.error);
  if (error) throw new Error(`the page reports: ${error}`);

  // Frames per second the page receives (over 3 s of wall time).
  const a = await page.evaluate(() => ({ n: window.tmlab.frames, t: performance.now() }));
  await page.waitForTimeout(3000);
  const b = await page.evaluate(() => ({ n: window.tmlab.frames, t: performance.now(), f: window.tmlab.force,
                                         p: window.tmlab.probe }));
  const fps = (1000 * (b.n - a.n)) / (b.t - a.t);
  const before = norm(b.f);

  // Drag the probe: from its centre on the screen to the screen point 15 mm below it, in steps.
  const from = await page.evaluate(() => window.tmlab.probeScreen());
  const to = await page.evaluate(([x, y, z]) => window.tmlab.worldToScreen(x, y, z - 0.015), b.p);
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let i = 1; i <= 20; ++i) {
    await page.mouse.move(from.x + ((to.x - from.x) * i) / 20, from.y + ((to.y - from.y) * i) / 20);
    await page.waitForTimeout(25);
  }
  await page.waitForFunction((f0) => {
    const f = window.tmlab.force;
    return Math.hypot(f[0], f[1], f[2]) > Math.max(0.05, f0 + 0.05);
  }, before, { timeout, polling: 50 });
  await page.waitForTimeout(500);
  const c = await page.evaluate(() => ({ f: window.tmlab.force, p: window.tmlab.probe, moves: window.tmlab.moves }));
  await page.screenshot({ path: screenshot });
  await page.mouse.up();
  const depth = await pressInDepth(page, screenshot.replace(/\.png$/, '') + '_depth.png');
  result = { ok: true, fps_received: fps, force_before_N: before, force_after_N: norm(c.f), force_after: c.f,
             probe_before: b.p, probe_after: c.p, probe_messages: c.moves, drag_px: [from, to], depth,
             console_errors: consoleErrors, screenshot };
  console.log(JSON.stringify(result));
} catch (e) {
  console.error(`browser test failed: ${e.message}`);
  process.exitCode = 1;
} finally {
  await browser.close();
}
