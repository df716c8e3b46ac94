// The web site in a real browser (ctest "browser"; docs/web.md): headless
// Chromium loads the pages `m4mesh serve` serves and checks
//   1. both conformance suites through the WebAssembly decoder: every
//      stream passes as `m4mesh conform` judges it;
//   2. `check` in the page lists what the native `m4mesh check` lists, on
//      every stream to reject of both suites;
//   3. the player shows a 3D stream shaded and a 2D stream as a warped
//      texture (screenshots that are not blank), each I-plane its own tile
//      of a texture for several (`m4mesh serve S.m4m S.png`);
//   4. a progressive stream held after its first units plays them before
//      the rest arrives, and the units applied grow while it plays (the
//      download is driven by what the page has drawn, so a busy machine
//      changes the times, not the outcome); `m4mesh serve --rate` throttles;
//   5. the analyzer lists a stream's units, their elements and its chart;
//   6. a stream's glTF (decode3d -o anim.glb) played by three.js's
//      GLTFLoader beside the stream shows the same positions, bit for bit;
//   7. real-size streams (from ../shared/data): the horse loads, plays
//      beside its glTF and is analysed without the page stopping to answer
//      for over 1.5 s; a progressive cpca-wpt cow served slowly draws
//      frames before its download ends.
// Usage: node browser_test.mjs M4MESH SITE [SCREENSHOT_FOLDER]
import { execFileSync } from 'node:child_process';
import { copyFileSync, existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import http from 'node:http';
import { join } from 'node:path';
import { colourCounts, gatedServe, launch, pictureStatistics, serve, unitOffsets, until, watchStalls } from './harness.mjs';

const [m4mesh, site, shots] = process.argv.slice(2);
if (!m4mesh || !site) throw new Error('usage: node browser_test.mjs M4MESH SITE [SCREENSHOT_FOLDER]');
if (shots) mkdirSync(shots, { recursive: true });

let failures = 0;
function expect(condition, what) {
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${what}`);
  if (!condition) failures++;
}

// Waits until `predicate(window.m4mesh)` holds; returns the state then. The
// budgets hold on a machine busy with other work (load 5 on 2 cores).
async function stateWhen(page, predicate, timeout = 120000) {
  await until(page, `() => (${predicate})(window.m4mesh)`, timeout);
  return page.evaluate(() => JSON.parse(JSON.stringify(window.m4mesh, (k, v) => (k.endsWith('View') || k === 'module' ? undefined : v))));
}

// Lets a held stream go on from byte `from` to byte `to` in three steps,
// each ending where a unit is whole (`offsets`: its units' start codes),
// and waits after each until the page has drawn a frame of a new
// refinement: as many refinements drawn during the download however busy
// the machine is.
async function releaseInSteps(page, gate, offsets, from, to) {
  const ends = offsets.map((o) => o + 4).filter((end) => end > from && end < to);
  for (const end of [ends[Math.floor(ends.length / 3)], ends[Math.floor((2 * ends.length) / 3)], to]) {
    const before = (await stateWhen(page, () => true)).player.unitsAppliedWhenDrawn.length;
    gate.allow(end);
    await stateWhen(page, `(s) => s.player.unitsAppliedWhenDrawn.length > ${before}`);
  }
}

async function openPage(browser, url) {
  const page = await browser.newPage({ viewport: { width: 1100, height: 760 } });
  page.on('pageerror', (error) => expect(false, `no error in the page (${error.message})`));
  await page.goto(url, { timeout: 120000 });
  return page;
}

// The viewport's screenshot, kept in SCREENSHOT_FOLDER, checked not to be blank.
async function picture(page, name, selector = '#viewport') {
  const png = await page.locator(selector).screenshot();
  if (shots) writeFileSync(join(shots, `${name}.png`), png);
  const { colours, spread } = await pictureStatistics(page, png);
  expect(colours >= 16 && spread >= 4, `${name}: the picture is not blank (${colours} colours, brightness spread ${spread.toFixed(1)})`);
}

const manifests = ['conformance', 'conformance/mesh3d'].map((suite) => ({
  suite, streams: JSON.parse(readFileSync(join(site, suite, 'manifest.json'))).streams,
}));
const server = await serve(m4mesh, site);
const slow = await serve(m4mesh, site, 4000);
const browser = await launch();
try {
  // 0. The server: the types modules and WebAssembly need, nothing outside its folder.
  const types = await Promise.all(['m4mesh.mjs', 'm4mesh.wasm'].map(async (f) => (await fetch(server.url + f)).headers.get('content-type')));
  expect(types[0] === 'text/javascript' && types[1] === 'application/wasm', `serve: ${types.join(', ')}`);
  const outside = await Promise.all(['/../../../../etc/passwd', '/%2e%2e/%2e%2e/etc/passwd', '/conformance/../../web'].map((path) =>
    new Promise((resolve) => http.get({ host: '127.0.0.1', port: new URL(server.url).port, path }, (r) => resolve(r.statusCode)))));
  expect(outside.every((code) => code === 404), `serve: paths out of its folder are not found (${outside.join(', ')})`);

  // 1. Both suites, decoded in the browser.
  let page = await openPage(browser, `${server.url}#conformance?run`);
  const run = (await stateWhen(page, (s) => s.conformance?.done, 180000)).conformance;
  const total = manifests.reduce((n, m) => n + m.streams.length, 0);
  expect(run.passed === total && run.failed === 0, `conformance in the browser: ${run.passed} of ${total} streams pass (${run.decoded} decoded with the manifest's MD5, ${run.rejected} rejected with its error)`);
  for (const r of run.results.filter((r) => !r.pass)) console.log(`     ${r.suite} ${r.id}: ${r.detail}`);

  // 2. The checker in the page against the native one, on every stream to reject.
  const rejected = manifests.flatMap(({ suite, streams }) => streams.filter((s) => s.expect !== 'decode').map((s) => join(suite, s.file)));
  const web = await page.evaluate(async (files) => {
    const out = {};
    for (const file of files) {
      const bytes = new Uint8Array(await (await fetch(file)).arrayBuffer());
      const report = JSON.parse(window.m4mesh.module.check(bytes));
      out[file] = report.error ? [`error: ${report.error.text}`] : report.findings.map((f) => `${f.error ? 'error' : 'warning'}: ${f.text.replace(/^(error|warning): /, '')}`);
    }
    return out;
  }, rejected);
  let same = 0;
  for (const file of rejected) {
    let native = '';
    try {
      native = execFileSync(m4mesh, ['check', join(site, file)], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
    } catch (e) {
      native = `${e.stdout}${e.stderr}`;
    }
    const lines = native.split('\n').filter((l) => /^(error|warning): /.test(l)).map((l) => l.replace(`${join(site, file)}: `, ''));
    if (JSON.stringify(lines) === JSON.stringify(web[file])) same++;
    else console.log(`     ${file}\n       native: ${JSON.stringify(lines)}\n       web:    ${JSON.stringify(web[file])}`);
  }
  expect(same === rejected.length, `check in the browser lists what m4mesh check lists: ${same} of ${rejected.length} streams to reject`);
  await page.close();

  // 3. A 3D stream shaded, a 2D stream as the texture it warps.
  page = await openPage(browser, `${server.url}#player?stream=conformance/mesh3d/streams/bfs3d-01-average.m4m`);
  let shown = await stateWhen(page, (s) => s.player?.done && s.player.framesDrawn >= 3);
  expect(shown.player.codec === 'bfs3d' && shown.player.error === null, `3D player: ${shown.player.codec}, ${shown.player.frames} frames, ${shown.player.framesDrawn} drawn`);
  await picture(page, 'player-3d');
  await page.close();
  // The camera frames the whole sequence, not frame 0: a vertex that jumps 2^26 grid steps in frame 1 stays in view.
  page = await openPage(browser, `${server.url}#player?stream=conformance/mesh3d/streams/bfs3d-08-position-limits.m4m`);
  shown = await stateWhen(page, (s) => s.player?.done && s.player.framedFrames === 2);
  const seen = await page.evaluate(() => window.m4mesh.playerView.visibleShare());
  expect(seen === 1, `3D player: ${(100 * seen).toFixed(1)} % of every frame's vertices in view`);
  await page.close();
  // URL parameters: start at frame 3 and hold it.
  page = await openPage(browser, `${server.url}#player?stream=conformance/mesh3d/streams/bfs3d-01-average.m4m&frame=3&pause`);
  shown = await stateWhen(page, (s) => s.player?.done && s.player.frameShown === 3);
  await new Promise((resolve) => setTimeout(resolve, 1000));
  const held = await page.evaluate(() => window.m4mesh.player);
  expect(held.frameShown === 3 && held.framesDrawn === shown.player.framesDrawn,
    `3D player: &frame=3&pause holds frame ${held.frameShown} (${held.framesDrawn - shown.player.framesDrawn} frames drawn in a second)`);
  // The open page follows its URL: another frame held, then playing once "pause" goes.
  await page.evaluate(() => (location.hash = location.hash.replace('frame=3', 'frame=1')));
  shown = await stateWhen(page, (s) => s.player.frameShown === 1);
  await page.evaluate(() => (location.hash = location.hash.replace('&pause', '')));
  const resumed = await stateWhen(page, `(s) => s.player.framesDrawn > ${shown.player.framesDrawn + 3}`);
  expect(resumed.player.framesDrawn > shown.player.framesDrawn, `3D player: a changed URL in the open page holds frame 1, then plays without &pause`);
  await page.close();

  // Your own streams: `m4mesh serve A.m4m B.m4m` lists them in the page and they play; a stream the page
  // cannot fetch fails naming its URL and why.
  const own = await serve(m4mesh, ['lcc-01-stream.m4m', 'ao-06-direct-root.m4m'].map((f) => join(site, 'conformance/mesh3d/streams', f)));
  page = await openPage(browser, own.url);
  shown = await stateWhen(page, (s) => s.ready && s.served?.length === 2);
  expect(shown.served.join() === 'ao-06-direct-root.m4m,lcc-01-stream.m4m', `serve A B: the page lists ${shown.served.join(', ')}`);
  await page.locator('a.served', { hasText: 'lcc-01-stream.m4m' }).click();
  shown = await stateWhen(page, (s) => s.player?.done && s.player.framesDrawn > 0);
  expect(shown.source === 'streams/lcc-01-stream.m4m' && shown.player.codec === 'lcc', `serve A B: ${shown.source} plays (${shown.player.codec})`);
  await page.close();
  page = await openPage(browser, `${own.url}#player?stream=http://127.0.0.1:9/elsewhere.m4m`);
  const failure = await (await page.waitForFunction(() => window.m4mesh.failure, null, { timeout: 60000 })).jsonValue();
  expect(failure.startsWith('http://127.0.0.1:9/elsewhere.m4m: cannot fetch') && failure.includes('Access-Control-Allow-Origin'),
    `a stream elsewhere: ${failure}`);
  await page.close();
  own.stop();
  page = await openPage(browser, `${server.url}#player?stream=conformance/streams/p35-long-sequence.m4m`);
  shown = await stateWhen(page, (s) => s.player?.done && s.player.framesDrawn >= 3);
  expect(shown.player.kind === '2d' && shown.player.frames > 2, `2D player: ${shown.player.frames} planes, ${shown.player.framesDrawn} drawn`);
  await picture(page, 'player-2d');
  await page.close();
  {
    // A texture of I-plane tiles in 2 columns (as track writes one past 16,384 rows), served beside its stream:
    // p17's I-planes 0, 3 and 6 each show their own tile, red, green and blue; the fourth tile is unused.
    const folder = mkdtempSync(join(tmpdir(), 'm4mesh-tiles-'));
    copyFileSync(join(site, 'conformance/streams/p17-repeated-intra.m4m'), join(folder, 'tiles.m4m'));
    execFileSync('/usr/bin/python3', ['-c', `
from PIL import Image, PngImagePlugin
info = PngImagePlugin.PngInfo(); info.add_text('I-planes', '0 3 6'); info.add_text('I-plane columns', '2')
tiles = Image.new('RGB', (512, 512))
for k, colour in enumerate([(255, 0, 0), (0, 255, 0), (0, 0, 255)]): tiles.paste(colour, (256 * (k % 2), 256 * (k // 2), 256 * (k % 2) + 256, 256 * (k // 2) + 256))
tiles.save('${join(folder, 'tiles.png')}', pnginfo=info)`]);
    const tiled = await serve(m4mesh, [join(folder, 'tiles.m4m'), join(folder, 'tiles.png')]);
    page = await openPage(browser, tiled.url);
    await stateWhen(page, (s) => s.ready && s.served?.length === 2);
    const href = await page.locator('a.served').getAttribute('href');
    const colours = [[255, 0, 0], [0, 255, 0], [0, 0, 255]];
    const seen = [];
    for (const [k, plane] of [0, 3, 6].entries()) {
      await page.evaluate(([link, frame]) => { location.hash = `${link}&frame=${frame}&pause`; }, [href, plane]);
      await stateWhen(page, `(s) => s.player?.frameShown === ${plane} && s.texture === 'streams/tiles.png'`);
      await new Promise((resolve) => setTimeout(resolve, 500));
      const counts = await colourCounts(page, await page.locator('#viewport').screenshot(), colours);
      seen.push(counts);
      if (!(counts[k] > 200 && counts.every((n, i) => i === k || n === 0))) console.log(`     plane ${plane}: pixels of red, green, blue ${counts.join(', ')}`);
    }
    expect(seen.every((counts, k) => counts[k] > 200 && counts.every((n, i) => i === k || n === 0)) && href.endsWith('&texture=streams/tiles.png'),
      `2D player, a texture of tiles served with its stream: I-planes 0, 3, 6 show their own tiles (${seen.map((c) => c.join('/')).join(', ')} pixels red/green/blue)`);
    await page.close();
    tiled.stop();
    rmSync(folder, { recursive: true, force: true });
  }

  // 4. A progressive stream held after its first four units: frames drawn from them, then refined as the rest arrives at 4,000 bytes/s.
  const manyClusters = 'conformance/mesh3d/streams/cpca-09-many-clusters.m4m';
  const gate = await gatedServe(server.url, `/${manyClusters}`, join(site, manyClusters));
  const manyClustersUnits = unitOffsets(readFileSync(join(site, manyClusters)));
  const firstUnits = manyClustersUnits[4] + 4;  // units 0 … 3 whole: the next start code has arrived
  gate.allow(firstUnits);
  page = await openPage(browser, `${gate.url}#player?stream=${manyClusters}`);
  shown = await stateWhen(page, (s) => s.player?.framesDrawn > 0);
  expect(!shown.player.downloadDone && shown.player.bytesReceived === firstUnits && shown.player.unitsApplied <= 4,
    `progressive: first frame drawn from the first ${firstUnits} of ${shown.player.bytesTotal} bytes, ${shown.player.unitsApplied} units applied`);
  await picture(page, 'progressive-1');
  await releaseInSteps(page, gate, manyClustersUnits, firstUnits, manyClustersUnits[Math.floor(manyClustersUnits.length / 2)] + 4);
  await picture(page, 'progressive-2');
  gate.flow(4000);
  shown = await stateWhen(page, (s) => s.player.done && s.player.unitsAppliedWhenDrawn.length >= 3);
  await picture(page, 'progressive-3');
  const applied = shown.player.unitsAppliedWhenDrawn;
  expect(applied.length >= 3 && applied[0] < applied[applied.length - 1],
    `progressive: frames drawn at ${applied.length} rising refinements (units ${applied[0]} … ${applied[applied.length - 1]})`);
  expect(shown.player.framesDrawnDuringDownload > 0, `progressive: ${shown.player.framesDrawnDuringDownload} frames drawn during the download`);
  gate.stop();
  // m4mesh serve --rate 4000 throttles: the stream cannot arrive sooner than its size allows (a busy machine only slows it more).
  const throttledStart = Date.now();
  const throttled = await (await fetch(`${slow.url}${manyClusters}`)).arrayBuffer();
  const throttledSeconds = (Date.now() - throttledStart) / 1000;
  expect(throttled.byteLength === gate.total && throttledSeconds >= 0.9 * gate.total / 4000,
    `serve --rate 4000: ${throttled.byteLength} bytes in ${throttledSeconds.toFixed(1)} s`);
  // The analyzer has not traced the stream while only the player was open; it does once its view opens.
  expect(shown.analyzer === null, 'player view: the analyzer waits for its view');
  await page.evaluate(() => (location.hash = location.hash.replace('#player', '#analyzer')));
  shown = await stateWhen(page, (s) => s.analyzer?.elementsShown > 0);
  expect(shown.analyzer.parts.some((p) => /refinement, cluster \d+ (start|component)/.test(p.label)),
    `analyzer opened later: ${shown.analyzer.parts.length} parts (${shown.analyzer.parts[2]?.label})`);
  await page.close();

  // 5. The analyzer: the units, the elements of one, the chart; a stream with an error located in the list.
  page = await openPage(browser, `${server.url}#analyzer?stream=conformance/mesh3d/streams/cpca-01-wpt.m4m`);
  shown = await stateWhen(page, (s) => s.analyzer?.elementsShown > 0);
  const info = execFileSync(m4mesh, ['info', join(site, 'conformance/mesh3d/streams/cpca-01-wpt.m4m')], { encoding: 'utf8' });
  const units = [...info.matchAll(/units: (\d+)/g)].reduce((n, m) => n + Number(m[1]), 0);
  expect(shown.analyzer.parts.length === units + 1 && shown.analyzer.errors === 0 && shown.analyzer.chartKinds.length > 0,
    `analyzer: ${shown.analyzer.parts.length - 1} units listed (m4mesh info: ${units}), ${shown.analyzer.elementsShown} elements of ${shown.analyzer.selected}, ${shown.analyzer.chartKinds.length} kinds in the chart`);
  await picture(page, 'analyzer', 'main');
  await page.close();
  page = await openPage(browser, `${server.url}#analyzer?stream=conformance/mesh3d/streams/x-62-cpca-beyond-trajectories.m4m`);
  shown = await stateWhen(page, (s) => s.analyzer?.elementsShown > 0);
  expect(shown.analyzer.errors === 1 && /unit 6/.test(shown.analyzer.selected) && /unit 6, cluster at bit \d+:/.test(shown.analyzer.findings[0]),
    `analyzer: the error is listed and its unit selected (${shown.analyzer.findings[0]}; ${shown.analyzer.selected})`);
  await picture(page, 'analyzer-error', 'main');
  await page.close();

  // 6. A stream and its glTF side by side: three.js's evaluation of the glTF equals the decoded frames.
  {
    const folder = mkdtempSync(join(tmpdir(), 'm4mesh-gltf-'));
    const glb = join(folder, 'bfs3d-01-average.glb');
    execFileSync(m4mesh, ['--quiet', 'decode3d', join(site, 'conformance/mesh3d/streams/bfs3d-01-average.m4m'), '-o', glb]);
    const own = await serve(m4mesh, [join(site, 'conformance/mesh3d/streams/bfs3d-01-average.m4m'), glb]);
    page = await openPage(browser, `${own.url}#player?stream=streams/bfs3d-01-average.m4m&gltf=streams/bfs3d-01-average.glb`);
    shown = await stateWhen(page, (s) => s.player?.done && s.gltf?.animated && s.player.framesDrawn >= 3);
    const same = await page.evaluate(() => window.m4mesh.playerView.compareGltf([0, 2, 5]));
    expect(shown.gltf.frames === 6 && same.compared === 3 * 3 * shown.player.vertices && same.differing === 0,
      `glTF beside the stream: ${shown.gltf.frames} frames; at frames 0, 2 and 5 ${same.compared - same.differing} of ${same.compared} coordinates equal the decoded ones` +
      (same.first ? ` (first difference: ${JSON.stringify(same.first)})` : ''));
    await picture(page, 'player-gltf');
    await page.close();
    own.stop();
    rmSync(folder, { recursive: true, force: true });
  }

  // 7. A real-size stream (the horse: 8,431 vertices, 48 frames, 3.65 M trace lines): the page keeps
  // answering while it loads and plays, and while the analyzer lists it, traces its base mesh and pages through it.
  const data = process.env.M4MESH_DATA;
  if (!data || !existsSync(join(data, 'horse-gallop'))) {
    console.log('skip: ../shared/data is absent: the real-size stream (the horse) is not tried');
  } else {
    const folder = mkdtempSync(join(tmpdir(), 'm4mesh-horse-'));
    const horse = join(folder, 'horse.m4m');
    execFileSync(m4mesh, ['--quiet', 'encode3d', join(data, 'horse-gallop'), '-o', horse]);
    execFileSync(m4mesh, ['--quiet', 'decode3d', horse, '-o', join(folder, 'horse.glb')]);
    const own = await serve(m4mesh, [horse, join(folder, 'horse.glb')]);
    page = await browser.newPage({ viewport: { width: 1100, height: 760 } });
    page.on('pageerror', (error) => expect(false, `no error in the page (${error.message})`));
    await watchStalls(page);
    await page.goto(`${own.url}#player?stream=streams/horse.m4m`);
    let started = Date.now();
    shown = await stateWhen(page, (s) => s.player?.done && s.player.framesDrawn >= 60, 120000);
    const playing = await page.evaluate(() => window.stall.longest);
    expect(shown.player.frames === 48 && playing < 1500,
      `horse: ${shown.player.framesDrawn} frames drawn in ${((Date.now() - started) / 1000).toFixed(1)} s, the page stopped answering at most ${playing.toFixed(0)} ms`);
    await picture(page, 'horse');
    // Its glTF beside it: the same positions in three.js, the page still answering.
    await page.evaluate(() => (location.hash = `${location.hash}&gltf=streams/horse.glb`));
    shown = await stateWhen(page, (s) => s.gltf?.animated, 120000);
    const horseSame = await page.evaluate(() => window.m4mesh.playerView.compareGltf([0, 24, 47]));
    const withGltf = await page.evaluate(() => window.stall.longest);
    expect(horseSame.compared === 3 * 3 * 8431 && horseSame.differing === 0 && withGltf < 1500,
      `horse beside its glTF (${shown.gltf.frames} frames): ${horseSame.compared - horseSame.differing} of ${horseSame.compared} coordinates equal at frames 0, 24, 47; ` +
      `the page stopped answering at most ${withGltf.toFixed(0)} ms`);
    await picture(page, 'horse-gltf');
    await page.evaluate(() => (location.hash = location.hash.replace('&gltf=streams/horse.glb', '')));
    started = Date.now();
    await page.evaluate(() => (location.hash = location.hash.replace('#player', '#analyzer')));
    shown = await stateWhen(page, (s) => s.analyzer?.rowsShown > 0, 120000);
    const listed = Date.now() - started;
    const baseMesh = shown.analyzer;
    expect(/^unit 0: base mesh/.test(baseMesh.selected) && baseMesh.elementsShown > 100000 && baseMesh.rowsShown === 500,
      `horse in the analyzer: ${baseMesh.selected} has ${baseMesh.elementsShown} elements, shown ${baseMesh.rowsShown} a page (${baseMesh.pages} pages)`);
    await page.locator('#page-next').click();
    shown = await stateWhen(page, (s) => s.analyzer.page === 1);
    await page.locator('#unit-list tr').last().click();
    shown = await stateWhen(page, (s) => /^unit \d+: group hash/.test(s.analyzer.selected) && s.analyzer.page === 0);
    const analysing = await page.evaluate(() => window.stall.longest);
    const horseUnits = [...execFileSync(m4mesh, ['info', horse], { encoding: 'utf8' }).matchAll(/units: (\d+)/g)].reduce((n, m) => n + Number(m[1]), 0);
    expect(shown.analyzer.parts.length === horseUnits + 1 && shown.analyzer.pages === 1 && analysing < 1500,
      `horse in the analyzer: ${shown.analyzer.parts.length - 1} units and the base mesh's first page in ${(listed / 1000).toFixed(1)} s, ` +
      `paged and the last unit chosen; the page stopped answering at most ${analysing.toFixed(0)} ms`);
    await picture(page, 'horse-analyzer', 'main');
    await page.close();
    own.stop();

    // The cow (2,904 vertices, 204 frames) in cpca-wpt, progressive: held after its first three units, drawn from them, then
    // let go in steps, a new refinement drawn after each.
    const cow = join(folder, 'cow.m4m');
    execFileSync(m4mesh, ['--quiet', 'encode3d', join(data, 'pcow'), '--codec', 'cpca-wpt', '-o', cow]);
    const cowServer = await serve(m4mesh, [cow]);
    const slowCow = await gatedServe(cowServer.url, '/streams/cow.m4m', cow);
    const cowUnits = unitOffsets(readFileSync(cow));
    const cowFirstUnits = cowUnits[3] + 4;  // units 0 … 2 whole
    slowCow.allow(cowFirstUnits);
    page = await openPage(browser, `${slowCow.url}#player?stream=streams/cow.m4m`);
    shown = await stateWhen(page, (s) => s.player?.framesDrawn > 0);
    const firstAt = shown.player.bytesReceived, total = shown.player.bytesTotal;
    await releaseInSteps(page, slowCow, cowUnits, cowFirstUnits, slowCow.total);
    shown = await stateWhen(page, (s) => s.player.done, 180000);
    const cowApplied = shown.player.unitsAppliedWhenDrawn;
    expect(cowApplied[0] <= 3 && firstAt === cowFirstUnits && shown.player.framesDrawnDuringDownload >= 3 && cowApplied.length >= 4 &&
      shown.player.frames === 204,
      `cow, progressive in steps: first frame drawn from the first ${firstAt} of ${total} bytes, ${shown.player.framesDrawnDuringDownload} frames drawn during the download, ` +
      `refined ${cowApplied.length} times (units ${cowApplied[0]} … ${cowApplied[cowApplied.length - 1]})`);
    await picture(page, 'cow-progressive');
    await page.close();
    slowCow.stop();
    cowServer.stop();
    rmSync(folder, { recursive: true, force: true });
  }
} finally {
  await browser.close();
  server.stop();
  slow.stop();
}
console.log(failures === 0 ? 'browser tests: all passed' : `browser tests: ${failures} failed`);
process.exit(failures === 0 ? 0 : 1);
