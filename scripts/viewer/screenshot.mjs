// Opens the viewer in Debian's headless Chromium (software GL), waits until the tileset reports every
// tile of the view loaded, and saves a screenshot. Prints one JSON line: seconds to load, the clear
// colour, and any request to another host (there must be none).
//
//   node scripts/viewer/screenshot.mjs WORLD_DIR OUT.png [--width 1280] [--height 720] [--timeout 120]
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { serveWorld } from './serve.mjs';

const [world, out, ...rest] = process.argv.slice(2);
const option = (name, fallback) => (rest.includes(name) ? Number(rest[rest.indexOf(name) + 1]) : fallback);
const width = option('--width', 1280), height = option('--height', 720), timeout = option('--timeout', 120) * 1000;

const { server, url } = await serveWorld(world, 0);
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'terrasynth-chromium-'));
// A fresh, empty profile; software GL (SwiftShader) in place of a GPU.
const browser = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  headless: true,
  viewport: { width, height },
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
    '--ignore-gpu-blocklist'],
});
const elsewhere = [];
let status = 0;
try {
  const page = browser.pages()[0] ?? await browser.newPage();
  const console_lines = [];
  page.on('console', (m) => console_lines.push(m.text()));
  // Nothing may leave localhost: other hosts are refused and reported.
  await page.route('**/*', (route) => {
    const u = route.request().url();
    if (u.startsWith(url) || u.startsWith('data:') || u.startsWith('blob:')) return route.continue();
    elsewhere.push(u);
    return route.abort();
  });
  const start = Date.now();
  await page.goto(url);
  await page.waitForFunction(() => window.terrasynthViewer && (window.terrasynthViewer.loaded || window.terrasynthViewer.error),
    null, { timeout, polling: 200 });
  const state = await page.evaluate(() => window.terrasynthViewer);
  if (state.error) throw new Error('viewer: ' + state.error + '\n' + console_lines.join('\n'));
  const seconds = (Date.now() - start) / 1000;
  await page.screenshot({ path: out });
  console.log(JSON.stringify({ seconds, clearColor: state.clearColor, width, height, elsewhere }));
} catch (e) {
  console.error(String(e && e.stack ? e.stack : e));
  status = 1;
} finally {
  await browser.close();
  server.close();
  fs.rmSync(profile, { recursive: true, force: true });
}
process.exit(status);
