"""Blender add-on: glTF files with M4MESH_vertex_animation (m4mesh gltf,
docs/extensions/M4MESH_vertex_animation) through Blender's own glTF importer.

Before the importer builds the scene, each channel's streams are decoded
with the m4mesh Python package, and the channel becomes what the importer
knows: every frame a morph target (its difference from POSITION) and a
weights channel that shows frame k alone at key k. Blender then makes one
shape key per frame over the Basis (the rest pose, POSITION) and an action
that plays them, at the keys' own times.

Install: Preferences > Add-ons > Install... this file, with the m4mesh
Python package importable by Blender's Python (`pip install ./python`, or
its build folder on PYTHONPATH).
"""
import numpy

bl_info = {
    "name": "m4mesh glTF vertex animation (M4MESH_vertex_animation)",
    "author": "the m4mesh developers",
    "version": (1, 1, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > glTF 2.0",
    "description": "Decodes m4mesh streams of a glTF file's vertex animations into shape keys",
    "category": "Import-Export",
}

EXTENSION_NAME = "M4MESH_vertex_animation"
FLOAT = 5126


def _add_floats(gltf, values, kind, bounds):
    """A float32 accessor of `values` (kind VEC3 or SCALAR) over a buffer of its own; its index."""
    from io_scene_gltf2.io.com import gltf2_io

    data = gltf.data
    raw = numpy.ascontiguousarray(values, dtype="<f4").tobytes()
    data.buffers.append(gltf2_io.Buffer.from_dict({"byteLength": len(raw)}))
    gltf.buffers[len(data.buffers) - 1] = raw
    data.buffer_views.append(gltf2_io.BufferView.from_dict({"buffer": len(data.buffers) - 1, "byteLength": len(raw)}))
    accessor = {"bufferView": len(data.buffer_views) - 1, "componentType": FLOAT, "count": len(values), "type": kind}
    if bounds:
        accessor["min"] = [float(x) for x in numpy.min(values, axis=0)]
        accessor["max"] = [float(x) for x in numpy.max(values, axis=0)]
    data.accessors.append(gltf2_io.Accessor.from_dict(accessor))
    return len(data.accessors) - 1


def _channel_as_morph_targets(gltf, animation, where, channel, meshes_done):
    from io_scene_gltf2.io.com import gltf2_io
    from io_scene_gltf2.io.imp.gltf2_io_binary import BinaryData
    import m4mesh

    data = gltf.data
    node = data.nodes[channel["node"]]
    if node.mesh is None:
        raise ImportError(f"{EXTENSION_NAME}: {where}: node {channel['node']} has no mesh")
    mesh = data.meshes[node.mesh]
    if node.mesh in meshes_done:
        raise ImportError(f"{EXTENSION_NAME}: {where}: mesh {node.mesh} plays in two channels, which this add-on does not take yet")
    if len(channel["primitives"]) != len(mesh.primitives):
        raise ImportError(f"{EXTENSION_NAME}: {where}: {len(channel['primitives'])} streams for the {len(mesh.primitives)} primitives of mesh {node.mesh}")
    keys = data.accessors[channel["input"]].count
    for p, (primitive, entry) in enumerate(zip(mesh.primitives, channel["primitives"])):
        stream = bytes(BinaryData.get_buffer_view(gltf, entry["bufferView"]))
        try:
            frames, _ = m4mesh.decode(stream)
        except m4mesh.Error as error:
            raise ImportError(f"{EXTENSION_NAME}: {where}, primitive {p}: {error}") from None
        rest = BinaryData.decode_accessor(gltf, primitive.attributes["POSITION"])
        if frames.shape[0] != keys or frames.shape[1] != rest.shape[0]:
            raise ImportError(f"{EXTENSION_NAME}: {where}, primitive {p}: {frames.shape[0]} frames of {frames.shape[1]} vertices "
                              f"for {keys} key times and {rest.shape[0]} positions")
        primitive.targets = [{"POSITION": _add_floats(gltf, frame - rest, "VEC3", True)} for frame in frames]
    mesh.weights = [0.0] * keys
    mesh.extras = dict(mesh.extras or {}, targetNames=[f"frame {k}" for k in range(keys)])
    meshes_done.add(node.mesh)
    interpolation = channel.get("interpolation", "LINEAR")
    output = _add_floats(gltf, numpy.eye(keys, dtype=numpy.float32).reshape(-1), "SCALAR", False)
    animation.samplers.append(gltf2_io.AnimationSampler.from_dict({"input": channel["input"], "output": output, "interpolation": interpolation}))
    animation.channels.append(gltf2_io.AnimationChannel.from_dict(
        {"sampler": len(animation.samplers) - 1, "target": {"node": channel["node"], "path": "weights"}}))


class glTF2ImportUserExtension:
    def __init__(self):
        from io_scene_gltf2.io.com.gltf2_io_extensions import Extension

        # Listed so that the importer takes files that require the extension (m4mesh gltf --required).
        self.extensions = [Extension(name=EXTENSION_NAME, extension={}, required=True)]

    def gather_import_gltf_before_hook(self, gltf):
        if EXTENSION_NAME not in (gltf.data.extensions_used or []):
            return
        meshes_done = set()
        for a, animation in enumerate(gltf.data.animations or []):
            extension = (animation.extensions or {}).get(EXTENSION_NAME)
            for c, channel in enumerate((extension or {}).get("channels", [])):
                _channel_as_morph_targets(gltf, animation, f"animation {a}, channel {c}", channel, meshes_done)


def register():
    pass


def unregister():
    pass
