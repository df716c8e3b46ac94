// m4mesh for the web and Node: the three.js loader of 3D streams, its
// GLTFLoader plugin for M4MESH_vertex_animation, and the
// decoder module itself (embind: streamKind, decode2d, Stream3d).
export { M4MeshAnimation, M4MeshLoader } from './M4MeshLoader.js';
export { EXTENSION_NAME, M4MeshGLTFPlugin } from './M4MeshGLTFPlugin.js';
export { createM4meshDecoder } from './decoder.js';
