#!/bin/sh
# Blender and m4mesh's glTF both ways (ctest blender_gltf): Blender's
# importer on decode3d's glTF animation (a small sequence, and the horse when
# ../shared/data is there); then encode3d on a skin and on morph targets
# Blender made and its exporter wrote; then m4mesh gltf on the shape-key
# sheet and on decode3d's glTF, and with --bake-skins on the skinned tube
# (a textured material, a placed armature), imported again with
# blender/m4mesh_gltf.py; the tube's output is checked by the Khronos
# validator (npm gltf-validator, with Node) and against its input.
# Usage: test.sh M4MESH DATA_FOLDER PYTHON_FOLDER (build/python: the m4mesh package the add-on decodes with)
set -eu
m4mesh="$1"
data="$2"
python_folder="$3"
here="$(cd "$(dirname "$0")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
check() {
  "$m4mesh" -q -y encode3d "$1" -o "$work/s.m4m"
  "$m4mesh" -q -y decode3d "$work/s.m4m" -o "$work/s.glb"
  "$m4mesh" -q -y decode3d "$work/s.m4m" -o "$work/s.f32"
  echo "$1:"
  status=0
  blender -b --factory-startup --python "$here/check_gltf.py" -- "$work/s.glb" "$work/s.f32" > "$work/out" 2>&1 || status=$?
  grep -E '^(ok|FAIL|frame)' "$work/out" || tail -5 "$work/out"
  return $status
}
check "$here/../data/tetra-frames"
if [ -d "$data/horse-gallop" ]; then
  check "$data/horse-gallop"
else
  echo "blender_gltf: ../shared/data is absent: the horse is skipped"
fi
blender -b --factory-startup --python "$here/export_gltf.py" -- "$work" > "$work/out" 2>&1 || { tail -20 "$work/out"; exit 1; }
for name in skin sheet; do
  echo "$name.glb (Blender's exporter):"
  "$m4mesh" -q -y convert "$work/$name.glb" "$work/$name.m4seq"
  python3 "$here/compare_frames.py" "$work/$name.m4seq" "$work/$name.f32"
  "$m4mesh" -q -y encode3d "$work/$name.glb" -o "$work/$name.m4m"
  "$m4mesh" -q metrics "$work/$name.m4seq" "$work/$name.m4m" | grep -i kg
done
# M4MESH_vertex_animation: the compressed files back in Blender, through the add-on.
for name in sheet s skin; do
  echo "$name.glb compressed (m4mesh gltf), imported with blender/m4mesh_gltf.py:"
  world=""
  if [ "$name" = skin ]; then
    "$m4mesh" -q -y gltf "$work/skin.glb" -o "$work/skin-m4mesh.glb" --codec bfs3d --bake-skins
    node "$here/../../web/tests/validate.mjs" "$work/skin.glb" "$work/skin-m4mesh.glb"
    python3 "$here/check_kept.py" "$work/skin.glb" "$work/skin-m4mesh.glb"
    world="$work/skin.f32"
  else
    "$m4mesh" -q -y gltf "$work/$name.glb" -o "$work/$name-m4mesh.glb" --codec bfs3d
  fi
  status=0
  blender -b --factory-startup --python "$here/check_extension.py" -- "$work/$name-m4mesh.glb" "$here/../../blender" "$python_folder" $world > "$work/out" 2>&1 || status=$?
  grep -E '^(ok|FAIL)' "$work/out" || tail -5 "$work/out"
  [ "$status" -eq 0 ] || exit "$status"
done
