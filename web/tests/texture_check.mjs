// A 2D stream and its texture of many I-planes (m4mesh track --texture) in
// the player, at real size: the time until plane FRAME is shown with its
// own tile, the longest the page stopped answering meanwhile (it must stay
// under 1.5 s), and a screenshot. Not in ctest (tracking a long video takes
// minutes); docs/web.md gives the run on the whole of vtest.avi.
// Usage: node texture_check.mjs M4MESH STREAM.m4m TEXTURE.png FRAME [SCREENSHOT.png]
import { basename } from 'node:path';
import { launch, pictureStatistics, serve, until, watchStalls } from './harness.mjs';

const [m4mesh, stream, texture, frameText, screenshot] = process.argv.slice(2);
if (!m4mesh || !stream || !texture || !frameText) throw new Error('usage: node texture_check.mjs M4MESH STREAM.m4m TEXTURE.png FRAME [SCREENSHOT.png]');
const frame = Number(frameText);
const server = await serve(m4mesh, [stream, texture]);
const browser = await launch();
let failed = false;
try {
  const page = await browser.newPage({ viewport: { width: 1100, height: 760 } });
  page.on('pageerror', (error) => ((failed = true), console.log(`FAIL an error in the page: ${error.message}`)));
  await watchStalls(page);
  const started = Date.now();
  await page.goto(`${server.url}#player?stream=streams/${basename(stream)}&texture=streams/${basename(texture)}&frame=${frame}&pause`);
  await until(page, `() => window.m4mesh.player?.frameShown === ${frame} && window.m4mesh.texture === 'streams/${basename(texture)}'`, 300000);
  const shown = (Date.now() - started) / 1000;
  await page.waitForTimeout(1000);
  const png = await page.locator('#viewport').screenshot(screenshot ? { path: screenshot } : {});
  const { colours } = await pictureStatistics(page, png);
  const stall = await page.evaluate(() => window.stall.longest);
  failed ||= stall >= 1500 || colours < 16;
  console.log(`${failed ? 'FAIL' : 'ok  '} plane ${frame} shown after ${shown.toFixed(1)} s; the page stopped answering at most ${stall.toFixed(0)} ms; ${colours} colours`);
} finally {
  await browser.close();
  server.stop();
}
process.exit(failed ? 1 : 0);
