// What the browser tests and the speed benchmark share: `m4mesh serve` on a
// free loopback port, Debian's Chromium driven by playwright-core, and a
// screenshot check that needs no image library (the page itself reads the
// PNG back and counts its colours).
import { spawn } from 'node:child_process';
import { cpSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

// `m4mesh serve FOLDER --port 0 [--rate R]` (or several paths: streams
// served with the tool's own site); resolves to { url, stop }.
export function serve(m4mesh, folder, rate = 0) {
  const args = ['serve', ...[].concat(folder), '--port', '0', ...(rate ? ['--rate', String(rate)] : [])];
  const child = spawn(m4mesh, args, { stdio: ['ignore', 'pipe', 'inherit'] });
  return new Promise((resolve, reject) => {
    let out = '';
    child.on('exit', (code) => reject(new Error(`m4mesh serve exited with ${code}`)));
    child.stdout.on('data', (data) => {
      out += data;
      const match = out.match(/at (http:\/\/\S+\/)/);
      if (match) resolve({ url: match[1], stop: () => child.kill() });
    });
  });
}

// A copy of the built site in a temporary folder, with `extra` files beside it ({ name: path }).
export function siteCopy(site, extra = {}) {
  const folder = mkdtempSync(join(tmpdir(), 'm4mesh-web-'));
  cpSync(site, folder, { recursive: true });
  for (const [name, path] of Object.entries(extra)) cpSync(path, join(folder, name));
  return { folder, remove: () => rmSync(folder, { recursive: true, force: true }) };
}

// Headless Chromium as this machine runs it: no sandbox (root), software WebGL, no background traffic.
export function launch() {
  return chromium.launch({
    executablePath: process.env.M4MESH_CHROMIUM || '/usr/bin/chromium',
    args: ['--no-sandbox', '--disable-gpu', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-background-networking',
      '--disable-component-update', '--disable-sync', '--no-first-run', '--disable-quic'],
  });
}

// What a screenshot shows, read back by the page: its distinct colours,
// the spread of its brightness (a blank page has one colour, no spread),
// and how many pixels are each of `targets` ([r, g, b]), each channel
// within `tolerance`.
async function screenshotFacts(page, png, targets = [], tolerance = 8) {
  return page.evaluate(async ([base64, wanted, within]) => {
    const image = new Image();
    image.src = `data:image/png;base64,${base64}`;
    await image.decode();
    const canvas = new OffscreenCanvas(image.width, image.height);
    const context = canvas.getContext('2d');
    context.drawImage(image, 0, 0);
    const data = context.getImageData(0, 0, image.width, image.height).data;
    const colours = new Set(), counts = wanted.map(() => 0);
    let sum = 0, squares = 0;
    for (let k = 0; k < data.length; k += 4) {
      colours.add((data[k] << 16) | (data[k + 1] << 8) | data[k + 2]);
      const light = (data[k] + data[k + 1] + data[k + 2]) / 3;
      sum += light, (squares += light * light);
      wanted.forEach((t, i) => {
        if (Math.abs(data[k] - t[0]) <= within && Math.abs(data[k + 1] - t[1]) <= within && Math.abs(data[k + 2] - t[2]) <= within) counts[i]++;
      });
    }
    const n = data.length / 4;
    return { colours: colours.size, spread: Math.sqrt(squares / n - (sum / n) ** 2), counts };
  }, [png.toString('base64'), targets, tolerance]);
}

// The screenshot's distinct colours and the spread of its brightness.
export async function pictureStatistics(page, png) {
  const { colours, spread } = await screenshotFacts(page, png);
  return { colours, spread };
}

// How many pixels of a screenshot are each of `colours`.
export async function colourCounts(page, png, colours) {
  return (await screenshotFacts(page, png, colours)).counts;
}

// From the page's next load on, window.stall.longest is the longest the
// page went without running a 50 ms timer: how long it stopped answering.
export async function watchStalls(page) {
  await page.addInitScript(() => {
    const stall = (window.stall = { longest: 0, last: performance.now() });
    setInterval(() => {
      const now = performance.now();
      stall.longest = Math.max(stall.longest, now - stall.last);
      stall.last = now;
    }, 50);
  });
}

// Resolves once `predicate` (a function run in the page) returns true,
// looking every half second; a page's own failure (window.m4mesh.failure)
// ends it. (Playwright's waitForFunction did not resolve here on a page
// busy with software WebGL.)
export async function until(page, predicate, timeout = 60000) {
  const end = Date.now() + timeout;
  for (;;) {
    await page.waitForTimeout(500);
    const [done, failure] = await page.evaluate(`[Boolean((${predicate})()), window.m4mesh?.failure ?? null]`);
    if (failure) throw new Error(`the page failed: ${failure}`);
    if (done) return;
    if (Date.now() > end) throw new Error(`timed out after ${timeout / 1000} s waiting for ${predicate}`);
  }
}
