// The package's decoding worker: the protocol of session.js over the
// decoder module, off the page's thread, as three.js's DRACOLoader decodes
// in workers. `new Worker(new URL('m4mesh/worker.js', import.meta.url), { type: 'module' })`.
import createM4meshDecoder from './m4mesh-decoder.mjs';
import { createSession } from './session.js';

const handle = createM4meshDecoder().then((module) => createSession(module, (message, transfer) => postMessage(message, transfer)));
onmessage = async ({ data }) => (await handle)(data);
