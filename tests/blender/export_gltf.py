"""Animations made in Blender and written by its own glTF exporter, for
encode3d's glTF input and m4mesh gltf --bake-skins (ctest blender_gltf,
tests/blender/test.sh): a tube bent by a two-bone armature (a skin), with
UVs and a material whose base colour is a PNG texture, and a sheet moved by
two shape keys (morph targets). Beside each .glb, every frame's evaluated
vertex positions in glTF's axes (Y up) as binary32 x y z, frame after
frame. tests/data/blender-tube-skin.glb is a copy of its skin.glb, for the
tests that run without Blender.

    blender -b --factory-startup --python export_gltf.py -- FOLDER
"""
import math
import os
import struct
import sys

import numpy

numpy.bool = bool  # Debian's numpy 1.24 dropped it; Blender 3.4's glTF exporter still uses it
import bpy  # noqa: E402

FRAMES = 10
folder = sys.argv[sys.argv.index("--") + 1]


def new_scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.fps = 25
    scene.frame_start, scene.frame_end = 1, FRAMES
    return scene


def mesh_object(name, vertices, faces):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(vertices, [], faces)
    for polygon in mesh.polygons:
        polygon.use_smooth = True  # shared normals: the exporter keeps one vertex per position
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def export(scene, obj, name):
    """The .glb by Blender's exporter, and the evaluated frames beside it."""
    bpy.ops.export_scene.gltf(filepath=os.path.join(folder, name + ".glb"), export_format="GLB", export_animations=True,
                              export_force_sampling=True, export_apply=False)
    values = []
    for frame in range(1, FRAMES + 1):
        scene.frame_set(frame)
        evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
        mesh = evaluated.to_mesh()
        for v in mesh.vertices:
            x, y, z = obj.matrix_world @ v.co
            values += [x, z, -y]  # glTF is Y-up
        evaluated.to_mesh_clear()
    with open(os.path.join(folder, name + ".f32"), "wb") as f:
        f.write(struct.pack(f"<{len(values)}f", *values))
    print(f"exported {name}: {len(obj.data.vertices)} vertices, {FRAMES} frames")


def tube(rings=9, around=8):
    vertices = [(0.3 * math.cos(2 * math.pi * a / around), 0.3 * math.sin(2 * math.pi * a / around), 2 * r / (rings - 1))
                for r in range(rings) for a in range(around)]
    faces = []
    for r in range(rings - 1):
        for a in range(around):
            p, q = r * around + a, r * around + (a + 1) % around
            faces += [(p, q, q + around), (p, q + around, p + around)]
    return vertices, faces


def paint(obj, vertices):
    """UVs by planar projection (one per vertex, so the exporter splits none) and a material with a PNG texture."""
    uv = obj.data.uv_layers.new(name="UVMap")
    for loop in obj.data.loops:
        x, _, z = vertices[loop.vertex_index]
        uv.data[loop.index].uv = (x + 0.5, z / 2)
    image = bpy.data.images.new("stripes", 8, 8)
    image.pixels = [c for i in range(64) for c in ((1.0, 0.4, 0.1, 1.0) if (i // 8) % 2 else (0.1, 0.3, 1.0, 1.0))]
    image.filepath_raw = os.path.join(folder, "stripes.png")
    image.file_format = "PNG"
    image.save()
    material = bpy.data.materials.new("striped")
    material.use_nodes = True
    texture = material.node_tree.nodes.new("ShaderNodeTexImage")
    texture.image = image
    material.node_tree.links.new(texture.outputs["Color"], material.node_tree.nodes["Principled BSDF"].inputs["Base Color"])
    obj.data.materials.append(material)


def skinned():
    scene = new_scene()
    vertices, faces = tube()
    obj = mesh_object("tube", vertices, faces)
    paint(obj, vertices)
    armature = bpy.data.armatures.new("bones")
    rig = bpy.data.objects.new("rig", armature)
    scene.collection.objects.link(rig)
    # Placed, turned and scaled: the tube's node has a transform of its own, which a baked skin must undo.
    rig.location, rig.rotation_euler, rig.scale = (0.5, 0.0, 0.25), (0.0, 0.0, 0.3), (1.25, 1.25, 1.25)
    bpy.context.view_layer.objects.active = rig
    bpy.ops.object.mode_set(mode="EDIT")
    lower = armature.edit_bones.new("lower")
    lower.head, lower.tail = (0, 0, 0), (0, 0, 1)
    upper = armature.edit_bones.new("upper")
    upper.head, upper.tail = (0, 0, 1), (0, 0, 2)
    upper.parent = lower
    bpy.ops.object.mode_set(mode="OBJECT")
    # Weights blend from the lower bone to the upper across the middle.
    low, up = obj.vertex_groups.new(name="lower"), obj.vertex_groups.new(name="upper")
    for index, (_, _, z) in enumerate(vertices):
        share = min(1.0, max(0.0, (z - 0.75) / 0.5))
        if share < 1:
            low.add([index], 1 - share, "REPLACE")
        if share > 0:
            up.add([index], share, "REPLACE")
    obj.parent = rig
    obj.modifiers.new("skin", "ARMATURE").object = rig
    pose = rig.pose.bones
    pose["upper"].rotation_mode = "QUATERNION"
    for frame, angle, shift in ((1, 0.0, 0.0), (FRAMES, 1.1, 0.4)):
        pose["upper"].rotation_quaternion = (math.cos(angle / 2), math.sin(angle / 2), 0, 0)
        pose["upper"].keyframe_insert("rotation_quaternion", frame=frame)
        pose["lower"].location = (shift, 0, 0)
        pose["lower"].keyframe_insert("location", frame=frame)
    export(scene, obj, "skin")


def morphed():
    scene = new_scene()
    side = 6
    vertices = [(x / (side - 1), y / (side - 1), 0.0) for y in range(side) for x in range(side)]
    faces = []
    for y in range(side - 1):
        for x in range(side - 1):
            p = y * side + x
            faces += [(p, p + 1, p + side + 1), (p, p + side + 1, p + side)]
    obj = mesh_object("sheet", vertices, faces)
    obj.shape_key_add(name="basis")
    dome, slant = obj.shape_key_add(name="dome"), obj.shape_key_add(name="slant")
    for index, (x, y, _) in enumerate(vertices):
        dome.data[index].co.z = 0.5 - (x - 0.5) ** 2 - (y - 0.5) ** 2
        slant.data[index].co.x = x + 0.3 * y
    for frame, (d, s) in ((1, (0.0, 0.0)), (5, (1.0, 0.2)), (FRAMES, (0.3, 1.0))):
        dome.value, slant.value = d, s
        dome.keyframe_insert("value", frame=frame)
        slant.keyframe_insert("value", frame=frame)
    export(scene, obj, "sheet")


skinned()
morphed()
