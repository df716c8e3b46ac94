"""encode3d's glTF input against Blender: the frames m4mesh baked from a .glb
Blender exported (a .m4seq from `m4mesh convert`) and the positions Blender
evaluated (export_gltf.py's .f32) must be the same points in every frame,
within float32 rounding of the exporter's and the baking's arithmetic. The
exporter may number the vertices its own way, so each point is matched to
the nearest of the other frame's.

    python3 compare_frames.py BAKED.m4seq BLENDER.f32
"""
import math
import struct
import sys

TOLERANCE = 1e-5  # of a model 2 units tall

baked_path, blender_path = sys.argv[1:]
with open(baked_path, "rb") as f:
    data = f.read()
vertices, faces, frames = struct.unpack_from("<3I", data, 7)
values = struct.unpack_from(f"<{3 * vertices * frames}f", data, 7 + 12 + 12 * faces)
baked = [[values[3 * (k * vertices + v):3 * (k * vertices + v) + 3] for v in range(vertices)] for k in range(frames)]
with open(blender_path, "rb") as f:
    data = f.read()
if len(data) % (12 * frames) != 0:
    sys.exit(f"FAIL: {baked_path} has {frames} frames, {blender_path} holds {len(data)} bytes")
points = len(data) // (12 * frames)
values = struct.unpack(f"<{len(data) // 4}f", data)
blender = [[values[3 * (k * points + v):3 * (k * points + v) + 3] for v in range(points)] for k in range(frames)]


def farthest(these, those):
    """The largest distance from a point of `these` to the nearest of `those`."""
    return max(min(math.dist(p, q) for q in those) for p in these)


worst = max(max(farthest(baked[k], blender[k]), farthest(blender[k], baked[k])) for k in range(frames))
status = "ok  " if worst <= TOLERANCE else "FAIL"
print(f"{status} {frames} frames of {vertices} vertices (Blender: {points}): the farthest point is {worst:.2e} from the other's")
sys.exit(0 if worst <= TOLERANCE else 1)
