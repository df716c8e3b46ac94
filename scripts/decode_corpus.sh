#!/usr/bin/env bash
# Decoding speed over the corpus (docs/rate_distortion.md, "Decoding
# speed"): the horse, the cow, the flag and the FAMC clips of ../shared/data,
# each coded by every codec at its defaults and at KG 0.5 and 0.1 %, kept in
# build/decode-corpus (made once, with a NAME.m4m.missed for a target out of a
# codec's reach; delete it to code again), then decoded by
# bench/decode_bench.cc on one core (taskset -c 0): vertex-frames a second,
# the first frame and the base mesh alone, the median of 5, and the stream's
# arithmetic-coded bins decoded alone (as vertex-frames a second if decoding
# took only their time).
#   bash scripts/decode_corpus.sh [BUILD]      # BUILD: build (default)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
m4mesh="$build/cli/m4mesh"
data=../shared/data
corpus="$build/decode-corpus"
[ -d "$data" ] || { echo "decode_corpus.sh: $data is absent: no corpus to decode"; exit 0; }
mkdir -p "$corpus"
declare -A inputs=([horse]="$data/horse-gallop" [cow]="$data/pcow" [flag]="$data/cloth/flag/flag.pc2"
                   [dance]="$data/openfamc_testdata/dance_mesh" [dog]="$data/openfamc_testdata/dog_mesh"
                   [handstand]="$data/openfamc_testdata/handstand_mesh")
streams=()
for name in horse cow flag dance dog handstand; do
  for codec in bfs3d affine-octree lcc cpca-wpt; do
    for target in default 0.5 0.1; do
      out="$corpus/$name-$codec-$target.m4m"
      # A target out of the codec's reach is noted beside the streams, and not tried again.
      [ -e "$out.missed" ] && continue
      if [ ! -s "$out" ]; then
        echo "coding $out" >&2
        if [ "$target" = default ]; then
          "$m4mesh" -q encode3d "${inputs[$name]}" --codec "$codec" -o "$out"
        elif ! "$m4mesh" -q encode3d "${inputs[$name]}" --codec "$codec" --target-kg "$target" -o "$out"; then
          echo "  $codec misses KG $target on $name: left out" >&2
          touch "$out.missed"
          continue
        fi
      fi
      streams+=("$(realpath "$out")")
    done
  done
done
list=$(IFS=,; echo "${streams[*]}")
M4MESH_DECODE_STREAMS="$list" taskset -c 0 "$build/bench/m4mesh_decode_bench" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_format=json > "$corpus/results.json"
python3 - "$corpus/results.json" <<'PYTHON'
import json, sys
runs = {b["run_name"]: b for b in json.load(open(sys.argv[1]))["benchmarks"] if b.get("aggregate_name") == "median"}
print(f"{'stream':<30} {'ms':>9} {'M vf/s':>8} {'first frame ms':>15} {'base mesh ms':>13} {'bins alone M vf/s':>18} {'ns/bin':>7}")
for name, b in runs.items():
    if not name.startswith("Decode/"):
        continue
    stream = name[len("Decode/"):]
    first, base, bins = (runs.get(f"{part}/{stream}", {}) for part in ("FirstFrame", "BaseMesh", "Bins"))
    print(f"{stream[:-4]:<30} {b['real_time']:>9.2f} {b['vf/s'] / 1e6:>8.2f} {first.get('real_time', 0):>15.2f} {base.get('real_time', 0):>13.2f}"
          f" {bins.get('vf/s', 0) / 1e6:>18.1f} {1e9 / bins['bins/s'] if bins.get('bins/s') else 0:>7.2f}")
PYTHON
