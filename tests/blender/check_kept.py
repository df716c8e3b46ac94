"""m4mesh gltf --bake-skins on a file Blender's exporter wrote (ctest
blender_gltf, tests/blender/test.sh): everything of the input but the baked
skin is in the output. Materials, textures, samplers, images and skins value
for value; the image, the primitives' other attributes, the indices, the
inverse bind matrices and every channel's keys and values byte for byte;
nodes value for value but for the skin the baked node gives up; the mesh's
JOINTS_n and WEIGHTS_n gone, since no node keeps a skin over it.

    python3 check_kept.py IN.glb OUT.glb
"""
import json
import struct
import sys


def parts(path):
    with open(path, "rb") as f:
        content = f.read()
    length = struct.unpack_from("<I", content, 12)[0]
    return json.loads(content[20:20 + length]), content[20 + length + 8:]


def view(document, chunk, index):
    v = document["bufferViews"][index]
    return chunk[v.get("byteOffset", 0):v.get("byteOffset", 0) + v["byteLength"]]


def accessor(document, chunk, index):
    return view(document, chunk, document["accessors"][index]["bufferView"])


(a, bin_a), (b, bin_b) = parts(sys.argv[1]), parts(sys.argv[2])
failures = 0


def report(ok, what):
    global failures
    print(f"{'ok  ' if ok else 'FAIL'} {what}")
    failures += not ok


for key in ("materials", "textures", "samplers", "scenes", "scene", "asset"):
    report(a.get(key) == b.get(key), f"{key} as in the input")
report([{k: v for k, v in n.items() if k != "skin"} for n in a["nodes"]] == b["nodes"],
       "nodes as in the input, but for the baked node's skin")
report(all("skin" not in n for n in b["nodes"] if "mesh" in n), "no node with a mesh keeps a skin")
report([{k: v for k, v in s.items() if k != "inverseBindMatrices"} for s in a["skins"]] ==
       [{k: v for k, v in s.items() if k != "inverseBindMatrices"} for s in b["skins"]] and
       all(accessor(a, bin_a, s["inverseBindMatrices"]) == accessor(b, bin_b, t["inverseBindMatrices"]) for s, t in zip(a["skins"], b["skins"])),
       "the skins, their inverse bind matrices byte for byte")
report(all(image_a.get("mimeType") == image_b.get("mimeType") and view(a, bin_a, image_a["bufferView"]) == view(b, bin_b, image_b["bufferView"])
           for image_a, image_b in zip(a["images"], b["images"])) and len(a["images"]) == len(b["images"]), "the images byte for byte")
for m, (mesh_a, mesh_b) in enumerate(zip(a["meshes"], b["meshes"])):
    for p, (pa, pb) in enumerate(zip(mesh_a["primitives"], mesh_b["primitives"])):
        kept = {name: index for name, index in pa["attributes"].items() if not name.startswith(("JOINTS_", "WEIGHTS_"))}
        report(set(pb["attributes"]) == set(kept) and all(accessor(a, bin_a, kept[n]) == accessor(b, bin_b, pb["attributes"][n]) for n in kept) and
               accessor(a, bin_a, pa["indices"]) == accessor(b, bin_b, pb["indices"]) and pa.get("material") == pb.get("material"),
               f"mesh {m}, primitive {p}: {', '.join(sorted(kept))} and the indices byte for byte, the material, no joints or weights")


def channels(document, chunk, animation):
    return [(c["target"], s.get("interpolation"), accessor(document, chunk, s["input"]), accessor(document, chunk, s["output"]))
            for c in animation["channels"] for s in [animation["samplers"][c["sampler"]]]]


report(len(a["animations"]) == len(b["animations"]) and
       all(x.get("name") == y.get("name") and channels(a, bin_a, x) == channels(b, bin_b, y) for x, y in zip(a["animations"], b["animations"])),
       "every animation's channels, their keys and values byte for byte")
report(all("M4MESH_vertex_animation" in y.get("extensions", {}) for y in b["animations"]), "each animation carries its baked skin as a stream")
sys.exit(1 if failures else 0)
