// m4mesh in the browser: loads the WebAssembly decoders (m4mesh.mjs, the
// project's C++ built by Emscripten), switches between the views and
// opens streams by URL, file or drop. Everything a test reads is in
// window.m4mesh; the views only record there what they show.
import createM4mesh from './m4mesh.mjs';
import { Player } from './player.js';
import { Analyzer } from './analyzer.js';
import { runConformance } from './conformance.js';
import { runBench } from './bench.js';

const state = { ready: false, view: 'player', source: null, player: null, gltf: null, analyzer: null, conformance: null, bench: null };
window.m4mesh = state;

const SAMPLES = [
  ['cpca-wpt (progressive)', 'conformance/mesh3d/streams/cpca-01-wpt.m4m'],
  ['bfs3d', 'conformance/mesh3d/streams/bfs3d-01-average.m4m'],
  ['lcc', 'conformance/mesh3d/streams/lcc-01-stream.m4m'],
  ['affine-octree', 'conformance/mesh3d/streams/ao-01-me1-k16.m4m'],
  ['2D uniform', 'conformance/streams/p04-uniform-split2.m4m'],
];

// Parameters after the view name: "#player?stream=a.m4m&texture=t.png",
// "&frame=K" (from 0) to start at frame K, "&pause" to hold it,
// "&gltf=a.glb" to play a glTF animation beside the stream.
function hashParameters() {
  const [view, query] = location.hash.slice(1).split('?');
  return { view: view || 'player', params: new URLSearchParams(query || '') };
}

function showView(view) {
  state.view = view;
  // The analyzer traces and checks a whole stream: only when its view is open.
  if (view === 'analyzer' && pendingAnalysis) analyze();
  for (const section of document.querySelectorAll('.view')) section.classList.toggle('active', section.id === view);
  for (const link of document.querySelectorAll('nav a')) link.classList.toggle('active', link.dataset.view === view);
  if (view === 'player') state.playerView?.resize();
}

// The stream as a ReadableStream of Uint8Array chunks, from a URL or a File.
async function openBody(source) {
  if (source instanceof File) return { body: source.stream(), size: source.size, name: source.name };
  let response;
  try {
    response = await fetch(source);
  } catch (error) {
    // The browser says only "Failed to fetch": name the URL and the usual reasons.
    const url = new URL(source, location.href);
    const reason = url.origin === location.origin
      ? 'the server did not answer'
      : `another server (${url.origin}) that does not allow this page (${location.origin}) to read it (no Access-Control-Allow-Origin), or does not answer`;
    throw new Error(`${url.href}: cannot fetch (${error.message}): ${reason}. Serve your streams with the page: m4mesh serve STREAM.m4m …`);
  }
  if (!response.ok) throw new Error(`${new URL(source, location.href).href}: HTTP ${response.status} ${response.statusText}`);
  const length = Number(response.headers.get('Content-Length')) || 0;
  return { body: response.body, size: length, name: source };
}

// The stream the analyzer has yet to see: its bytes (a promise) and name.
let pendingAnalysis = null;

function analyze() {
  const { bytes, name } = pendingAnalysis;
  pendingAnalysis = null;
  state.analyzerView.load(bytes, name).catch(report);
}

async function openStream(source) {
  state.source = source instanceof File ? source.name : source;
  state.analyzer = null;
  const opened = await openBody(source);
  // The analyzer needs every byte, when its view opens; the player takes them as they arrive.
  const tee = opened.body.tee();
  pendingAnalysis = { bytes: new Response(tee[1]).arrayBuffer(), name: opened.name };
  if (state.view === 'analyzer') analyze();
  await state.playerView.play(tee[0], opened.size, opened.name);
}

async function main() {
  const module = await createM4mesh();
  state.playerView = new Player(document.getElementById('viewport'), state);
  state.analyzerView = new Analyzer(state);
  state.module = module;
  state.ready = true;

  const samples = document.getElementById('samples');
  // Streams `m4mesh serve STREAM.m4m …` was given come first.
  const served = await fetch('streams.json').then((r) => (r.ok ? r.json() : [])).catch(() => []);
  state.served = served.map((s) => s.name);
  for (const { name, url } of served) {
    if (name.endsWith('.png')) continue;  // a texture: it comes with its stream, NAME.m4m with NAME.png
    const texture = name.replace(/\.m4m$/, '.png');
    const link = document.createElement('a');
    link.href = /\.(glb|gltf)$/.test(url) ? `#player?gltf=${url}`
      : `#player?stream=${url}${texture !== name && state.served.includes(texture) ? `&texture=streams/${texture}` : ''}`;
    link.textContent = name;
    link.className = 'served';
    samples.append(link);
  }
  for (const [label, url] of SAMPLES) {
    const link = document.createElement('a');
    link.href = `#player?stream=${url}`;
    link.textContent = label;
    samples.append(link);
  }
  document.getElementById('open').addEventListener('submit', (event) => {
    event.preventDefault();
    const url = document.getElementById('url').value.trim();
    if (url) location.hash = `#${state.view}?stream=${encodeURIComponent(url)}`;
  });
  document.getElementById('file').addEventListener('change', (event) => {
    if (event.target.files[0]) openStream(event.target.files[0]).catch(report);
  });
  document.body.addEventListener('dragover', (event) => {
    event.preventDefault();
    document.body.classList.add('dragging');
  });
  document.body.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
  document.body.addEventListener('drop', (event) => {
    event.preventDefault();
    document.body.classList.remove('dragging');
    const file = event.dataTransfer.files[0];
    if (file) openStream(file).catch(report);
  });
  document.getElementById('run-conformance').addEventListener('click', () => runConformance(module, state).catch(report));
  document.getElementById('run-bench').addEventListener('click', () => runBench(module, state, hashParameters().params).catch(report));

  const route = () => {
    const { view, params } = hashParameters();
    showView(view);
    if (params.get('texture')) state.playerView.setTexture(params.get('texture')).catch(report);
    // The player follows its URL: a frame given is shown, and it plays unless "pause" is there.
    if (view === 'player') state.playerView.start(params.has('frame') ? Math.max(0, Number(params.get('frame')) || 0) : undefined, params.has('pause'));
    if (params.get('stream') && params.get('stream') !== state.source) {
      document.getElementById('url').value = params.get('stream');
      openStream(params.get('stream')).catch(report);
    }
    if (params.get('gltf') && params.get('gltf') !== state.gltf?.url) state.playerView.openGltf(params.get('gltf')).catch(report);
    if (!params.get('gltf')) state.playerView.closeGltf();
    if (view === 'conformance' && params.get('run') !== null && !state.conformance) runConformance(module, state).catch(report);
    if (view === 'bench' && params.get('run') !== null && !state.bench) runBench(module, state, params).catch(report);
  };
  window.addEventListener('hashchange', route);
  route();
}

function report(error) {
  const status = document.getElementById('status');
  status.textContent = String(error.message || error);
  status.classList.add('error');
  state.failure = String(error.message || error);
}

main().catch(report);
