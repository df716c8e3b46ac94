// What the browser tests and the speed benchmark share: `m4mesh serve` on a
// free loopback port, Debian's Chromium driven by playwright-core, and a
// screenshot check that needs no image library (the page itself reads the
// PNG back and counts its colours).
import { execFileSync, spawn } from 'node:child_process';
import { cpSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import http from 'node:http';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
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

// The byte offsets of a 3D stream's units (their start codes 00 00 01 C5).
export function unitOffsets(bytes) {
  const offsets = [];
  for (let k = 0; k + 3 < bytes.length; ++k)
    if (bytes[k] === 0 && bytes[k + 1] === 0 && bytes[k + 2] === 1 && bytes[k + 3] === 0xc5) offsets.push(k);
  return offsets;
}

// A server in front of `upstream` (serve()'s url) that sends the file at
// `path` only as far as the test allows: allow(n) lets its first n bytes
// go, flow(rate) the rest at `rate` bytes/s. A test thus drives a slow
// download by what the page has shown, not by how fast the machine is.
// Resolves to { url, total, allow, flow, stop }.
export function gatedServe(upstream, path, file) {
  const bytes = readFileSync(file);
  const target = new URL(upstream);
  let allowed = 0, timer = null;
  const responses = new Set();
  const pump = () => {
    for (const res of responses) {
      if (res.sentBytes < allowed) res.write(bytes.subarray(res.sentBytes, allowed)), (res.sentBytes = allowed);
      if (res.sentBytes === bytes.length) res.end(), responses.delete(res);
    }
  };
  const server = http.createServer((req, res) => {
    if (new URL(req.url, 'http://x').pathname === path) {
      res.writeHead(200, { 'Content-Type': 'application/octet-stream', 'Content-Length': bytes.length, 'Cache-Control': 'no-store' });
      res.sentBytes = 0;
      responses.add(res);
      return pump();
    }
    const forward = http.request({ host: target.hostname, port: target.port, path: req.url, method: req.method, headers: req.headers }, (up) => {
      res.writeHead(up.statusCode, up.headers);
      up.pipe(res);
    });
    req.pipe(forward);
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve({
    url: `http://127.0.0.1:${server.address().port}/`,
    total: bytes.length,
    allow: (n) => ((allowed = Math.min(bytes.length, Math.max(allowed, n))), pump()),
    flow: (rate) => {
      clearInterval(timer);
      timer = setInterval(() => {
        allowed = Math.min(bytes.length, allowed + Math.ceil(rate / 20));
        pump();
        if (allowed === bytes.length) clearInterval(timer);
      }, 50);
    },
    stop: () => (clearInterval(timer), server.closeAllConnections(), server.close()),
  })));
}

// The assembled npm package (build/web/package) as an application gets it:
// `npm pack`, then installed offline into an empty application in `work`
// beside the checkout's three.js (and `others` of web/node_modules).
// Returns the application's folder.
export function installPackage(packageDir, source, work, others = []) {
  const tarball = execFileSync('npm', ['pack', packageDir, '--pack-destination', work, '--silent'], { encoding: 'utf8' }).trim().split('\n').pop();
  const app = join(work, 'app');
  mkdirSync(app);
  writeFileSync(join(app, 'package.json'), JSON.stringify({ name: 'app', private: true, type: 'module' }));
  execFileSync('npm', ['install', '--offline', '--no-audit', '--no-fund', '--ignore-scripts', '--silent', join(work, tarball),
    ...['three', ...others].map((name) => resolve(source, 'web', 'node_modules', name))], { cwd: app, stdio: 'inherit' });
  return app;
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
