"""Blender's glTF importer with blender/m4mesh_gltf.py on files of m4mesh gltf
(ctest blender_gltf, tests/blender/test.sh): the Basis is the primitive's
POSITION, there is a shape key per decoded frame, and at each key's time
the evaluated mesh is the frame m4mesh decodes (within Blender's float32
sums Basis + (frame − Basis): at most 2 ulps of the larger term). Given the
frames Blender evaluated before export (export_gltf.py's .f32, in the
world), a baked skin's frames placed by their object's world transform are
those points, within the stream's error (WORLD_TOLERANCE).

    blender -b --factory-startup --python check_extension.py -- FILE.glb ADDON_FOLDER PYTHON_FOLDER [WORLD.f32]
"""
import json
import struct
import sys

import numpy

numpy.bool = bool  # Debian's numpy 1.24 dropped it; Blender 3.4's glTF importer still uses it
import addon_utils  # noqa: E402
import bpy  # noqa: E402

WORLD_TOLERANCE = 1e-3  # of a model 2 units tall
glb, addon_folder, python_folder, *world_frames = sys.argv[sys.argv.index("--") + 1:]
sys.path[:0] = [addon_folder, python_folder]
import m4mesh  # noqa: E402

bpy.ops.wm.read_factory_settings(use_empty=True)
addon_utils.enable("m4mesh_gltf", default_set=True)
bpy.ops.import_scene.gltf(filepath=glb)

# The stream, taken out of the file and decoded; the rest pose.
with open(glb, "rb") as f:
    content = f.read()
length = struct.unpack_from("<I", content, 12)[0]
document = json.loads(content[20:20 + length])
bin_chunk = content[20 + length + 8:]
channel = document["animations"][0]["extensions"]["M4MESH_vertex_animation"]["channels"][0]
view = document["bufferViews"][channel["primitives"][0]["bufferView"]]
frames, _ = m4mesh.decode(bin_chunk[view.get("byteOffset", 0):view.get("byteOffset", 0) + view["byteLength"]])

mesh_object = next(o for o in bpy.context.scene.objects if o.type == "MESH" and o.data.shape_keys)
keys = mesh_object.data.shape_keys.key_blocks
vertices = len(mesh_object.data.vertices)
failures = 0


def as_gltf(blender_points):
    """Blender's Z-up coordinates as glTF's Y-up ones: (x, y, z) came in as (x, -z, y)."""
    points = numpy.array(blender_points, dtype=numpy.float32).reshape(-1, 3)
    return numpy.stack([points[:, 0], points[:, 2], -points[:, 1]], axis=1)


def report(ok, what):
    global failures
    print(f"{'ok  ' if ok else 'FAIL'} {what}")
    failures += not ok


report(len(keys) == frames.shape[0] + 1 and vertices == frames.shape[1],
       f"{len(keys) - 1} shape keys over the Basis for {frames.shape[0]} frames, {vertices} vertices for {frames.shape[1]}")
rest = as_gltf([c for point in keys[0].data for c in point.co])
world = None
if world_frames:
    world = numpy.fromfile(world_frames[0], dtype="<f4").reshape(frames.shape[0], -1, 3)
curves = {c.data_path: c for c in mesh_object.data.shape_keys.animation_data.action.fcurves}
for k in sorted({0, frames.shape[0] // 2, frames.shape[0] - 1}):
    curve = curves[f'key_blocks["{keys[k + 1].name}"].value']
    at = next(p.co[0] for p in curve.keyframe_points if p.co[1] == 1.0)
    bpy.context.scene.frame_set(int(at), subframe=at - int(at))
    evaluated = mesh_object.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh()
    got = as_gltf([c for v in evaluated.vertices for c in v.co])
    # Units in the last place of the larger of the two numbers Blender sums.
    ulps = numpy.abs(got - frames[k]) / numpy.spacing(numpy.maximum(numpy.maximum(numpy.abs(frames[k]), numpy.abs(rest)), numpy.float32(1e-30)))
    report(float(ulps.max()) <= 2, f"frame {k} (scene frame {at:g}): every vertex within {float(ulps.max()):.0f} ulps of the decoded frame")
    if world is not None:
        placed = as_gltf([c for v in evaluated.vertices for c in mesh_object.matrix_world @ v.co])
        # The exporter numbers vertices its own way: each point against the nearest of the other's.
        distances = numpy.linalg.norm(placed[:, None, :] - world[k][None, :, :], axis=2)
        farthest = float(max(distances.min(axis=1).max(), distances.min(axis=0).max()))
        report(farthest <= WORLD_TOLERANCE, f"frame {k}: placed by its object, every point within {farthest:.1e} of Blender's skinned one")
    mesh_object.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh_clear()
sys.exit(1 if failures else 0)
