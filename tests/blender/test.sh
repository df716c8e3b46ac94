#!/bin/sh
# Blender's glTF importer on decode3d's glTF animation (ctest blender_gltf):
# a small sequence, and the horse when ../shared/data is there.
# Usage: test.sh M4MESH DATA_FOLDER
set -eu
m4mesh="$1"
data="$2"
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
