// three.js GLTFLoader plugin for M4MESH_vertex_animation
// (docs/extensions/M4MESH_vertex_animation): each channel's streams are
// decoded (in the package's Worker where there is one) and the frames
// become absolute morph targets of the primitive's mesh, driven by a track
// added to the animation's clip, so that the mesh plays as the file's
// uncompressed morph-target animation did, every key's positions exactly
// the decoded ones.
//
//   const loader = new GLTFLoader();
//   loader.register((parser) => new M4MeshGLTFPlugin(parser));
//   loader.load('walk.glb', (gltf) => new AnimationMixer(gltf.scene).clipAction(gltf.animations[0]).play());
import { BufferAttribute, BufferGeometry, InterpolateDiscrete, InterpolateLinear, NumberKeyframeTrack } from 'three';
import { M4MeshLoader } from './M4MeshLoader.js';

export const EXTENSION_NAME = 'M4MESH_vertex_animation';

export class M4MeshGLTFPlugin {
  // options.loader: the M4MeshLoader that decodes the streams (default: a new one, with the package's Worker).
  constructor(parser, options = {}) {
    this.parser = parser;
    this.name = EXTENSION_NAME;
    this.loader = options.loader ?? new M4MeshLoader();
  }

  async afterRoot(result) {
    const animations = this.parser.json.animations ?? [];
    const jobs = [];
    animations.forEach((animation, a) => {
      const extension = animation.extensions?.[EXTENSION_NAME];
      if (!extension) return;
      if (!Array.isArray(extension.channels) || extension.channels.length === 0) throw this.error(a, null, 'no channels');
      extension.channels.forEach((channel, c) => jobs.push(this.loadChannel(a, c, channel)));
    });
    const byMesh = new Map();  // three.js mesh → its channels' { animation, times, interpolation, frames }, in the file's order
    for (const pieces of await Promise.all(jobs))
      for (const [mesh, frames] of pieces) byMesh.set(mesh, [...(byMesh.get(mesh) ?? []), frames]);
    const owners = new Map();  // geometry → the mesh whose frames it holds
    for (const [mesh, pieces] of byMesh) {
      if (owners.has(mesh.geometry)) mesh.geometry = mesh.geometry.clone();
      owners.set(mesh.geometry, mesh);
      const frames = pieces.flatMap((p) => p.frames);
      setFrames(mesh.geometry, frames);
      mesh.updateMorphTargets();
      let first = 0;
      for (const piece of pieces) {
        const clip = result.animations[piece.animation];
        clip.tracks.push(influenceTrack(mesh, piece, first, frames.length));
        clip.resetDuration();
        first += piece.frames.length;
      }
    }
  }

  // The decoded frames of channel c of animation a, per three.js mesh of its node's primitives.
  async loadChannel(a, c, channel) {
    const json = this.parser.json;
    const node = json.nodes?.[channel.node];
    if (node?.mesh === undefined) throw this.error(a, c, `node ${channel.node} has no mesh`);
    const primitives = json.meshes[node.mesh].primitives;
    if (!Array.isArray(channel.primitives) || channel.primitives.length !== primitives.length)
      throw this.error(a, c, `${channel.primitives?.length ?? 0} streams for the ${primitives.length} primitives of mesh ${node.mesh}`);
    const [object, input] = await Promise.all([this.parser.getDependency('node', channel.node), this.parser.getDependency('accessor', channel.input)]);
    const times = new Float32Array(input.count);
    for (let k = 0; k < input.count; ++k) times[k] = input.getX(k);
    const interpolation = channel.interpolation ?? 'LINEAR';
    if (interpolation !== 'LINEAR' && interpolation !== 'STEP') throw this.error(a, c, `interpolation ${interpolation}`);
    const meshes = this.primitiveMeshes(object, node.mesh);
    return Promise.all(
      channel.primitives.map(async ({ bufferView }, p) => {
        const mesh = meshes.get(p);
        if (!mesh) throw this.error(a, c, `no three.js mesh for primitive ${p} of mesh ${node.mesh}`);
        const bytes = await this.parser.getDependency('bufferView', bufferView);
        let decoded;
        try {
          decoded = await this.loader.parse(new Uint8Array(bytes));
        } catch (error) {
          throw this.error(a, c, `primitive ${p}: ${error.message}`);
        }
        const vertices = mesh.geometry.attributes.position.count;
        if (decoded.frameCount !== times.length) throw this.error(a, c, `primitive ${p}: ${decoded.frameCount} frames for ${times.length} key times`);
        if (decoded.vertexCount !== vertices) throw this.error(a, c, `primitive ${p}: ${decoded.vertexCount} vertices, POSITION has ${vertices}`);
        return [mesh, { animation: a, times, interpolation, frames: decoded.frames }];
      }),
    );
  }

  // Per primitive index: the three.js mesh GLTFLoader made of it for this node (the node itself, or its group's children).
  primitiveMeshes(object, meshIndex) {
    const found = new Map();
    for (const candidate of [object, ...object.children]) {
      const association = this.parser.associations.get(candidate);
      const ofNode = candidate === object || association?.nodes === undefined;
      if (candidate.isMesh && ofNode && association?.meshes === meshIndex && association.primitives !== undefined) found.set(association.primitives, candidate);
    }
    return found;
  }

  error(a, c, text) {
    return new Error(`${EXTENSION_NAME}: animation ${a}${c === null ? '' : `, channel ${c}`}: ${text}`);
  }
}

// The frames as absolute morph targets (base weight 0 at a full influence:
// exact), and each frame's normals when the primitive has normals.
function setFrames(geometry, frames) {
  geometry.morphAttributes.position = frames.map((frame) => new BufferAttribute(frame, 3));
  geometry.morphTargetsRelative = false;
  if (!geometry.attributes.normal) return;
  const scratch = new BufferGeometry();
  if (geometry.index) scratch.setIndex(geometry.index);
  geometry.morphAttributes.normal = frames.map((frame) => {
    scratch.setAttribute('position', new BufferAttribute(frame, 3));
    scratch.deleteAttribute('normal');
    scratch.computeVertexNormals();
    return scratch.attributes.normal;
  });
}

// Influences that show the piece's frame k at its key k: one-hot over the mesh's `count` targets, its frames from `first`.
function influenceTrack(mesh, piece, first, count) {
  const keys = piece.times.length;
  const values = new Float32Array(keys * count);
  for (let k = 0; k < keys; ++k) values[k * count + first + k] = 1;
  const track = new NumberKeyframeTrack(`${mesh.uuid}.morphTargetInfluences`, piece.times, values);
  track.setInterpolation(piece.interpolation === 'STEP' ? InterpolateDiscrete : InterpolateLinear);
  return track;
}
