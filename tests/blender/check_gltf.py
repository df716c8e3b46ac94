"""Blender's own glTF importer on m4mesh's glTF animation (ctest blender_gltf,
tests/blender/test.sh): at the first, a middle and the last frame, the
evaluated vertex positions must equal the decoded frames bit for bit (float32),
in the stream's vertex order.

    blender -b --factory-startup --python check_gltf.py -- ANIM.glb FRAMES.f32
"""
import struct
import sys

import numpy

numpy.bool = bool  # Debian's numpy 1.24 dropped it; Blender 3.4's glTF importer still uses it
import bpy  # noqa: E402

glb, f32 = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb)
mesh_object = next(o for o in bpy.context.scene.objects if o.type == "MESH")
keys = mesh_object.data.shape_keys.key_blocks
vertices = len(mesh_object.data.vertices)
with open(f32, "rb") as f:
    data = f.read()
frames = len(data) // (vertices * 12)
if frames * vertices * 12 != len(data) or len(keys) != frames + 1:
    sys.exit(f"FAIL: {vertices} vertices, {len(keys) - 1} shape keys, {len(data)} bytes of frames")

# The scene frame at which shape key k has weight 1: its first keyframe of value 1.
curves = {c.data_path: c for c in mesh_object.data.shape_keys.animation_data.action.fcurves}
failures = 0
for k in sorted({0, frames // 2, frames - 1}):
    curve = curves[f'key_blocks["{keys[k + 1].name}"].value']
    at = next(p.co[0] for p in curve.keyframe_points if p.co[1] == 1.0)
    bpy.context.scene.frame_set(int(at), subframe=at - int(at))  # the key's own time: the stream's frame rate need not be the scene's
    evaluated = mesh_object.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh()
    expected = struct.unpack_from(f"<{3 * vertices}f", data, 12 * vertices * k)
    wrong = 0
    for v in range(vertices):
        x, y, z = evaluated.vertices[v].co
        # glTF is Y-up, Blender Z-up: (x, y, z) comes in as (x, -z, y).
        got = struct.unpack("<3f", struct.pack("<3f", x, z, -y))
        if got != expected[3 * v:3 * v + 3]:
            wrong += 1
            if wrong <= 3:
                print(f"frame {k} vertex {v}: Blender {got}, decoded {expected[3 * v:3 * v + 3]}")
    print(f"{'ok  ' if wrong == 0 else 'FAIL'} frame {k} (scene frame {at:g}): {vertices - wrong} of {vertices} vertices equal the decoded frame")
    failures += wrong > 0
    mesh_object.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh_clear()
sys.exit(1 if failures else 0)
