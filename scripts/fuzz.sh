#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan) and runs each for a
# bounded time, seeded from the conformance suite. Fails on any crash, leak,
# timeout, out-of-memory or sanitizer report; findings are left in
# BUILD/findings/ (turn them into regression tests in tests/fuzz_regressions/).
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET (default 60)] [BUILD]
#   BUILD: a build folder configured with clang and -DM4MESH_FUZZ=ON (scripts/test.sh's
#   build-sanitize); without it, build-fuzz, configured here.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
build="${2:-build-fuzz}"
if [ -z "${2:-}" ]; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
    -DM4MESH_FUZZ=ON -DM4MESH_CGAL=OFF -DM4MESH_BENCHMARKS=OFF -DM4MESH_WEB=OFF > /dev/null
fi
# The fuzz targets and the tool that checks the build and makes their seeds (nothing else when configured here).
cmake --build "$build" -j"$(nproc)" --target m4mesh decoder_fuzzer checker_fuzzer text_fuzzer mesh3d_fuzzer gltf_fuzzer api_fuzzer > /dev/null

# The clang build decodes every conformance stream (the manifests' MD5s
# come from GCC builds): decoding is bit-exact across compilers.
"$build"/cli/m4mesh conform conformance > /dev/null || { echo "clang build: 2D conformance failed"; exit 1; }
"$build"/cli/m4mesh conform conformance/mesh3d > /dev/null || { echo "clang build: 3D conformance failed"; exit 1; }
echo "clang build: both conformance suites decode to the manifests' MD5s"

work="$build"/run
rm -rf "$work"
mkdir -p "$work/seeds-stream" "$work/seeds-text" "$work/seeds-mesh3d" "$work/seeds-gltf" "$work/seeds-api" "$build"/findings
# Seeds no longer than the inputs the fuzzers make (-max_len).
find conformance/streams tests/fuzz_regressions -name '*.m4m' -size -8193c -exec cp {} "$work/seeds-stream/" \;
cp tests/fuzz_regressions/*.txt "$work/seeds-text/" 2> /dev/null || true
for stream in conformance/streams/p0*.m4m conformance/streams/p1*.m4m conformance/streams/p2[0-4]*.m4m; do
  "$build"/cli/m4mesh decode "$stream" -o "$work/seeds-text/$(basename "$stream" .m4m).txt" > /dev/null 2>&1 || true
done

# 3D streams: the 3D conformance suite (both codecs), and the first frames
# of a test sequence with both bfs3d predictions.
cp conformance/mesh3d/streams/*.m4m "$work/seeds-mesh3d/"
for bits in 6 10; do
  "$build"/cli/m4mesh encode3d tests/data/tetra-frames -o "$work/seeds-mesh3d/tetra-$bits.m4m" --bits "$bits" > /dev/null 2>&1 || true
  "$build"/cli/m4mesh encode3d tests/data/tetra-frames -o "$work/seeds-mesh3d/tetra-$bits-p.m4m" --bits "$bits" --parallelogram > /dev/null 2>&1 || true
done

# glTF: a small animation as GLB (morph targets and a STEP weights animation), at two rates, and a skin Blender exported.
for fps in 25 7; do
  "$build"/cli/m4mesh -y convert tests/data/tetra-frames "$work/seeds-gltf/tetra-$fps.glb" --fps "$fps" > /dev/null 2>&1 || true
done
cp tests/data/blender-tube-skin.glb "$work/seeds-gltf/"

# The C interface's inputs: a stream and the size of the pieces it is pushed in (its last byte + 1).
for stream in "$work"/seeds-stream/*.m4m "$work"/seeds-mesh3d/*.m4m; do
  { cat "$stream"; printf '\074'; } > "$work/seeds-api/$(basename "$stream")"
done

# One fuzzer per core at a time, each for the same time; their reports in the targets' order.
fuzz_one() {
  local target=$1 seeds="$work/seeds-stream"
  [ "$target" = text ] && seeds="$work/seeds-text"
  [ "$target" = mesh3d ] && seeds="$work/seeds-mesh3d"
  [ "$target" = gltf ] && seeds="$work/seeds-gltf"
  [ "$target" = api ] && seeds="$work/seeds-api"
  mkdir -p "$work/corpus-$target"
  local status=0
  "$build"/fuzz/${target}_fuzzer "$work/corpus-$target" "$seeds" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 -max_len=4096 -print_final_stats=1 -artifact_prefix="$build"/findings/ > "$work/$target.log" 2>&1 || status=$?
  echo "$status" > "$work/$target.status"
}
targets=(decoder checker text mesh3d gltf api)
echo "== ${#targets[@]} fuzzers for ${seconds}s each, $(nproc) at a time"
for target in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do wait -n || true; done
  fuzz_one "$target" &
done
wait
total=0
for target in "${targets[@]}"; do
  if [ "$(cat "$work/$target.status")" != 0 ]; then
    tail -40 "$work/$target.log"
    echo "FAIL: ${target}_fuzzer found a problem (artifact in $build/findings/)"
    exit 1
  fi
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$work/$target.log" | grep -o '[0-9]*$')
  echo "${target}_fuzzer: $runs executions, no findings"
  total=$((total + runs))
done
echo "fuzzing: $total executions in all, no findings"
