// The player: a 3D stream shaded under an orbit camera, decoded as it
// downloads (a progressive stream plays from its base mesh on and refines
// at every unit); a 2D stream as the texture warped by every plane.
// Decoding runs in the npm package's Web Worker (m4mesh/worker.js, from
// web/package/): the page asks it for
// the frames it shows. What it shows is recorded in state.player for the
// tests.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

// A checkerboard texture for 2D streams opened without one (as `m4mesh render`).
function checkerboard(size = 256, square = 16) {
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = size;
  const context = canvas.getContext('2d');
  for (let y = 0; y < size; y += square)
    for (let x = 0; x < size; x += square) {
      const shade = Math.round((255 * x) / size);
      context.fillStyle = ((x + y) / square) % 2 ? '#ffffff' : `rgb(${shade},90,${200 - shade / 2})`;
      context.fillRect(x, y, square, square);
    }
  const texture = new THREE.CanvasTexture(canvas);
  texture.colorSpace = THREE.SRGBColorSpace;
  return texture;
}

// The texts of a PNG's tEXt chunks before its image data, keyword → text
// (none for another format).
function pngTexts(bytes) {
  const texts = {}, view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength), latin1 = new TextDecoder('latin1');
  if (bytes.length < 8 || view.getUint32(0) !== 0x89504e47) return texts;
  for (let at = 8; at + 12 <= bytes.length;) {
    const length = view.getUint32(at), type = latin1.decode(bytes.subarray(at + 4, at + 8));
    if (type === 'IDAT' || length > bytes.length - at - 12) break;
    if (type === 'tEXt') {
      const data = bytes.subarray(at + 8, at + 8 + length), zero = data.indexOf(0);
      if (zero >= 0) texts[latin1.decode(data.subarray(0, zero))] = latin1.decode(data.subarray(zero + 1));
    }
    at += 12 + length;
  }
  return texts;
}

// The tiles of a texture for several I-planes, as `track` writes them and
// `m4mesh render` reads them (render/image.h): its "I-planes" text lists
// their planes, its "I-plane columns" text (else 1) the columns, the k-th
// tile at column k mod columns, row k / columns. Null for one texture.
function textureTiles(texts, width, height, name) {
  const list = texts['I-planes'], columnsText = texts['I-plane columns'] ?? '1';
  if (list === undefined) return null;
  const planes = list.trim().split(/\s+/).map(Number), columns = Number(columnsText);
  if (!/^[1-9][0-9]*$/.test(columnsText) || width % columns !== 0)
    throw new Error(`${name}: its 'I-plane columns' text "${columnsText}" is not a number of equal columns of its width`);
  const rows = Math.ceil(planes.length / columns);
  if (!planes.every((p, k) => Number.isInteger(p) && (k === 0 ? p === 0 : p > planes[k - 1])) || height % rows !== 0)
    throw new Error(`${name}: its 'I-planes' text "${list}" does not list increasing planes from 0, one per equal part of its ${columns === 1 ? 'height' : `${columns} columns`}`);
  return { planes, columns, rows };
}

// The rectangle, in pixels, that nodes (x, y pairs in half pixels) reach;
// with `whole`, that of the pixels holding them (as canvas_over does).
function bounds(nodeLists, whole = false) {
  let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
  for (const nodes of nodeLists)
    for (let k = 0; k < nodes.length; k += 2) {
      const x = whole ? Math.floor(nodes[k] / 2) : nodes[k] / 2, y = whole ? Math.floor(nodes[k + 1] / 2) : nodes[k + 1] / 2;
      x0 = Math.min(x0, x), x1 = Math.max(x1, whole ? x + 1 : x);
      y0 = Math.min(y0, y), y1 = Math.max(y1, whole ? y + 1 : y);
    }
  return { x0, y0, x1, y1 };
}

export class Player {
  constructor(container, state) {
    this.container = container;
    this.worker = new Worker(new URL('./m4mesh/worker.js', import.meta.url), { type: 'module' });
    this.worker.onmessage = ({ data }) => this.receive(data);
    this.waiting = new Map();  // frame index → resolvers of fetchFrame
    this.state = state;
    this.renderer = new THREE.WebGLRenderer({ antialias: true });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    container.append(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x20242c);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x445066, 1.4));
    const light = new THREE.DirectionalLight(0xffffff, 2.2);
    light.position.set(2, 3, 4);
    this.scene.add(light);
    this.perspective = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
    this.orthographic = new THREE.OrthographicCamera(-1, 1, 1, -1, -10, 10);
    this.camera = this.perspective;
    this.controls = new OrbitControls(this.perspective, this.renderer.domElement);
    this.controls.addEventListener('change', () => (this.dirty = true));
    // Once the viewer turns or zooms, the camera stays where they put it.
    this.controls.addEventListener('start', () => (this.cameraMoved = true));
    this.texture = checkerboard();
    this.playing = true;
    this.frame = 0;
    this.lastTick = 0;
    this.bindControls();
    window.addEventListener('resize', () => this.resize());
    this.resize();
    this.renderer.setAnimationLoop((time) => this.tick(time));
  }

  bindControls() {
    this.playButton = document.getElementById('play');
    this.slider = document.getElementById('frame');
    this.label = document.getElementById('frame-label');
    this.fps = document.getElementById('fps');
    this.status = document.getElementById('status');
    this.playButton.addEventListener('click', () => {
      this.playing = !this.playing;
      this.playButton.textContent = this.playing ? 'Pause' : 'Play';
    });
    this.slider.addEventListener('input', () => this.show(Number(this.slider.value)));
    document.getElementById('wireframe').addEventListener('change', (event) => {
      if (this.mesh) this.mesh.material.wireframe = event.target.checked, (this.dirty = true);
    });
    document.getElementById('texture').addEventListener('change', (event) => {
      if (event.target.files[0]) this.setTexture(event.target.files[0]);
    });
  }

  resize() {
    const width = this.container.clientWidth, height = this.container.clientHeight;
    if (!width || !height) return;
    this.renderer.setSize(width, height);
    this.dirty = true;
    this.perspective.aspect = width / height;
    this.perspective.updateProjectionMatrix();
    if (this.bounds2d) this.fitOrthographic();
  }

  // A texture for 2D streams: one picture, or a tile per I-plane (track's),
  // each cut into a texture of its own (a picture of tiles may pass the
  // largest texture WebGL takes, which would shrink it).
  async setTexture(source) {
    const name = source instanceof File ? source.name : source;
    let bytes;
    if (source instanceof File) {
      bytes = new Uint8Array(await source.arrayBuffer());
    } else {
      const response = await fetch(source);
      if (!response.ok) throw new Error(`${name}: cannot fetch the texture (HTTP ${response.status})`);
      bytes = new Uint8Array(await response.arrayBuffer());
    }
    const picture = await createImageBitmap(new Blob([bytes]));
    const tiles = textureTiles(pngTexts(bytes), picture.width, picture.height, name);
    const grid = tiles ?? { planes: [0], columns: 1, rows: 1 };
    const width = picture.width / grid.columns, height = picture.height / grid.rows;
    const textures = new Map();
    for (const [k, plane] of grid.planes.entries()) {
      const canvas = document.createElement('canvas');
      canvas.width = width, (canvas.height = height);
      canvas.getContext('2d').drawImage(picture, (k % grid.columns) * width, Math.floor(k / grid.columns) * height, width, height, 0, 0, width, height);
      const texture = new THREE.CanvasTexture(canvas);
      texture.colorSpace = THREE.SRGBColorSpace;
      textures.set(plane, texture);
    }
    picture.close();
    for (const texture of [this.texture, ...(this.tiles?.values() ?? [])]) texture.dispose();
    this.texture = tiles ? checkerboard() : textures.get(0);
    this.tiles = tiles ? textures : null;
    this.state.texture = name;
    if (this.kind === '2d') this.meshIntra = undefined, (this.changed = true);  // laid again with its I-plane's own
  }

  // I-plane `intra`'s texture: the texture's tile for it, else its one
  // picture, else the checkerboard (no texture, or tiles without one for it).
  textureOf(intra) {
    return this.tiles?.get(intra) ?? this.texture;
  }

  reset(name, size) {
    this.session = (this.session || 0) + 1;
    if (this.mesh) {
      this.scene.remove(this.mesh);
      this.mesh.geometry.dispose();
    }
    this.mesh = null;
    this.frames = new Map();  // index → {version, positions}, as the worker sent them
    this.requested = new Set();  // "index version" asked for
    this.version = 0;  // a progressive stream's units applied (its frames change with each); 0 otherwise
    this.waiting.clear();
    this.worker.postMessage({ type: 'open', session: this.session });
    this.planes = null;
    this.bounds2d = null;
    this.frame = 0;
    this.shownFrame = null;
    this.box = new THREE.Box3();
    this.boxFrames = 0;
    this.cameraMoved = false;
    this.status.classList.remove('error');
    this.state.player = {
      name, kind: null, codec: null, frames: 0, vertices: 0, progressive: false, bytesTotal: size, bytesReceived: 0,
      bytesDecoded: 0, unitsApplied: 0, downloadDone: false, done: false, error: null, frameShown: -1, framesDrawn: 0,
      framesDrawnDuringDownload: 0, unitsAppliedWhenDrawn: [],
    };
    return this.session;
  }

  // Plays `body` (a ReadableStream) while it arrives: its bytes go to the worker (copies: a tee's other branch reads the same chunks).
  async play(body, size, name) {
    const session = this.reset(name, size);
    const player = this.state.player;
    const reader = body.getReader();
    for (;;) {
      const { value, done } = await reader.read();
      if (session !== this.session) return reader.cancel();
      if (done) break;
      player.bytesReceived += value.length;
      const chunk = value.slice();
      this.worker.postMessage({ type: 'push', session, chunk: chunk.buffer }, [chunk.buffer]);
      this.describe();
    }
    player.downloadDone = true;
    this.worker.postMessage({ type: 'end', session });
    this.describe();
  }

  // What the worker sends: a status (with the faces once, the box when it grows), the 2D planes, a frame.
  receive(message) {
    if (message.session !== this.session) return;
    if (message.type === 'status') this.take(message);
    else if (message.type === 'planes') this.open2d(message.result);
    else if (message.type === 'frame') this.store(message);
    else if (message.type === 'failure') this.state.player.error = { text: message.text }, this.describe();
  }

  take({ kind, status, faces, box }) {
    const player = this.state.player;
    player.kind = kind;
    if (!status) return;
    Object.assign(player, {
      bytesDecoded: status.bytesDecoded, unitsApplied: status.unitsApplied, done: status.done, error: status.error ?? null,
    });
    if (status.header) {
      Object.assign(player, {
        codec: status.header.codec, frames: status.header.frames, vertices: status.header.vertices,
        progressive: status.header.progressive, framesDecoded: status.framesDecoded,
      });
      this.version = status.version;
      if (faces) this.build3d(faces, status.header);
      if (box) this.frameSequence(box);
      if (this.fpsSession !== this.session) this.fps.value = Math.round(status.header.frameRate), (this.fpsSession = this.session);
    }
    this.changed = true;
    this.describe();
  }

  store({ index, version, positions }) {
    this.requested.delete(`${index} ${version}`);
    if (positions.length > 0) this.frames.set(index, { version, positions });
    for (const resolve of this.waiting.get(index) ?? []) resolve(positions);
    this.waiting.delete(index);
    if (index === this.frame) this.changed = true;
  }

  // Asks the worker for frame `index` as the stream stands now (once per version).
  request(index) {
    const key = `${index} ${this.version}`;
    if (this.frames.get(index)?.version === this.version || this.requested.has(key)) return;
    this.requested.add(key);
    this.worker.postMessage({ type: 'frame', session: this.session, index });
  }

  // Frame `index` as the stream stands now (for the tests).
  fetchFrame(index) {
    return new Promise((resolve) => {
      this.waiting.set(index, [...(this.waiting.get(index) ?? []), resolve]);
      this.worker.postMessage({ type: 'frame', session: this.session, index });
    });
  }

  build3d(faces, header) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(header.vertices * 3), 3));
    geometry.setIndex(new THREE.BufferAttribute(faces, 1));
    const material = new THREE.MeshStandardMaterial({
      color: 0xc8b8a0, roughness: 0.65, metalness: 0.05, side: THREE.DoubleSide,
      wireframe: document.getElementById('wireframe').checked,
    });
    this.mesh = new THREE.Mesh(geometry, material);
    this.scene.add(this.mesh);
    this.kind = '3d';
    this.camera = this.perspective;
    this.controls.enabled = true;
    this.load3d(0);
  }

  // The camera frames every frame decoded so far (a progressive stream's
  // frames when the download ends): the box they fill (the worker's), seen
  // from the side across its longer horizontal extent (y is up; a walk or
  // a gallop goes across the view), 20° above, as `m4mesh render3d` does.
  frameSequence({ min, max, frames }) {
    this.box.set(new THREE.Vector3(...min), new THREE.Vector3(...max));
    this.boxFrames = frames;
    this.state.player.framedFrames = frames;
    this.placeGltf();
    this.frameCamera();
  }

  frameCamera() {
    if (this.cameraMoved || (this.box.isEmpty() && !this.gltf)) return;
    // A glTF beside the stream: framed with it; alone, its first frame.
    const box = this.box.isEmpty() ? new THREE.Box3().setFromObject(this.gltf.scene, true) : this.box.clone();
    if (this.gltf && !this.box.isEmpty()) box.union(this.box.clone().translate(this.gltf.scene.position));
    const center = box.getCenter(new THREE.Vector3()), size = box.getSize(new THREE.Vector3());
    const across = size.x >= size.z ? new THREE.Vector3(0, 0, 1) : new THREE.Vector3(1, 0, 0);
    const elevation = (20 * Math.PI) / 180, azimuth = (25 * Math.PI) / 180;
    const direction = across.clone().applyAxisAngle(new THREE.Vector3(0, 1, 0), azimuth).multiplyScalar(Math.cos(elevation));
    direction.y = Math.sin(elevation);
    // Near enough that the box fills the view, far enough that each corner
    // lies inside it (with 5 % to spare): per corner, its side offsets over
    // the tangents of the half fields of view, plus its depth toward the camera.
    const right = new THREE.Vector3().crossVectors(direction, new THREE.Vector3(0, 1, 0)).normalize().negate();
    const up = new THREE.Vector3().crossVectors(right, direction).negate();
    const tanV = Math.tan((this.perspective.fov * Math.PI) / 360) / 1.05, tanH = tanV * this.perspective.aspect;
    let distance = 1e-6;
    for (const corner of [0, 1, 2, 3, 4, 5, 6, 7]) {
      const p = new THREE.Vector3(corner & 1 ? size.x : 0, corner & 2 ? size.y : 0, corner & 4 ? size.z : 0).add(box.min).sub(center);
      const depth = p.dot(direction);
      distance = Math.max(distance, depth + Math.abs(p.dot(right)) / tanH, depth + Math.abs(p.dot(up)) / tanV);
    }
    this.controls.target.copy(center);
    this.perspective.position.copy(center).addScaledVector(direction, distance);
    this.perspective.near = distance / 100;
    this.perspective.far = distance * 100;
    this.perspective.updateProjectionMatrix();
    this.controls.update();
    this.dirty = true;
  }

  // A glTF animation (URL parameter gltf) played by three.js's own loader
  // and mixer beside the stream, at the frame the player shows: the
  // stream's glTF (decode3d -o anim.glb) shows the same positions.
  async openGltf(url) {
    const loaded = await new GLTFLoader().loadAsync(url);
    if (!this.state.player) this.reset(url, 0);
    if (this.gltf) this.scene.remove(this.gltf.scene);
    let mesh = null;
    loaded.scene.traverse((o) => (mesh ??= o.isMesh ? o : null));
    if (!mesh) throw new Error(`${url}: no mesh in the glTF`);
    // Tinted apart from the stream; faceted, as a glTF without normals is.
    mesh.material = new THREE.MeshStandardMaterial({ color: 0xa8bccc, roughness: 0.65, metalness: 0.05, side: THREE.DoubleSide, flatShading: true });
    const clip = loaded.animations[0] ?? null;
    const mixer = new THREE.AnimationMixer(loaded.scene);
    const action = clip ? mixer.clipAction(clip).setLoop(THREE.LoopOnce, 1).play() : null;
    // Frame k at its keyframe time (STEP: that key's weights exactly).
    const times = clip?.tracks[0]?.times ?? new Float32Array([0]);
    this.gltf = { scene: loaded.scene, mesh, mixer, action, times };
    this.scene.add(loaded.scene);
    this.state.gltf = { url, frames: times.length, vertices: mesh.geometry.getAttribute('position').count, animated: Boolean(clip) };
    this.describe();
    this.placeGltf();
    this.showGltf(this.frame);
    this.frameCamera();
  }

  closeGltf() {
    if (!this.gltf) return;
    this.scene.remove(this.gltf.scene);
    this.gltf = null;
    this.state.gltf = null;
    this.frameCamera();
  }

  // Beside the stream across the view (to its right): along the box's longer horizontal extent.
  placeGltf() {
    if (!this.gltf || this.box.isEmpty()) return;
    const size = this.box.getSize(new THREE.Vector3());
    this.gltf.scene.position.set(size.x >= size.z ? -1.15 * size.x : 0, 0, size.x >= size.z ? 0 : -1.15 * size.z);
    this.dirty = true;
  }

  // The glTF at frame `index`: the action placed at that key's time and the mixer applied.
  showGltf(index) {
    if (!this.gltf?.action) return;
    const { times, mixer, action } = this.gltf;
    action.time = times[Math.min(index, times.length - 1)];
    mixer.update(0);
    this.dirty = true;
  }

  // Frames `indices` of the stream (from the worker) against the glTF's
  // vertices as three.js evaluates them at the same frame (morph targets,
  // skin): how many coordinates differ, compared as float32, and the first.
  async compareGltf(indices) {
    const { mesh } = this.gltf;
    const vertex = new THREE.Vector3();
    let compared = 0, differing = 0, first = null;
    for (const index of indices) {
      const decoded = await this.fetchFrame(index);
      this.showGltf(index);
      for (let v = 0; v < decoded.length / 3; ++v) {
        mesh.getVertexPosition(v, vertex);
        for (const [c, value] of [vertex.x, vertex.y, vertex.z].entries()) {
          ++compared;
          if (Math.fround(value) !== decoded[3 * v + c] && differing++ === 0) first = { frame: index, vertex: v, glTF: value, decoded: decoded[3 * v + c] };
        }
      }
    }
    this.showGltf(this.state.player.frameShown);
    return { compared, differing, first };
  }

  // The share of every decoded frame's vertices the camera sees (for the tests).
  async visibleShare() {
    if (!this.mesh) return 0;
    this.perspective.updateMatrixWorld();
    let seen = 0, total = 0;
    const point = new THREE.Vector3();
    for (let f = 0; f < (this.state.player.framesDecoded ?? 0); ++f) {
      const positions = await this.fetchFrame(f);
      for (let k = 0; k < positions.length; k += 3, ++total) {
        point.set(positions[k], positions[k + 1], positions[k + 2]).project(this.perspective);
        if (Math.abs(point.x) <= 1 && Math.abs(point.y) <= 1 && point.z <= 1) ++seen;
      }
    }
    return total ? seen / total : 0;
  }

  // The frame to show (URL parameter frame; undefined: the one shown) and
  // whether to hold it (pause) or play.
  start(frame, paused) {
    if (frame !== undefined) this.pendingFrame = frame;
    this.playing = !paused;
    this.playButton.textContent = paused ? 'Play' : 'Pause';
  }

  // Shows frame `index` if the worker has sent it (an older refinement
  // meanwhile), asking for it as the stream stands now and for the next.
  load3d(index) {
    this.request(index);
    const available = this.available();
    if (available > 1) this.request((index + 1) % available);
    const frame = this.frames.get(index);
    if (!frame || frame === this.shownFrame) return false;
    this.shownFrame = frame;
    const attribute = this.mesh.geometry.getAttribute('position');
    attribute.array.set(frame.positions);
    attribute.needsUpdate = true;
    this.mesh.geometry.computeVertexNormals();
    this.shownVersion = frame.version;
    return true;
  }

  open2d(result) {
    const player = this.state.player;
    player.error = result.error ?? null;
    player.done = !result.error;
    if (!result.planes) return;
    this.planes = result.planes;
    player.frames = this.planes.length;
    player.framesDecoded = this.planes.length;
    player.vertices = this.planes[0]?.nodes.length / 2 || 0;
    player.codec = '2D mesh object';
    if (this.planes.length === 0) return;
    this.kind = '2d';
    this.camera = this.orthographic;
    this.controls.enabled = false;
    // The view holds every plane's nodes (half pixels; y down as in the picture).
    this.bounds2d = bounds(this.planes.map((plane) => plane.nodes));
    this.fitOrthographic();
    this.changed = true;
  }

  fitOrthographic() {
    const { x0, y0, x1, y1 } = this.bounds2d;
    const aspect = this.container.clientWidth / this.container.clientHeight;
    const cx = (x0 + x1) / 2, cy = -(y0 + y1) / 2;
    let half = Math.max((y1 - y0) / 2, (x1 - x0) / 2 / aspect) * 1.08;
    Object.assign(this.orthographic, { left: cx - half * aspect, right: cx + half * aspect, top: cy + half, bottom: cy - half });
    this.orthographic.updateProjectionMatrix();
    this.dirty = true;
  }

  // The mesh of plane `index`: the texture (its I-plane's tile) lies on its
  // I-plane's nodes, stretched over their pixels; the checkerboard when a
  // texture of tiles has none for it.
  load2d(index) {
    let intra = index;
    while (!this.planes[intra].intra) --intra;
    if (!this.mesh || this.meshIntra !== intra) {
      if (this.mesh) this.scene.remove(this.mesh), this.mesh.geometry.dispose();
      const nodes = this.planes[intra].nodes;
      const { x0, y0, x1, y1 } = bounds([nodes], true);
      const uv = new Float32Array(nodes.length);
      for (let k = 0; k < nodes.length; k += 2) {
        uv[k] = (nodes[k] / 2 - x0) / (x1 - x0);
        uv[k + 1] = 1 - (nodes[k + 1] / 2 - y0) / (y1 - y0);
      }
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array((nodes.length / 2) * 3), 3));
      geometry.setAttribute('uv', new THREE.BufferAttribute(uv, 2));
      geometry.setIndex(this.planes[intra].triangles);
      const material = new THREE.MeshBasicMaterial({
        map: this.textureOf(intra), side: THREE.DoubleSide,
        wireframe: document.getElementById('wireframe').checked,
      });
      this.mesh = new THREE.Mesh(geometry, material);
      this.scene.add(this.mesh);
      this.meshIntra = intra;
    }
    const nodes = this.planes[index].nodes, attribute = this.mesh.geometry.getAttribute('position');
    for (let k = 0, v = 0; k < nodes.length; k += 2, v += 3)
      attribute.array[v] = nodes[k] / 2, attribute.array[v + 1] = -nodes[k + 1] / 2, attribute.array[v + 2] = 0;
    attribute.needsUpdate = true;
    return true;
  }

  // Frames that can be shown now: every frame of a progressive stream once
  // its base mesh is in, else the frames decoded so far.
  available() {
    const player = this.state.player;
    if (!player) return 0;
    if (player.kind === '2d') return this.planes?.length ?? 0;
    return player.kind === '3d' ? player.framesDecoded ?? 0 : this.gltf?.times.length ?? 0;
  }

  show(index) {
    this.frame = index;
    this.changed = true;
  }

  tick(time) {
    const available = this.available();
    // A frame asked for is shown once decoded (past the end of a stream decoded whole: its last).
    if (this.pendingFrame !== undefined && available > 0 && (available > this.pendingFrame || this.state.player?.done))
      this.frame = Math.min(this.pendingFrame, available - 1), (this.pendingFrame = undefined), (this.changed = true);
    if (this.playing && available > 0 && time - this.lastTick >= 1000 / Math.max(1, Number(this.fps.value))) {
      this.lastTick = time;
      this.frame = (this.frame + 1) % available;
      this.changed = true;
    }
    const player = this.state.player;
    if (this.changed && available > 0 && (this.mesh || this.kind === '2d' || this.gltf)) {
      this.changed = false;
      this.frame = Math.min(this.frame, available - 1);
      // A glTF alone is shown by showGltf below.
      if (this.kind === '2d' ? this.load2d(this.frame) : this.mesh ? this.load3d(this.frame) : true) {
        this.dirty = true;
        this.showGltf(this.frame);
        player.frameShown = this.frame;
        player.framesDrawn += 1;
        if (!player.downloadDone) player.framesDrawnDuringDownload += 1;
        // A progressive stream's frame is as the units applied when the worker sent it; a frame
        // cached at an older refinement may follow a newer one, so only new highs are recorded.
        const applied = this.kind === '3d' && player.progressive ? this.shownVersion : player.unitsApplied;
        const units = player.unitsAppliedWhenDrawn;
        if (!(units[units.length - 1] >= applied)) units.push(applied);
      }
      this.slider.max = String(Math.max(0, (player.frames || available) - 1));
      this.slider.value = String(this.frame);
      this.label.textContent = `frame ${this.frame + 1} / ${player.frames || available}`;
    }
    // Drawn only when something changed: software WebGL keeps up, laptops stay cool.
    if (this.dirty) {
      this.dirty = false;
      this.renderer.render(this.scene, this.camera);
    }
  }

  describe() {
    const p = this.state.player;
    const parts = [p.name];
    if (p.codec) parts.push(`${p.codec}${p.progressive ? ' (progressive)' : ''}`, `${p.vertices} vertices`, `${p.frames} frames`);
    parts.push(`${p.bytesReceived.toLocaleString()}${p.bytesTotal ? ' / ' + p.bytesTotal.toLocaleString() : ''} bytes received`);
    if (p.kind === '3d') parts.push(`${p.unitsApplied} units applied`);
    parts.push(p.error ? 'stopped at an error' : p.done ? 'complete' : p.downloadDone ? 'downloaded' : 'downloading…');
    if (this.state.gltf) parts.push(`right: ${this.state.gltf.url} (three.js GLTFLoader)`);
    this.status.textContent = parts.join(' · ') + (p.error ? `\nerror: ${p.error.text}` : '');
    this.status.classList.toggle('error', Boolean(p.error));
  }
}
