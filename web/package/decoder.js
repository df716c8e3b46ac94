// The decoder module (embind: streamKind, decode2d, Stream3d) for where the
// code runs: the ES module in browsers and workers, the CommonJS one, given
// its .wasm's bytes, in Node.
export async function createM4meshDecoder() {
  const node = typeof process === 'object' && typeof process.versions?.node === 'string' && typeof window === 'undefined' &&
    typeof importScripts !== 'function';
  if (node) {
    const [{ createRequire }, { readFile }] = await Promise.all([import('node:module'), import('node:fs/promises')]);
    const wasmBinary = await readFile(new URL('./m4mesh-decoder-node.wasm', import.meta.url));
    return createRequire(import.meta.url)('./m4mesh-decoder-node.cjs')({ wasmBinary });
  }
  return (await import('./m4mesh-decoder.mjs')).default();
}
