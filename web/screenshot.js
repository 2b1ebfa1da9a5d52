#!/usr/bin/env node
// A screenshot of the explorer (scripts/screenshot-web.sh): serve web/dist on 127.0.0.1 (serve.js),
// open the page with a URL query in headless Chromium (driven by playwright-core, as the e2e test
// does), wait for the page's ready marker (<body data-ready="true">, set once the first case is
// shown) and for the engine to be idle, then write the whole page as PNG.
// Usage: node web/screenshot.js [URL-query] [out.png] [--dist DIR] [--width W] [--height H]
'use strict';
const { spawn } = require('node:child_process');
const fs = require('node:fs');
const os = require('node:os');
const path = require('node:path');

const args = process.argv.slice(2);
const opt = (name, fallback) => {
  const i = args.indexOf(name);
  if (i < 0) return fallback;
  const v = args[i + 1];
  args.splice(i, 2);
  return v;
};
const dist = path.resolve(opt('--dist', path.join(__dirname, 'dist')));
const width = Number(opt('--width', '1400'));
const height = Number(opt('--height', '1150'));
const query = (args[0] || '').replace(/^\?/, '');
const out = path.resolve(args[1] || 'explorer.png');
const CHROMIUM = process.env.OSCIDRUM_CHROMIUM || '/usr/bin/chromium';

function fail(why) {
  console.error(`screenshot-web: ${why}`);
  process.exit(2);
}
if (!fs.existsSync(path.join(dist, 'oscidrum.wasm'))) fail(`${dist}/oscidrum.wasm not found: build it with scripts/build-web.sh`);
if (!fs.existsSync(CHROMIUM)) fail(`${CHROMIUM} not found (apt-get install chromium, or set OSCIDRUM_CHROMIUM)`);
let chromium;
try {
  ({ chromium } = require(path.join(__dirname, 'node_modules', 'playwright-core')));
} catch {
  fail('playwright-core not installed: run scripts/build-web.sh (npm ci in web/)');
}

function startServer() {
  return new Promise((resolve, reject) => {
    const server = spawn(process.execPath, [path.join(__dirname, 'serve.js'), '--port', '0', '--dir', dist], { stdio: ['ignore', 'pipe', 'inherit'] });
    server.stdout.on('data', (d) => {
      const m = /http:\/\/127\.0\.0\.1:\d+\//.exec(String(d));
      if (m) resolve({ server, url: m[0] });
    });
    server.on('exit', (code) => reject(new Error(`server exited with ${code}`)));
  });
}

async function main() {
  const { server, url } = await startServer();
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'oscidrum-screenshot-'));
  let browser = null;
  try {
    browser = await chromium.launchPersistentContext(profile, {
      executablePath: CHROMIUM,
      headless: true,
      viewport: { width, height },
      args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run',
        '--disable-background-networking', '--disable-component-update', '--disable-sync'],
    });
    const page = browser.pages()[0] || await browser.newPage();
    await page.goto(url + (query ? `?${query}` : ''));
    await page.waitForSelector('body[data-ready="true"]', { timeout: 60000 });
    await page.waitForFunction(() => !window.explorer.busy(), null, { timeout: 60000 });
    await page.waitForTimeout(700);  // a frame of the drum's animation
    await page.screenshot({ path: out, fullPage: true });
    const status = await page.textContent('#status');
    console.log(`screenshot-web: ${out} (${status})`);
  } finally {
    if (browser) await browser.close();
    server.kill();
    fs.rmSync(profile, { recursive: true, force: true });
  }
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
