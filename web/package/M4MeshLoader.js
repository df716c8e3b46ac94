// three.js's loader of m4mesh 3D streams (.m4m), in the manner of
// DRACOLoader: the stream is decoded as it downloads, in a Web Worker
// (worker.js) or, where there is none (Node), in this thread.
//
//   const animation = new M4MeshLoader().load(url, (animation) => {
//     const mesh = new THREE.Mesh(animation.geometry, material);
//     mesh.updateMorphTargets();
//     mixer.clipAction(animation.createClip(), mesh).play();
//   });
//   animation.addEventListener('frames', () => …);  // frames as they come, a progressive stream's refined in place
import { AnimationClip, BufferAttribute, BufferGeometry, EventDispatcher, Loader } from 'three';
import { createM4meshDecoder } from './decoder.js';
import { createSession } from './session.js';

let sessions = 0;

// A decoded animation, filled as the stream arrives. Events: 'header'
// (the stream's facts), 'frames' (frames arrived or were refined: their
// indices), 'done'.
export class M4MeshAnimation extends EventDispatcher {
  constructor() {
    super();
    this.codec = '';
    this.frameRate = 0;
    this.frameCount = 0;     // 0 until the header (and for a live stream)
    this.vertexCount = 0;
    this.progressive = false;
    this.faces = null;       // Uint32Array, 3 indices per face
    this.frames = [];        // per frame: Float32Array of x, y, z per vertex (refined in place), or undefined before it comes
    this.units = 0;          // units decoded so far (hash units included)
    this.done = false;
    this.geometry = new BufferGeometry();  // the faces and frame 0; every frame as a morph target once done
  }

  // Morph target influences that show frame k at time k / frameRate.
  createClip(name = 'm4mesh') {
    if (!this.done) throw new Error('M4MeshAnimation.createClip: the stream is still loading');
    return AnimationClip.CreateFromMorphTargetSequence(name, this.frames.map((_, k) => ({ name: String(k) })), this.frameRate, false);
  }

  // The faces and the first frame as they come; every frame as a morph target once all are in.
  updateGeometry() {
    if (!this.geometry.index && this.faces && this.frames[0]) {
      this.geometry.setIndex(new BufferAttribute(this.faces, 1));
      this.geometry.setAttribute('position', new BufferAttribute(this.frames[0].slice(), 3));
      this.geometry.computeVertexNormals();
    }
    if (this.done) {
      this.geometry.morphAttributes.position = this.frames.map((frame, k) => Object.assign(new BufferAttribute(frame, 3), { name: String(k) }));
      this.geometry.morphTargetsRelative = false;
    }
  }
}

// In Node, outside a browser page: a path or a file: URL names a file (fetch takes neither).
function isNodeFile(url) {
  const node = typeof process !== 'undefined' && process.versions?.node && typeof document === 'undefined';
  return Boolean(node) && (url.startsWith('file:') || !/^[a-z][a-z0-9+.-]*:/i.test(url));
}
// Node's own modules by a name that browser bundlers do not try to resolve.
function nodeModule(name) {
  return `node:${name}`;
}

export class M4MeshLoader extends Loader {
  // workerUrl: the package's worker.js (beside this file by default); null decodes in this thread.
  constructor(manager, workerUrl = typeof Worker === 'undefined' ? null : new URL('./worker.js', import.meta.url)) {
    super(manager);
    this.workerUrl = workerUrl;
  }

  // Starts loading `url` and returns its animation at once, filled as the
  // stream arrives; onLoad(animation) once every frame is final,
  // onProgress({ loaded, total, lengthComputable, units }) per chunk,
  // onError(error) on a bad stream or a failed download.
  load(url, onLoad, onProgress, onError) {
    const animation = new M4MeshAnimation();
    const resolved = this.manager.resolveURL(this.path + url);
    this.manager.itemStart(resolved);
    this.decode(animation, async (send) => {
      const { total, chunks } = await this.fetchBytes(resolved);
      let loaded = 0;
      for await (const value of chunks) {
        loaded += value.length;
        send(value);
        onProgress?.({ loaded, total, lengthComputable: total > 0, units: animation.units });
      }
    })
      .then(() => onLoad?.(animation))
      .catch((error) => {
        if (onError) onError(error);
        else console.error(error);
        this.manager.itemError(resolved);
      })
      .finally(() => this.manager.itemEnd(resolved));
    return animation;
  }

  // The stream's size (0: not known) and its bytes as they come: over HTTP
  // with fetch, or in Node a file, named by a path or a file: URL.
  async fetchBytes(resolved) {
    if (isNodeFile(resolved)) {
      const [fs, url] = await Promise.all([import(/* @vite-ignore */ nodeModule('fs')), import(/* @vite-ignore */ nodeModule('url'))]);
      const path = resolved.startsWith('file:') ? url.fileURLToPath(resolved) : resolved;
      const { size } = await fs.promises.stat(path);
      return { total: size, chunks: fs.createReadStream(path, { highWaterMark: 1 << 16 }) };
    }
    const response = await fetch(resolved, { headers: this.requestHeader, credentials: this.withCredentials ? 'include' : 'same-origin' });
    if (!response.ok) throw new Error(`${resolved}: HTTP ${response.status} ${response.statusText}`);
    const reader = response.body.getReader();
    const chunks = (async function* () {
      for (;;) {
        const { done, value } = await reader.read();
        if (done) return;
        yield value;
      }
    })();
    return { total: Number(response.headers.get('content-length')) || 0, chunks };
  }

  // A whole stream in memory (ArrayBuffer or a typed array): a promise of its animation.
  parse(bytes) {
    const animation = new M4MeshAnimation();
    const view = ArrayBuffer.isView(bytes) ? new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength) : new Uint8Array(bytes);
    return this.decode(animation, async (send) => send(view)).then(() => animation);
  }

  // Runs a decoding session over the chunks `feed` sends; resolves when the animation is done.
  async decode(animation, feed) {
    const id = ++sessions;
    let channel;
    const finished = new Promise((resolve, reject) => {
      const state = { requested: 0, batch: null, version: -1, pending: 0, status: null };
      const receive = (message) => {
        try {
          if (message.session !== undefined && message.session !== id) return;  // the worker's own failure has none
          if (message.type === 'failure') throw new Error(message.text);
          if (message.type === 'planes') throw new Error('a 2D stream: M4MeshLoader loads 3D streams');
          if (message.type === 'status') onStatus(message);
          else if (message.type === 'frame') onFrame(message);
        } catch (error) {
          reject(error);
        }
      };
      const ask = (index) => (++state.pending, channel.send({ type: 'frame', session: id, index }));
      const onStatus = ({ status, faces }) => {
        if (status.error) throw new Error(status.error.text);
        if (!status.header) return;
        state.status = status;
        animation.units = status.unitsApplied;
        if (!animation.frameRate) {
          const h = status.header;
          Object.assign(animation, { codec: h.codec, frameRate: h.frameRate, frameCount: h.frames, vertexCount: h.vertices, progressive: h.progressive });
          animation.dispatchEvent({ type: 'header' });
        }
        if (faces) animation.faces = faces;
        askFrames();
      };
      // A progressive stream's frames all change with every unit: a batch of them at a time, the newest refinement's.
      const askFrames = () => {
        const status = state.status;
        if (animation.progressive) {
          if (state.batch === null && status.unitsApplied > 0 && status.version !== state.version) {
            state.batch = status.version;
            for (let k = 0; k < status.framesDecoded; ++k) ask(k);
          }
        } else {
          while (state.requested < status.framesDecoded) ask(state.requested++);
        }
        settle();
      };
      const onFrame = ({ index, positions, version }) => {
        --state.pending;
        if (positions.length === 0) {
          if (!animation.progressive) state.requested = Math.min(state.requested, index);  // not decoded yet: asked again
        } else if (animation.frames[index]) {
          animation.frames[index].set(positions);
        } else {
          animation.frames[index] = positions;
          if (!animation.progressive) channel.send({ type: 'drop', session: id, index });  // final: the decoder need not keep it
        }
        if (state.pending > 0) return;
        if (animation.progressive) (state.version = state.batch), (state.batch = null);
        animation.updateGeometry();
        animation.dispatchEvent({ type: 'frames' });
        askFrames();
      };
      const settle = () => {
        const status = state.status;
        if (!status?.done || state.pending > 0 || state.batch !== null) return;
        if (animation.progressive && state.version !== status.version) return;
        if (animation.frames.length < status.framesDecoded || animation.frames.some((f) => !f)) return;
        animation.done = true;
        animation.updateGeometry();
        animation.dispatchEvent({ type: 'done' });
        resolve();
      };
      channel = this.open(receive);
    });
    finished.catch(() => {});  // awaited below, once the stream is fed
    try {
      channel.send({ type: 'open', session: id, box: false });  // the box would take every frame twice
      await feed((chunk) => {
        const copy = chunk.slice();  // its own buffer, transferred to the worker
        channel.send({ type: 'push', session: id, chunk: copy.buffer }, [copy.buffer]);
      });
      channel.send({ type: 'end', session: id });
      return await finished;
    } finally {
      channel.close();
    }
  }

  // { send(message, transfer), close() } to a worker, or to a session in this thread.
  open(receive) {
    if (this.workerUrl) {
      const worker = new Worker(this.workerUrl, { type: 'module' });
      worker.onmessage = ({ data }) => receive(data);
      worker.onerror = (event) => receive({ type: 'failure', text: `the worker failed: ${event.message}` });
      return { send: (message, transfer) => worker.postMessage(message, transfer), close: () => worker.terminate() };
    }
    // Messages both ways are delivered later, in order, as a worker's would be.
    const ready = createM4meshDecoder().then((module) => createSession(module, (message) => queueMicrotask(() => receive(message))));
    return {
      send: (message) => ready.then((handle) => handle(message)),
      close: () => ready.then((handle) => handle({ type: 'open', session: 0 })),  // frees the stream's decoder
    };
  }

  dispose() {}
}
