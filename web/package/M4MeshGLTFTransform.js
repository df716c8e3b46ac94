// glTF-Transform (@gltf-transform/core) extension for M4MESH_vertex_animation
// (docs/extensions/M4MESH_vertex_animation): read, kept through a
// document's edits, written back. An animation's VertexAnimation lists its
// channels; a channel names its node and its key-time accessor, and holds
// one m4mesh stream (bytes) per primitive of the node's mesh.
//
//   const io = new NodeIO().registerExtensions([M4MeshVertexAnimation]);
//   const document = await io.read('walk-m4mesh.glb');
//   for (const a of document.getRoot().listAnimations())
//     for (const c of a.getExtension('M4MESH_vertex_animation')?.listChannels() ?? []) console.log(c.getNode().getName(), c.listStreams().length);
import { Extension, ExtensionProperty, PropertyType, RefList } from '@gltf-transform/core';

const NAME = 'M4MESH_vertex_animation';

export class VertexAnimationChannel extends ExtensionProperty {
  static EXTENSION_NAME = NAME;
  init() {
    this.extensionName = NAME;
    this.propertyType = 'M4MeshVertexAnimationChannel';
    this.parentTypes = ['M4MeshVertexAnimation'];
  }
  getDefaults() {
    return Object.assign(super.getDefaults(), { node: null, input: null, interpolation: 'LINEAR', streams: [] });
  }
  getNode() {
    return this.getRef('node');
  }
  setNode(node) {
    return this.setRef('node', node);
  }
  // The key times (an Accessor of SCALAR floats): key k shows decoded frame k.
  getInput() {
    return this.getRef('input');
  }
  setInput(accessor) {
    return this.setRef('input', accessor, { usage: 'OTHER' });  // as an animation sampler's input
  }
  getInterpolation() {
    return this.get('interpolation');
  }
  setInterpolation(interpolation) {
    return this.set('interpolation', interpolation);
  }
  // Per primitive of the node's mesh, its stream's bytes (Uint8Array).
  listStreams() {
    return this.get('streams');
  }
  setStreams(streams) {
    return this.set('streams', streams);
  }
}

export class VertexAnimation extends ExtensionProperty {
  static EXTENSION_NAME = NAME;
  init() {
    this.extensionName = NAME;
    this.propertyType = 'M4MeshVertexAnimation';
    this.parentTypes = [PropertyType.ANIMATION];
  }
  getDefaults() {
    return Object.assign(super.getDefaults(), { channels: new RefList() });
  }
  addChannel(channel) {
    return this.addRef('channels', channel);
  }
  removeChannel(channel) {
    return this.removeRef('channels', channel);
  }
  listChannels() {
    return this.listRefs('channels');
  }
}

export class M4MeshVertexAnimation extends Extension {
  static EXTENSION_NAME = NAME;
  extensionName = NAME;
  prewriteTypes = [PropertyType.BUFFER];

  createVertexAnimation() {
    return new VertexAnimation(this.document.getGraph());
  }
  createChannel() {
    return new VertexAnimationChannel(this.document.getGraph());
  }

  read(context) {
    const json = context.jsonDoc.json;
    (json.animations ?? []).forEach((animationDef, a) => {
      const def = animationDef.extensions?.[NAME];
      if (!def) return;
      const vertexAnimation = this.createVertexAnimation();
      for (const channelDef of def.channels ?? []) {
        const channel = this.createChannel()
          .setNode(context.nodes[channelDef.node])
          .setInput(context.accessors[channelDef.input])
          .setInterpolation(channelDef.interpolation ?? 'LINEAR')
          .setStreams((channelDef.primitives ?? []).map(({ bufferView }) => context.bufferViews[bufferView].slice()));
        vertexAnimation.addChannel(channel);
      }
      context.animations[a].setExtension(NAME, vertexAnimation);
    });
    return this;
  }

  // The streams go to the first buffer as buffer views of their own.
  prewrite(context) {
    const buffer = this.document.getRoot().listBuffers()[0];
    const views = context.otherBufferViews.get(buffer) ?? [];
    for (const property of this.properties)
      if (property instanceof VertexAnimationChannel) for (const stream of property.listStreams()) views.push(stream);
    if (views.length) context.otherBufferViews.set(buffer, views);
    return this;
  }

  write(context) {
    const json = context.jsonDoc.json;
    for (const animation of this.document.getRoot().listAnimations()) {
      const vertexAnimation = animation.getExtension(NAME);
      if (!vertexAnimation) continue;
      const animationDef = json.animations[context.animationIndexMap.get(animation)];
      animationDef.extensions ??= {};
      animationDef.extensions[NAME] = {
        channels: vertexAnimation.listChannels().map((channel) => {
          const def = context.createPropertyDef(channel);
          def.node = context.nodeIndexMap.get(channel.getNode());
          def.input = context.accessorIndexMap.get(channel.getInput());
          def.interpolation = channel.getInterpolation();
          def.primitives = channel.listStreams().map((stream) => ({ bufferView: context.otherBufferViewsIndexMap.get(stream) }));
          return def;
        }),
      };
    }
    return this;
  }
}
