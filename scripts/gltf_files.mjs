// What the benches against glTF tools share (scripts/anchor_bench.mjs,
// scripts/gltf_bench.mjs): the sequences of ../shared/data, GLB files read
// and written, a sequence as m4mesh's glTF and as an artist's (the rest pose
// and morph targets of differences), gltfpack -cc files, brotli sizes.
// `context`: { m4mesh, data, work, modules, fps }.
import { execFileSync } from 'node:child_process';
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { brotliCompressSync, constants } from 'node:zlib';

export const SEQUENCES = { horse: 'horse-gallop', cow: 'pcow', flag: 'cloth/flag/flag.pc2', dance: 'openfamc_testdata/dance_mesh',
                           dog: 'openfamc_testdata/dog_mesh', handstand: 'openfamc_testdata/handstand_mesh' };

// ---- glb files: a JSON chunk and a BIN chunk.
export function readGlb(path) {
  const bytes = readFileSync(path);
  const jsonLength = bytes.readUInt32LE(12);
  const json = JSON.parse(bytes.subarray(20, 20 + jsonLength).toString('utf8'));
  const binStart = 20 + jsonLength + 8;
  return { json, bin: bytes.subarray(binStart, binStart + bytes.readUInt32LE(20 + jsonLength)) };
}

export function writeGlb(path, json, bin) {
  const pad = (buffer, fill) => Buffer.concat([buffer, Buffer.alloc((4 - (buffer.length % 4)) % 4, fill)]);
  const jsonChunk = pad(Buffer.from(JSON.stringify(json)), 0x20), binChunk = pad(Buffer.from(bin), 0);
  const header = Buffer.alloc(12), jsonHeader = Buffer.alloc(8), binHeader = Buffer.alloc(8);
  header.write('glTF', 0), header.writeUInt32LE(2, 4), header.writeUInt32LE(12 + 8 + jsonChunk.length + 8 + binChunk.length, 8);
  jsonHeader.writeUInt32LE(jsonChunk.length, 0), jsonHeader.write('JSON', 4);
  binHeader.writeUInt32LE(binChunk.length, 0), binHeader.write('BIN\0', 4);
  writeFileSync(path, Buffer.concat([header, jsonHeader, jsonChunk, binHeader, binChunk]));
}

// A tightly packed accessor of m4mesh's own glTF (uint32 indices, float32 positions), copied.
export function accessorArray({ json, bin }, index, Type) {
  const accessor = json.accessors[index];
  const view = json.bufferViews[accessor.bufferView];
  const components = { SCALAR: 1, VEC3: 3 }[accessor.type];
  const start = bin.byteOffset + (view.byteOffset || 0) + (accessor.byteOffset || 0);
  return new Type(bin.buffer.slice(start, start + accessor.count * components * Type.BYTES_PER_ELEMENT));
}

// The sequence as m4mesh reads it (convert to a glTF whose targets are the frames), then as an artist's file: the
// rest pose (frame 0) and one morph target per frame of its differences, a STEP weights animation.
export function sequenceOf({ m4mesh, data, work, fps }, name) {
  const absolute = join(work, `${name}-frames.glb`);
  if (!existsSync(absolute)) execFileSync(m4mesh, ['-q', '-y', 'convert', join(data, SEQUENCES[name]), absolute, '--fps', String(fps)]);
  const glb = readGlb(absolute);
  const primitive = glb.json.meshes[0].primitives[0];
  const faces = accessorArray(glb, primitive.indices, Uint32Array);
  const frames = primitive.targets.map((t) => accessorArray(glb, t.POSITION, Float32Array));
  return { absolute, faces, frames, vertices: frames[0].length / 3 };
}

export function restPoseGlb({ work, fps }, name, sequence) {
  const path = join(work, `${name}-rest.glb`);
  const { faces, frames, vertices } = sequence;
  const parts = [], views = [], accessors = [];
  let offset = 0;
  const add = (typed, accessor) => {
    const bytes = Buffer.from(typed.buffer, typed.byteOffset, typed.byteLength);
    views.push({ buffer: 0, byteOffset: offset, byteLength: bytes.length });
    parts.push(bytes), (offset += bytes.length);
    accessors.push({ bufferView: views.length - 1, ...accessor });
    return accessors.length - 1;
  };
  const bounds = (values) => {
    const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < values.length; ++i) (min[i % 3] = Math.min(min[i % 3], values[i])), (max[i % 3] = Math.max(max[i % 3], values[i]));
    return { min, max };
  };
  const indices = add(faces, { componentType: 5125, count: faces.length, type: 'SCALAR' });
  const position = add(frames[0], { componentType: 5126, count: vertices, type: 'VEC3', ...bounds(frames[0]) });
  const targets = frames.map((frame) => {
    const delta = new Float32Array(frame.length);
    for (let i = 0; i < frame.length; ++i) delta[i] = frame[i] - frames[0][i];
    return { POSITION: add(delta, { componentType: 5126, count: vertices, type: 'VEC3', ...bounds(delta) }) };
  });
  const times = add(Float32Array.from(frames, (_, k) => k / fps), { componentType: 5126, count: frames.length, type: 'SCALAR', min: [0], max: [(frames.length - 1) / fps] });
  const weights = new Float32Array(frames.length * frames.length);
  for (let k = 0; k < frames.length; ++k) weights[k * frames.length + k] = 1;
  const weightValues = add(weights, { componentType: 5126, count: weights.length, type: 'SCALAR' });
  const json = {
    asset: { version: '2.0', generator: 'm4mesh anchor_bench' }, scene: 0, scenes: [{ nodes: [0] }], nodes: [{ mesh: 0, name }],
    meshes: [{ primitives: [{ attributes: { POSITION: position }, indices, targets }], weights: new Array(frames.length).fill(0) }],
    animations: [{ samplers: [{ input: times, output: weightValues, interpolation: 'STEP' }], channels: [{ sampler: 0, target: { node: 0, path: 'weights' } }] }],
    accessors, bufferViews: views, buffers: [{ byteLength: offset }],
  };
  writeGlb(path, json, Buffer.concat(parts));
  return path;
}

// gltfpack -cc at `bits` of position quantization (-vp) of a rest-pose file, made once.
export function gltfpackFile({ work, modules }, name, rest, bits) {
  const path = join(work, `${name}-gltfpack-vp${bits}.glb`);
  if (!existsSync(path)) execFileSync('node', [join(modules, 'gltfpack', 'cli.js'), '-i', rest, '-o', path, '-cc', '-vp', String(bits)], { stdio: 'ignore' });
  return path;
}

export const brotli = (path) => brotliCompressSync(readFileSync(path), { params: { [constants.BROTLI_PARAM_QUALITY]: 11 } }).length;
