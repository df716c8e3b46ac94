// The decoding protocol of the package's worker (worker.js; docs/web.md):
// messages in — open (`box: false`: no box wanted), push (a chunk of the
// stream as it downloads), end, frame (ask for one), drop (forget a final
// frame taken) — and out through `post`: status (JSON of the decoder, the
// faces once, the box the frames fill, which takes every frame once more),
// frame (transferred, not copied), planes (a 2D stream, decoded when its
// download ends), failure. The stream's kind comes from the C++
// (streamKind); a 3D stream's units are decoded as soon as they are whole.
// M4MeshLoader runs it in a worker, or in its own thread where there is
// none (Node).

// A handler of the protocol's messages over the decoder module `module`.
export function createSession(module, post) {
  let session = null;

  function open(id, wantsBox) {
    session?.stream?.delete();
    session = { id, module, kind: null, head: [], stream: null, chunks: [], facesSent: false, wantsBox, box: null, boxFrames: 0, version: 0 };
  }

  function concatenate(chunks) {
    const bytes = new Uint8Array(chunks.reduce((n, c) => n + c.length, 0));
    let at = 0;
    for (const chunk of chunks) bytes.set(chunk, at), (at += chunk.length);
    return bytes;
  }

  // The frames' box (a progressive stream's first frame until its last unit is in, as they all change with every unit).
  function frameBox(status) {
    const progressive = status.header.progressive;
    const frames = status.done || !progressive ? status.framesDecoded : 1;
    if (frames <= session.boxFrames) return null;
    if (progressive || !session.box) session.box = { min: [Infinity, Infinity, Infinity], max: [-Infinity, -Infinity, -Infinity] }, (session.boxFrames = 0);
    const { min, max } = session.box;
    for (let f = session.boxFrames; f < frames; ++f) {
      const positions = session.stream.frame(f);
      for (let k = 0; k < positions.length; k += 3)
        for (let c = 0; c < 3; ++c) min[c] = Math.min(min[c], positions[k + c]), (max[c] = Math.max(max[c], positions[k + c]));
    }
    session.boxFrames = frames;
    return { min, max, frames };
  }

  // Runs one Stream3d call and posts its status, with the faces once they are known and the box when it grows.
  function step3d(call) {
    const status = JSON.parse(call(session.stream));
    const message = { type: 'status', session: session.id, kind: '3d', status };
    const transfer = [];
    if (status.header) {
      session.version = status.header.progressive ? status.unitsApplied : 0;
      status.version = session.version;
      if (!session.facesSent && status.framesDecoded > 0) {
        message.faces = session.stream.faces();
        transfer.push(message.faces.buffer);
        session.facesSent = true;
      }
      if (status.framesDecoded > 0 && session.wantsBox) message.box = frameBox(status);
    }
    post(message, transfer);
  }

  // The first four bytes tell the kind; the bytes before that wait.
  function push(chunk) {
    if (!session.kind) {
      session.head.push(chunk);
      const head = concatenate(session.head);
      if (head.length < 4) return;
      session.kind = JSON.parse(session.module.streamKind(head)).kind;
      session.head = [];
      chunk = head;
      if (session.kind === 'none') throw new Error(notAStream(head));
    }
    if (session.kind === '2d') {
      session.chunks.push(chunk);
      post({ type: 'status', session: session.id, kind: '2d', status: null });
      return;
    }
    session.stream ??= new session.module.Stream3d();
    step3d((s) => s.push(chunk));
  }

  // What bytes that begin no m4mesh stream are.
  function notAStream(head) {
    if (head.length === 0) return 'an empty stream: no bytes arrived';
    const start = [...head.subarray(0, 4)].map((b) => b.toString(16).padStart(2, '0')).join(' ');
    return `not an m4mesh stream: it starts with ${start}${head.length < 4 ? ` and ends there (${head.length} bytes)` : ''} ` +
      '(a 3D stream starts with 00 00 01 c4, a 2D one with 00 00 01 bc)';
  }

  function end() {
    // Under four bytes in all: no stream.
    if (!session.kind) throw new Error(notAStream(concatenate(session.head)));
    if (session.kind === '3d') return step3d((s) => s.end());
    const result = JSON.parse(session.module.decode2d(concatenate(session.chunks), 2));
    post({ type: 'planes', session: session.id, result });
  }

  return (data) => {
    try {
      if (data.type === 'open') open(data.session, data.box !== false);
      else if (!session || data.session !== session.id) return;  // an older stream's message
      else if (data.type === 'push') push(new Uint8Array(data.chunk));
      else if (data.type === 'end') end();
      else if (data.type === 'drop') session.stream?.drop(data.index);
      else if (data.type === 'frame') {
        const positions = session.stream ? session.stream.frame(data.index) : new Float32Array(0);
        post({ type: 'frame', session: session.id, index: data.index, version: session.version, positions }, [positions.buffer]);
      } else throw new Error(`unknown request ${data.type}`);
    } catch (error) {
      post({ type: 'failure', session: data.session, text: String(error.message || error) });
    }
  };
}
