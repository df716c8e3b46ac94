"""A decoded animation opened in Blender, rendered headless (docs/gltf.md's
picture): Blender's own glTF importer, a camera framing the mesh from the
side, a sun and Cycles on the CPU.

    blender -b --factory-startup --python scripts/render_gltf_in_blender.py -- ANIM.glb OUT.png [FRAME]
"""
import math
import sys

import numpy

numpy.bool = bool  # Debian's numpy 1.24 dropped it; Blender 3.4's glTF importer still uses it
import bpy  # noqa: E402
from mathutils import Vector  # noqa: E402

arguments = sys.argv[sys.argv.index("--") + 1:]
glb, out = arguments[:2]
frame = int(arguments[2]) if len(arguments) > 2 else 0

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb)
scene = bpy.context.scene
mesh = next(o for o in scene.objects if o.type == "MESH")
scene.frame_set(frame)
for polygon in mesh.data.polygons:
    polygon.use_smooth = True

# The evaluated mesh's box, seen from the side across its longer extent, 15° above, from as
# far as keeps its length inside the picture's wide angle and its height inside the narrow one.
evaluated = mesh.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh()
points = [mesh.matrix_world @ v.co for v in evaluated.vertices]
low = Vector([min(p[i] for p in points) for i in range(3)])
high = Vector([max(p[i] for p in points) for i in range(3)])
centre, size = (low + high) / 2, high - low
across = Vector((0, -1, 0)) if size.x >= size.y else Vector((1, 0, 0))
elevation = math.radians(15)
camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
scene.render.resolution_x, scene.render.resolution_y = 800, 450
wide = camera.data.angle  # across the picture's longer side (sensor fit: auto)
narrow = 2 * math.atan(math.tan(wide / 2) * scene.render.resolution_y / scene.render.resolution_x)
length, depth = max(size.x, size.y), min(size.x, size.y)
distance = depth / 2 + 1.2 * max(length / 2 / math.tan(wide / 2), size.z / 2 / math.tan(narrow / 2))
camera.location = centre + distance * (math.cos(elevation) * across + Vector((0, 0, math.sin(elevation))))
camera.rotation_euler = (centre - camera.location).to_track_quat("-Z", "Y").to_euler()
scene.collection.objects.link(camera)
scene.camera = camera
sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
sun.data.energy = 4
sun.rotation_euler = (math.radians(40), math.radians(20), math.radians(30))
scene.collection.objects.link(sun)
world = bpy.data.worlds.new("world")
world.color = (0.05, 0.06, 0.08)
scene.world = world

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 24
scene.cycles.use_denoising = False  # Debian's Blender is built without OpenImageDenoise
scene.render.filepath = out
bpy.ops.render.render(write_still=True)
print(f"rendered {glb} frame {frame} to {out}")
