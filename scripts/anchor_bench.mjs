// m4mesh against the tools it replaces, in one run (docs/rate_distortion.md,
// "Against meshoptimizer and Draco"): each sequence of ../shared/data as
// gltfpack -cc (meshoptimizer's EXT_meshopt_compression, morph targets) and
// as Draco per frame (draco3d, edgebreaker), each at the fewest bytes that
// keep the KG error within 0.5 % and 0.1 %, against m4mesh's cpca-wpt
// stream at the same target (scripts/decode_corpus.sh's corpus). For each:
// bytes, brotli bytes, KG and max error (m4mesh metrics on the decoded
// frames), decoding to float32 positions in Node on one thread (the best of
// 5), and the bandwidth above which the other file, downloaded then
// decoded, plays before m4mesh's.
// Usage: node scripts/anchor_bench.mjs [BUILD (default build)] [DATA (default ../shared/data)] [SEQUENCE …]
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { setFlagsFromString } from 'node:v8';
import { runInNewContext } from 'node:vm';
import { SEQUENCES, brotli, gltfpackFile, readGlb, restPoseGlb, sequenceOf, writeGlb } from './gltf_files.mjs';

const root = resolve(new URL('..', import.meta.url).pathname);
const build = resolve(process.argv[2] || join(root, 'build'));
const data = resolve(process.argv[3] || join(root, '..', 'shared', 'data'));
const m4mesh = join(build, 'cli', 'm4mesh');
const modules = join(root, 'web', 'node_modules');
const corpus = join(build, 'decode-corpus');
const work = join(build, 'anchor-bench');
const TARGETS = [0.5, 0.1];
const FPS = 25;
const RUNS = 5;
const context = { m4mesh, data, work, modules, fps: FPS };

if (!existsSync(data)) {
  console.log(`skipped: no ${data}`);
  process.exit(0);
}
mkdirSync(work, { recursive: true });
const { MeshoptDecoder } = await import(join(modules, 'meshoptimizer', 'index.js'));
const draco3d = (await import(join(modules, 'draco3d', 'draco3d.js'))).default;
const { createM4meshDecoder } = await import(join(build, 'web', 'package', 'decoder.js'));
await MeshoptDecoder.ready;
const dracoEncoder = await draco3d.createEncoderModule({});
const dracoDecoder = await draco3d.createDecoderModule({});
const m4meshModule = await createM4meshDecoder();

// Decoded frames in m4mesh's order, written as m4mesh writes a glTF animation (targets are frames), for m4mesh metrics.
function metricsOf(name, sequence, decodedFrames, label) {
  const path = join(work, `${name}-${label}-decoded.glb`);
  const original = readGlb(sequence.absolute);
  const bin = Buffer.from(original.bin);
  const primitive = original.json.meshes[0].primitives[0];
  primitive.targets.forEach((t, k) => {
    const accessor = original.json.accessors[t.POSITION];
    const view = original.json.bufferViews[accessor.bufferView];
    Buffer.from(decodedFrames[k].buffer, decodedFrames[k].byteOffset, decodedFrames[k].byteLength).copy(bin, view.byteOffset || 0);
    delete accessor.min;  // the original frame's bounds, no longer these values'
    delete accessor.max;
  });
  writeGlb(path, original.json, bin);
  const metrics = JSON.parse(execFileSync(m4mesh, ['metrics', sequence.absolute, path, '--json'], { encoding: 'utf8' }));
  return { kg: metrics.kg_error_percent, maxError: metrics.max_error };
}

// Each original vertex's decoded vertex, for one file (the order depends on the setting): the one nearest at frame 0 (a grid of the decoded rest pose), ties between
// coincident vertices broken by the whole trajectory. The decoders reorder (and may merge) vertices.
function vertexMap(sequence, decodedFrames) {
  const { frames, vertices } = sequence;
  const decodedCount = decodedFrames[0].length / 3;
  const rest = decodedFrames[0];
  const { min, max } = (() => {
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < rest.length; ++i) (lo[i % 3] = Math.min(lo[i % 3], rest[i])), (hi[i % 3] = Math.max(hi[i % 3], rest[i]));
    return { min: lo, max: hi };
  })();
  const cell = Math.max(max[0] - min[0], max[1] - min[1], max[2] - min[2]) / Math.cbrt(decodedCount) || 1;
  const key = (x, y, z) => `${x},${y},${z}`;
  const grid = new Map();
  for (let j = 0; j < decodedCount; ++j) {
    const k = key(...[0, 1, 2].map((a) => Math.floor((rest[3 * j + a] - min[a]) / cell)));
    if (!grid.has(k)) grid.set(k, []);
    grid.get(k).push(j);
  }
  const sampled = [0, frames.length >> 2, frames.length >> 1, (3 * frames.length) >> 2, frames.length - 1];
  const cost = (i, j) => {
    let sum = 0;
    for (const f of sampled)
      for (let a = 0; a < 3; ++a) sum += (frames[f][3 * i + a] - decodedFrames[f][3 * j + a]) ** 2;
    return sum;
  };
  const map = new Uint32Array(vertices);
  for (let i = 0; i < vertices; ++i) {
    const c = [0, 1, 2].map((a) => Math.floor((frames[0][3 * i + a] - min[a]) / cell));
    let best = -1, bestCost = Infinity;
    for (let radius = 1; best < 0; ++radius)
      for (let dx = -radius; dx <= radius; ++dx)
        for (let dy = -radius; dy <= radius; ++dy)
          for (let dz = -radius; dz <= radius; ++dz)
            for (const j of grid.get(key(c[0] + dx, c[1] + dy, c[2] + dz)) || []) {
              const value = cost(i, j);
              if (value < bestCost) (bestCost = value), (best = j);
            }
    map[i] = best;
  }
  return map;
}

function reordered(decodedFrames, map) {
  return decodedFrames.map((frame) => {
    const out = new Float32Array(map.length * 3);
    for (let i = 0; i < map.length; ++i) for (let a = 0; a < 3; ++a) out[3 * i + a] = frame[3 * map[i] + a];
    return out;
  });
}

// A full garbage collection before each timed run, so that no decoder pays for the garbage of the one before.
setFlagsFromString('--expose-gc');
const collectGarbage = runInNewContext('gc');

// The best of RUNS after one run that warms the JIT up.
const best = (run) => {
  let ms = Infinity, result = run();
  for (let r = 0; r < RUNS; ++r) {
    result = null;
    collectGarbage();
    const start = performance.now();
    result = run();
    ms = Math.min(ms, performance.now() - start);
  }
  return { ms, result };
};

// ---- gltfpack -cc: the compressed views decoded by meshoptimizer, then each frame's positions to float32 (the rest
// pose plus the frame's target, through the node's dequantizing transform).
// The compressed views decoded (what a loader that keeps gltfpack's quantized positions on the GPU does), or also
// every frame as float32 positions: gltfpack's integer positions and targets through the node's scale and translation.
function decodeGltfpack(glb, toFloat) {
  const views = glb.json.bufferViews.map((view) => {
    const ext = view.extensions && view.extensions.EXT_meshopt_compression;
    if (!ext) return glb.bin.subarray(view.byteOffset || 0, (view.byteOffset || 0) + view.byteLength);
    const target = new Uint8Array(ext.count * ext.byteStride);
    MeshoptDecoder.decodeGltfBuffer(target, ext.count, ext.byteStride, glb.bin.subarray(ext.byteOffset || 0, (ext.byteOffset || 0) + ext.byteLength),
                                    ext.mode, ext.filter);
    return target;
  });
  if (!toFloat) return null;
  const node = glb.json.nodes.find((n) => n.mesh !== undefined);
  const primitive = glb.json.meshes[node.mesh].primitives[0];
  const s = node.scale || [1, 1, 1], t = node.translation || [0, 0, 0];
  const values = (index) => {
    const accessor = glb.json.accessors[index];
    const Type = { 5120: Int8Array, 5121: Uint8Array, 5122: Int16Array, 5123: Uint16Array }[accessor.componentType];
    const view = glb.json.bufferViews[accessor.bufferView], bytes = views[accessor.bufferView];
    if (!Type || accessor.normalized || !view.byteStride) throw new Error(`${index}: gltfpack wrote positions in a form this bench does not read`);
    const stride = view.byteStride / Type.BYTES_PER_ELEMENT;
    return { array: new Type(bytes.buffer, bytes.byteOffset + (accessor.byteOffset || 0), accessor.count * stride), stride };
  };
  const base = values(primitive.attributes.POSITION);
  const count = base.array.length / base.stride;
  return primitive.targets.map((target) => {
    const delta = values(target.POSITION);
    const frame = new Float32Array(count * 3);
    for (let i = 0; i < count; ++i)
      for (let a = 0; a < 3; ++a) frame[3 * i + a] = t[a] + s[a] * (base.array[base.stride * i + a] + delta.array[delta.stride * i + a]);
    return frame;
  });
}

// ---- Draco per frame: each frame a mesh of the same faces, positions quantized to `bits`.
function dracoFile(name, sequence, bits) {
  const path = join(work, `${name}-draco-q${bits}.bin`);
  if (existsSync(path)) return path;
  const chunks = [];
  for (const frame of sequence.frames) {
    const encoder = new dracoEncoder.Encoder(), builder = new dracoEncoder.MeshBuilder(), mesh = new dracoEncoder.Mesh();
    builder.AddFacesToMesh(mesh, sequence.faces.length / 3, sequence.faces);
    builder.AddFloatAttributeToMesh(mesh, dracoEncoder.POSITION, sequence.vertices, 3, frame);
    encoder.SetAttributeQuantization(dracoEncoder.POSITION, bits);
    const buffer = new dracoEncoder.DracoInt8Array();
    const length = encoder.EncodeMeshToDracoBuffer(mesh, buffer);
    const bytes = Buffer.alloc(4 + length);
    bytes.writeUInt32LE(length, 0);
    for (let i = 0; i < length; ++i) bytes[4 + i] = buffer.GetValue(i) & 0xff;
    chunks.push(bytes);
    [buffer, mesh, builder, encoder].forEach((o) => dracoEncoder.destroy(o));
  }
  writeFileSync(path, Buffer.concat(chunks));
  return path;
}

function decodeDraco(path) {
  const bytes = readFileSync(path);
  const decoder = new dracoDecoder.Decoder();
  const frames = [];
  for (let at = 0; at < bytes.length;) {
    const length = bytes.readUInt32LE(at);
    const mesh = new dracoDecoder.Mesh();
    const status = decoder.DecodeArrayToMesh(bytes.subarray(at + 4, at + 4 + length), length, mesh);
    if (!status.ok()) throw new Error(`${path}: ${status.error_msg()}`);
    const attribute = decoder.GetAttribute(mesh, decoder.GetAttributeId(mesh, dracoDecoder.POSITION));
    const count = mesh.num_points() * 3;
    const pointer = dracoDecoder._malloc(count * 4);
    decoder.GetAttributeDataArrayForAllPoints(mesh, attribute, dracoDecoder.DT_FLOAT32, count * 4, pointer);
    frames.push(new Float32Array(dracoDecoder.HEAPF32.buffer, pointer, count).slice());
    dracoDecoder._free(pointer);
    dracoDecoder.destroy(mesh);
    at += 4 + length;
  }
  dracoDecoder.destroy(decoder);
  return frames;
}

// ---- m4mesh: the npm package's module, every frame taken as float32 positions.
function decodeM4mesh(path) {
  const stream = new m4meshModule.Stream3d();
  stream.push(readFileSync(path));
  const status = JSON.parse(stream.end());
  if (status.error) throw new Error(`${path}: ${status.error.text}`);
  for (let f = 0; f < status.header.frames; ++f) stream.frame(f);
  stream.delete();
}

// The fewest bytes at each KG target over a tool's settings (coarsest first).
function smallestWithin(settings, make) {
  const chosen = {};
  for (const setting of settings) {
    const entry = make(setting);
    for (const target of TARGETS) if (entry.kg <= target && !chosen[target]) chosen[target] = { ...entry, setting };
    if (TARGETS.every((target) => chosen[target])) break;
  }
  return chosen;
}

// Above this many bit/s the other file, downloaded then decoded, plays first; null: m4mesh plays first at every
// bandwidth, 0: at none.
const breakEven = (m4, other) => {
  if (other.ms >= m4.ms) return other.bytes >= m4.bytes ? null : 0;
  return other.bytes <= m4.bytes ? 0 : (8 * (other.bytes - m4.bytes)) / ((m4.ms - other.ms) / 1000);
};

const rows = [];
const chosenSequences = process.argv.length > 4 ? process.argv.slice(4) : Object.keys(SEQUENCES);
for (const name of chosenSequences) {
  if (!SEQUENCES[name]) throw new Error(`no sequence ${name}: ${Object.keys(SEQUENCES).join(', ')}`);
  if (!existsSync(join(data, SEQUENCES[name]))) continue;
  process.stderr.write(`${name}\n`);
  const sequence = sequenceOf(context, name);
  const vertexFrames = sequence.vertices * sequence.frames.length;
  const rest = restPoseGlb(context, name, sequence);
  const gltfpack = smallestWithin([8, 9, 10, 11, 12, 13, 14, 15, 16], (bits) => {
    const path = gltfpackFile(context, name, rest, bits);
    const glb = readGlb(path);
    const stored = best(() => decodeGltfpack(glb, false)).ms;
    const { ms, result } = best(() => decodeGltfpack(glb, true));
    return { path, bytes: readFileSync(path).length, ms, stored, ...metricsOf(name, sequence, reordered(result, vertexMap(sequence, result)), `gltfpack-vp${bits}`) };
  });
  const draco = smallestWithin([8, 9, 10, 11, 12, 13, 14, 15, 16], (bits) => {
    const path = dracoFile(name, sequence, bits);
    const { ms, result } = best(() => decodeDraco(path));
    return { path, bytes: readFileSync(path).length, ms, ...metricsOf(name, sequence, reordered(result, vertexMap(sequence, result)), `draco-q${bits}`) };
  });
  for (const target of TARGETS) {
    const stream = join(corpus, `${name}-cpca-wpt-${target}.m4m`);
    if (!existsSync(stream)) {
      process.stderr.write(`  no ${stream} (scripts/decode_corpus.sh makes it): left out\n`);
      continue;
    }
    const m4 = { bytes: readFileSync(stream).length, ms: best(() => decodeM4mesh(stream)).ms };
    const metrics = JSON.parse(execFileSync(m4mesh, ['metrics', sequence.absolute, stream, '--json'], { encoding: 'utf8' }));
    m4.brotli = brotli(stream);
    const row = { sequence: name, target, vertexFrames, m4mesh: { ...m4, kg: metrics.kg_error_percent, maxError: metrics.max_error } };
    for (const [tool, chosen] of [['gltfpack', gltfpack], ['draco', draco]]) {
      const entry = chosen[target];
      if (!entry) continue;
      row[tool] = { setting: entry.setting, bytes: entry.bytes, brotli: brotli(entry.path), kg: entry.kg, maxError: entry.maxError, ms: entry.ms, storedMs: entry.stored };
      row[tool].breakEvenMbps = breakEven({ bytes: m4.brotli, ms: m4.ms }, { bytes: row[tool].brotli, ms: entry.ms });
    }
    rows.push(row);
  }
}
writeFileSync(join(work, 'results.json'), JSON.stringify(rows, null, 1));

const mvf = (row, entry) => (row.vertexFrames / (entry.ms / 1000) / 1e6).toFixed(1);
const kb = (bytes) => (bytes / 1000).toFixed(1);
const mbps = (bits) => (bits === null ? 'never' : `${(bits / 1e6).toFixed(1)}`);
console.log('| sequence | KG ≤ | m4mesh cpca-wpt: kB (brotli) · KG · M vf/s | gltfpack -cc: -vp · kB (brotli) · KG · M vf/s | break-even Mbit/s | Draco per frame: -qp · kB (brotli) · KG · M vf/s | break-even Mbit/s |');
console.log('|---|---|---|---|---|---|---|');
for (const row of rows) {
  const cells = [row.sequence, row.target];
  const m = row.m4mesh;
  cells.push(`${kb(m.bytes)} (${kb(m.brotli)}) · ${m.kg.toFixed(3)} · ${mvf(row, m)}`);
  for (const tool of ['gltfpack', 'draco']) {
    const e = row[tool];
    cells.push(e ? `${e.setting} · ${kb(e.bytes)} (${kb(e.brotli)}) · ${e.kg.toFixed(3)} · ${mvf(row, e)}` : 'out of reach', e ? mbps(e.breakEvenMbps) : '');
  }
  console.log(`| ${cells.join(' | ')} |`);
}
console.log(`(${work}/results.json has the max errors, the times, and gltfpack's decoding alone as storedMs, positions left quantized)`);
