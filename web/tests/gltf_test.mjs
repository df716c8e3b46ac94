// M4MESH_vertex_animation end to end, in Node: glTF files with a
// morph-target animation and what else a real asset has (a textured
// material, normals and UVs, another mesh, a camera, another animation,
// extras), built with glTF-Transform from m4mesh's own glTF of a sequence
// (a tetrahedron's, and the horse's, the cow's and the flag's);
// `m4mesh gltf` compresses each; then
// - the Khronos validator reports no error on the input or the output;
// - three.js's GLTFLoader with the npm package's M4MeshGLTFPlugin plays
//   the animation's clip with, at every key, each vertex exactly where
//   `m4mesh decode3d` puts it (the stream taken out of the file), in Node
//   and in Chromium (decoding in the package's worker, the file over HTTP);
// - GLTFLoader without the plugin shows the rest pose (the input's POSITION);
// - every part of the input but the replaced morph targets and weights is in
//   the output: materials, textures, cameras, nodes, scenes, extras value for
//   value, the image byte for byte, the other channels' keys and values;
// - glTF-Transform, with the package's extension, reads the output and
//   writes it back, and that file plays exactly the same;
// - a skinned tube Blender exported, compressed with --bake-skins, is valid
//   and plays its stream exactly in Node and in Chromium;
// - a file compressed already, and one without morph targets, are refused.
// Usage: node gltf_test.mjs M4MESH PACKAGE_DIR SOURCE_DIR [DATA_DIR]
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { extname, join, normalize } from 'node:path';
import { pathToFileURL } from 'node:url';
import { NodeIO } from '@gltf-transform/core';
import validator from 'gltf-validator';
import { installPackage, launch } from './harness.mjs';

const [m4mesh, packageDir, source, data] = process.argv.slice(2);
const work = mkdtempSync(join(tmpdir(), 'm4mesh-gltf-'));
let failures = 0;
const check = (ok, what) => {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
};

// A GLB's JSON and BIN chunks.
function glbParts(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const jsonLength = view.getUint32(12, true);
  const json = JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + jsonLength)));
  const binAt = 20 + jsonLength;
  const bin = binAt < bytes.length ? bytes.subarray(binAt + 8, binAt + 8 + view.getUint32(binAt, true)) : new Uint8Array(0);
  return { json, bin };
}
const viewBytes = ({ json, bin }, index) => {
  const view = json.bufferViews[index];
  return bin.subarray(view.byteOffset ?? 0, (view.byteOffset ?? 0) + view.byteLength);
};

// m4mesh's glTF of a sequence (every frame an absolute target over zeros)
// made into an asset as an artist's tool writes it: POSITION the first
// frame (the rest pose), targets its differences, with normals, UVs, a
// textured material, a second mesh and node with a camera, a second
// animation turning it, and extras; `moveNode` also gives the animated
// node a translation channel in the same animation.
async function makeAsset(frames, path, { moveNode = false } = {}) {
  const raw = join(work, 'raw.glb');
  execFileSync(m4mesh, ['-q', '-y', 'convert', frames, raw]);
  const io = new NodeIO();
  const doc = await io.read(raw);
  const root = doc.getRoot();
  const buffer = root.listBuffers()[0];
  const primitive = root.listMeshes()[0].listPrimitives()[0];
  const targets = primitive.listTargets();
  const rest = targets[0].getAttribute('POSITION').getArray().slice();
  primitive.getAttribute('POSITION').setArray(rest);
  for (const target of targets) {
    const values = target.getAttribute('POSITION').getArray().slice();
    for (let i = 0; i < values.length; ++i) values[i] -= rest[i];
    target.getAttribute('POSITION').setArray(values);
  }
  const vertices = rest.length / 3;
  const uv = new Float32Array(2 * vertices).map((_, i) => (i % 2 ? rest[3 * (i >> 1) + 1] : rest[3 * (i >> 1)]));
  const normal = new Float32Array(3 * vertices).map((_, i) => (i % 3 === 2 ? 1 : 0));
  primitive.setAttribute('TEXCOORD_0', doc.createAccessor('uv').setType('VEC2').setArray(uv).setBuffer(buffer));
  primitive.setAttribute('NORMAL', doc.createAccessor('normal').setType('VEC3').setArray(normal).setBuffer(buffer));
  const png = readFileSync(join(source, 'docs', 'figures', 'gltf-horse-blender.png'));
  const texture = doc.createTexture('painting').setImage(png).setMimeType('image/png');
  primitive.setMaterial(doc.createMaterial('painted').setBaseColorTexture(texture).setRoughnessFactor(0.25).setExtras({ kept: 'material' }));
  root.listMeshes()[0].setExtras({ targetNames: targets.map((_, k) => `frame ${k}`), kept: 'mesh' });

  const triangle = doc.createPrimitive()
    .setAttribute('POSITION', doc.createAccessor('triangle').setType('VEC3').setArray(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0])).setBuffer(buffer));
  const still = doc.createNode('still').setMesh(doc.createMesh('triangle').addPrimitive(triangle)).setTranslation([2, 0, 0]).setExtras({ kept: 'node' });
  const eye = doc.createNode('eye').setCamera(doc.createCamera('lens').setType('perspective').setYFov(0.8).setZNear(0.01)).setTranslation([0, 1, 5]);
  root.listScenes()[0].addChild(still).addChild(eye);
  const keys = (values) => doc.createAccessor().setArray(new Float32Array(values)).setBuffer(buffer);
  const spin = doc.createAnimationSampler().setInput(keys([0, 1])).setOutput(keys([0, 0, 0, 1, 0, 0.7071068, 0, 0.7071068]).setType('VEC4'))
    .setInterpolation('LINEAR');
  doc.createAnimation('spin').addSampler(spin).addChannel(doc.createAnimationChannel().setTargetNode(still).setTargetPath('rotation').setSampler(spin));
  if (moveNode) {
    const animation = root.listAnimations()[0];
    const slide = doc.createAnimationSampler().setInput(keys([0, 1])).setOutput(keys([0, 0, 0, 0, 0.5, 0]).setType('VEC3'));
    animation.addSampler(slide).addChannel(doc.createAnimationChannel().setTargetNode(root.listNodes()[0]).setTargetPath('translation').setSampler(slide));
  }
  root.setExtras({ kept: 'asset' });
  await io.write(path, doc);
  rmSync(raw);
}

async function validate(bytes, what) {
  const report = await validator.validateBytes(new Uint8Array(bytes), { maxIssues: 100 });
  const errors = report.issues.messages.filter((m) => m.severity === 0);
  check(errors.length === 0, `${what}: the Khronos validator reports ${report.issues.numErrors} errors${errors.length ? `: ${errors.slice(0, 3).map((m) => `${m.code} ${m.pointer} ${m.message}`).join('; ')}` : ''}`);
}

// A value without the members the compressor is allowed to change.
const without = (value, keys) => Object.fromEntries(Object.entries(value ?? {}).filter(([k]) => !keys.includes(k)));
const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);

try {
  const app = installPackage(packageDir, source, work, ['@gltf-transform/core']);
  const modules = join(app, 'node_modules');
  const THREE = await import(pathToFileURL(join(modules, 'three', 'build', 'three.module.js')));
  const { GLTFLoader } = await import(pathToFileURL(join(modules, 'three', 'examples', 'jsm', 'loaders', 'GLTFLoader.js')));
  const { M4MeshGLTFPlugin } = await import(pathToFileURL(join(modules, 'm4mesh', 'index.js')));
  const { M4MeshVertexAnimation } = await import(pathToFileURL(join(modules, 'm4mesh', 'M4MeshGLTFTransform.js')));
  // Node has no image decoder: textures load as empty ones (the image bytes are checked in the file).
  const noImages = () => ({ name: 'no-images', loadTexture: async () => new THREE.Texture() });
  const load = (bytes, plugin) =>
    new Promise((resolve, reject) => {
      const loader = new GLTFLoader().register(noImages);
      if (plugin) loader.register((parser) => new M4MeshGLTFPlugin(parser));
      loader.parse(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength), '', resolve, reject);
    });

  // three.js with the plugin: at every key, every vertex where decode3d puts it.
  async function playsExactly(bytes, decoded, asset, what) {
    const gltf = await load(bytes, true);
    const mesh = gltf.scene.getObjectByProperty('isMesh', true);
    const clip = gltf.animations[0];
    const times = clip.tracks.find((t) => t.name.endsWith('.morphTargetInfluences')).times;
    const vertices = mesh.geometry.attributes.position.count;
    check(times.length * vertices * 3 === decoded.length, `${what}: ${times.length} keys of ${vertices} vertices, as many as decode3d's frames`);
    const mixer = new THREE.AnimationMixer(gltf.scene);
    mixer.clipAction(clip).setLoop(THREE.LoopOnce, 1).play().clampWhenFinished = true;  // the last key shown, not wrapped to the first
    const point = new THREE.Vector3();
    let wrong = 0, compared = 0;
    for (let k = 0; k < times.length; ++k) {
      mixer.setTime(times[k]);
      for (let v = 0; v < vertices; ++v, compared += 3) {
        mesh.getVertexPosition(v, point);
        const at = 3 * (k * vertices + v);
        if (point.x !== decoded[at] || point.y !== decoded[at + 1] || point.z !== decoded[at + 2]) wrong++;
      }
    }
    check(wrong === 0, `${what}: three.js plays ${compared} coordinates at the keys, ${compared - 3 * wrong} of them exactly decode3d's`);
    check(mesh.geometry.morphAttributes.normal?.length === times.length, `${what}: a normal per frame, computed from its positions`);
    if (asset.moveNode) {
      const sliding = new THREE.AnimationMixer(gltf.scene);
      sliding.clipAction(clip).play();
      sliding.setTime(1);
      check(mesh.position.y === 0.5, `${what}: the same animation's translation channel still plays (y ${mesh.position.y} at 1 s)`);
    }
  }

  // The file's one stream taken out and decoded by m4mesh decode3d.
  function decodedStream(parts, name) {
    const extension = parts.json.animations[0].extensions?.M4MESH_vertex_animation;
    check(extension?.channels?.length === 1 && extension.channels[0].primitives.length === 1, `${name}: one channel of one primitive's stream`);
    const stream = join(work, `${name}.m4m`), decodedPath = join(work, `${name}.f32`);
    writeFileSync(stream, viewBytes(parts, extension.channels[0].primitives[0].bufferView));
    execFileSync(m4mesh, ['-q', '-y', 'decode3d', stream, '-o', decodedPath]);
    const bytes = readFileSync(decodedPath);
    return new Float32Array(bytes.buffer, bytes.byteOffset, bytes.length / 4);
  }

  const assets = [{ name: 'tetra', frames: join(source, 'tests', 'data', 'tetra-frames'), args: ['--codec', 'bfs3d'] }];
  // The project's sequences, when ../shared/data is there.
  for (const [name, path, extra] of [['horse', 'horse-gallop', { moveNode: true }], ['cow', 'pcow', {}], ['flag', 'cloth/flag/flag.pc2', {}]]) {
    const frames = data && join(data, path);
    if (frames && existsSync(frames)) assets.push({ name, frames, args: ['--target-kg', '0.5', '--codec', 'bfs3d'], ...extra });
    else console.log(`skip the ${name}: no ${frames ?? '../shared/data'}`);
  }

  const played = [];  // the compressed files and their decoded frames, for Chromium
  for (const asset of assets) {
    const input = join(work, `${asset.name}.glb`), output = join(work, `${asset.name}-m4mesh.glb`);
    await makeAsset(asset.frames, input, asset);
    execFileSync(m4mesh, ['-q', 'gltf', input, '-o', output, ...asset.args]);
    const before = readFileSync(input), after = readFileSync(output);
    console.log(`${asset.name}: ${before.length} bytes, compressed ${after.length}`);
    await validate(before, `${asset.name}: the input`);
    await validate(after, `${asset.name}: the output`);
    const a = glbParts(before), b = glbParts(after);

    const decoded = decodedStream(b, asset.name);

    await playsExactly(after, decoded, asset, asset.name);
    played.push({ file: `${asset.name}-m4mesh.glb`, decoded, name: asset.name });
    // Without the plugin: the rest pose.
    const plain = await load(after, false);
    const still = plain.scene.getObjectByProperty('isMesh', true);
    const rest = (await new NodeIO().readBinary(new Uint8Array(before))).getRoot().listMeshes()[0].listPrimitives()[0].getAttribute('POSITION').getArray();
    const shown = still.geometry.attributes.position;
    const restShown = Array.from({ length: 3 * shown.count }, (_, i) => [shown.getX, shown.getY, shown.getZ][i % 3].call(shown, Math.floor(i / 3)));
    check(same(restShown, Array.from(rest)) && !still.geometry.morphAttributes.position,
      `${asset.name}: without the plugin, the rest pose and no morph targets`);

    // Everything else as it was.
    for (const key of ['materials', 'textures', 'samplers', 'cameras', 'scenes', 'scene', 'extras', 'asset'])
      check(same(a.json[key], b.json[key]), `${asset.name}: ${key} as in the input`);
    check(same(a.json.nodes.map((n) => without(n, ['weights'])), b.json.nodes), `${asset.name}: nodes as in the input (their default weights gone)`);
    // Accessors are renumbered: primitives compare by their attributes' bytes.
    const primitives = (parts, mesh) => parts.json.meshes[mesh].primitives.map((p) => [without(p, ['attributes', 'indices', 'targets']),
      ...Object.entries(p.attributes).map(([name, index]) => [name, Buffer.from(viewBytes(parts, parts.json.accessors[index].bufferView)).toString('base64')])]);
    check(same(without(a.json.meshes[0], ['weights', 'primitives', 'extras']), without(b.json.meshes[0], ['primitives', 'extras'])) &&
      same(without(a.json.meshes[0].extras, ['targetNames']), b.json.meshes[0].extras) && same(primitives(a, 0), primitives(b, 0)) &&
      a.json.meshes.length === b.json.meshes.length && a.json.meshes.slice(1).every((m, i) => same(without(m, ['primitives']), without(b.json.meshes[i + 1], ['primitives'])) && same(primitives(a, i + 1), primitives(b, i + 1))),
      `${asset.name}: meshes as in the input, but for the morph targets, their weights and names`);
    const imageOf = (parts) => viewBytes(parts, parts.json.images[0].bufferView);
    check(Buffer.compare(imageOf(a), imageOf(b)) === 0 && a.json.images[0].mimeType === b.json.images[0].mimeType, `${asset.name}: the image byte for byte`);
    const channels = (parts, animation) =>
      parts.json.animations[animation].channels.filter((c) => c.target.path !== 'weights').map((c) => {
        const s = parts.json.animations[animation].samplers[c.sampler];
        const bytesOf = (index) => Buffer.from(viewBytes(parts, parts.json.accessors[index].bufferView)).toString('base64');
        return [c.target, s.interpolation, bytesOf(s.input), bytesOf(s.output)];
      });
    check(same(channels(a, 1), channels(b, 1)) && a.json.animations[1].name === b.json.animations[1].name, `${asset.name}: the other animation's keys and values`);
    if (asset.moveNode) check(same(channels(a, 0), channels(b, 0)), `${asset.name}: the animation's other channel's keys and values`);
    else check(b.json.animations[0].channels.length === 1 && b.json.animations[0].channels[0].target.path === 'translation',
      `${asset.name}: the animation, left without a channel, holds its node's translation`);

    const io = new NodeIO().registerExtensions([M4MeshVertexAnimation]);
    const transformed = await io.readBinary(new Uint8Array(after));
    const channel = transformed.getRoot().listAnimations()[0].getExtension('M4MESH_vertex_animation')?.listChannels()[0];
    check(channel?.listStreams().length === 1 && channel.getInput().getCount() === decoded.length / 3 / channel.getNode().getMesh().listPrimitives()[0].getAttribute('POSITION').getCount(),
      `${asset.name}: glTF-Transform reads the extension: its node, its ${channel?.getInput().getCount()} key times and its stream`);
    const rewritten = Buffer.from(await io.writeBinary(transformed));
    await validate(rewritten, `${asset.name}: written back by glTF-Transform`);
    await playsExactly(rewritten, decoded, asset, `${asset.name}, written back by glTF-Transform`);
  }

  // A skin Blender's exporter wrote (tests/data/blender-tube-skin.glb, tests/blender/export_gltf.py's tube: a textured
  // material, a placed armature), compressed with --bake-skins: valid, a mesh that is no longer skinned, whose
  // clip plays the stream's frames exactly (the rest of that file: ctest blender_gltf).
  {
    const output = join(work, 'tube-m4mesh.glb');
    execFileSync(m4mesh, ['-q', 'gltf', join(source, 'tests', 'data', 'blender-tube-skin.glb'), '-o', output, '--codec', 'bfs3d', '--bake-skins']);
    const after = readFileSync(output);
    await validate(after, 'tube, its skin baked: the output');
    const decoded = decodedStream(glbParts(after), 'tube');
    await playsExactly(after, decoded, {}, 'tube, its skin baked');
    const gltf = await load(after, true);
    check(!gltf.scene.getObjectByProperty('isSkinnedMesh', true), 'tube, its skin baked: a mesh, no longer a skinned one');
    // In the world, at every key, where three.js skins the uncompressed file's tube (within the stream's error).
    const skinned = await load(readFileSync(join(source, 'tests', 'data', 'blender-tube-skin.glb')), false);
    const baked = gltf.scene.getObjectByProperty('isMesh', true), original = skinned.scene.getObjectByProperty('isSkinnedMesh', true);
    const players = [gltf, skinned].map((g) => {
      const mixer = new THREE.AnimationMixer(g.scene);
      mixer.clipAction(g.animations[0]).setLoop(THREE.LoopOnce, 1).play().clampWhenFinished = true;
      return mixer;
    });
    const times = gltf.animations[0].tracks.find((t) => t.name.endsWith('.morphTargetInfluences')).times;
    const p = new THREE.Vector3(), q = new THREE.Vector3();
    let farthest = 0;
    for (const t of times) {
      players.forEach((mixer) => mixer.setTime(t));
      gltf.scene.updateMatrixWorld(true), skinned.scene.updateMatrixWorld(true);
      for (let v = 0; v < original.geometry.attributes.position.count; ++v)
        farthest = Math.max(farthest, baked.localToWorld(baked.getVertexPosition(v, p)).distanceTo(original.localToWorld(original.getVertexPosition(v, q))));
    }
    check(farthest < 1e-3, `tube, its skin baked: in the world, at its ${times.length} keys, every vertex within ${farthest.toExponential(1)} of the skinned original's`);
    played.push({ file: 'tube-m4mesh.glb', decoded, name: 'tube, its skin baked' });
  }

  // Chromium: the package and three.js through an import map, each file over HTTP, decoded in the package's worker.
  writeFileSync(join(app, 'index.html'), `<!doctype html><script type="importmap">
{"imports": {"three": "/node_modules/three/build/three.module.js", "three/addons/": "/node_modules/three/examples/jsm/", "m4mesh": "/node_modules/m4mesh/index.js"}}
</script><script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { M4MeshGLTFPlugin } from 'm4mesh';
// Every vertex three.js evaluates at every key of the first animation's vertex track, as float32 bytes in base64.
window.play = (url) => new GLTFLoader().register((parser) => new M4MeshGLTFPlugin(parser)).loadAsync(url).then((gltf) => {
  const mesh = gltf.scene.getObjectByProperty('isMesh', true);
  const clip = gltf.animations[0];
  const times = clip.tracks.find((t) => t.name.endsWith('.morphTargetInfluences')).times;
  const mixer = new THREE.AnimationMixer(gltf.scene);
  mixer.clipAction(clip).setLoop(THREE.LoopOnce, 1).play().clampWhenFinished = true;
  const count = mesh.geometry.attributes.position.count, out = new Float32Array(times.length * count * 3), point = new THREE.Vector3();
  for (let k = 0; k < times.length; ++k) {
    mixer.setTime(times[k]);
    for (let v = 0; v < count; ++v) mesh.getVertexPosition(v, point).toArray(out, 3 * (k * count + v));
  }
  let text = '';
  const bytes = new Uint8Array(out.buffer);
  for (let i = 0; i < bytes.length; i += 8192) text += String.fromCharCode(...bytes.subarray(i, i + 8192));
  return { positions: btoa(text) };
}, (error) => ({ error: String(error.message) }));
</script>`);
  const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.wasm': 'application/wasm', '.glb': 'model/gltf-binary' };
  const server = createServer((request, response) => {
    const path = decodeURIComponent(new URL(request.url, 'http://x').pathname);
    const file = path.startsWith('/files/') ? join(work, normalize(path.slice('/files/'.length))) : join(app, normalize(path === '/' ? '/index.html' : path));
    try {
      const body = readFileSync(file);
      response.writeHead(200, { 'content-type': types[extname(file)] ?? 'application/octet-stream', 'content-length': statSync(file).size }).end(body);
    } catch {
      response.writeHead(404).end();
    }
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const browser = await launch();
  try {
    const page = await browser.newPage();
    page.on('pageerror', (error) => check(false, `Chromium page error: ${error.message}`));
    await page.goto(`http://127.0.0.1:${server.address().port}/`);
    await page.waitForFunction(() => typeof window.play === 'function');
    for (const { file, decoded, name } of played) {
      const result = await page.evaluate((url) => window.play(url), `/files/${file}`);
      const positions = result.positions && new Float32Array(new Uint8Array(Buffer.from(result.positions, 'base64')).buffer);
      check(positions && positions.length === decoded.length && positions.every((x, i) => x === decoded[i]),
        `Chromium: ${name}: ${positions?.length ?? 0} coordinates three.js plays at the keys, exactly decode3d's${result.error ? `: ${result.error}` : ''}`);
    }
  } finally {
    await browser.close();
    server.close();
  }

  // What the compressor refuses, and says why.
  const refused = (file, says, what) => {
    const run = spawnSync(m4mesh, ['gltf', file, '-o', join(work, 'refused.glb')], { encoding: 'utf8' });
    check(run.status !== 0 && says.test(run.stderr) && !existsSync(join(work, 'refused.glb')), `${what}: refused (${run.stderr.trim()})`);
  };
  refused(join(work, 'tetra-m4mesh.glb'), /M4MESH_vertex_animation already/, 'a compressed file');
  const io = new NodeIO();
  const doc = await io.read(join(work, 'tetra.glb'));
  for (const p of doc.getRoot().listMeshes()[0].listPrimitives()) for (const t of p.listTargets()) t.dispose();
  for (const a of doc.getRoot().listAnimations()) a.dispose();
  await io.write(join(work, 'static.glb'), doc);
  refused(join(work, 'static.glb'), /no animation drives morph targets/, 'a file without morph-target animation');
} catch (error) {
  check(false, error.stack);
} finally {
  rmSync(work, { recursive: true, force: true });
}
console.log(failures ? `${failures} failed` : 'all passed');
process.exit(failures ? 1 : 0);
