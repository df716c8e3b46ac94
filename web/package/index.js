// m4mesh for the web and Node: the three.js loader of 3D streams, and the
// decoder module itself (embind: streamKind, decode2d, Stream3d).
export { M4MeshAnimation, M4MeshLoader } from './M4MeshLoader.js';
export { createM4meshDecoder } from './decoder.js';
