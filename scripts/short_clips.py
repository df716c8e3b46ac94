#!/usr/bin/python3
"""Short clips against the Coddyac-style coder (docs/rate_distortion.md,
"Short clips"): windows of 11 frames cut from ../shared/data's long
sequences, each coded by `m4mesh encode3d --codec auto --target-kg X
--reorder` and by the ideal coder of bench/baselines_bench.cc, in bits per
vertex and frame at KG 0.5 % and 0.1 %, with m4mesh's rate over the ideal
coder's (the mark is 0.8).

    /usr/bin/python3 scripts/short_clips.py [--build build] [--data ../shared/data] [--work DIR] [--set tune|unseen|all]
        [--window NAME=PATH:A:B ...] [--mark 0.8]

`tune` holds the windows rate choices were made on, `unseen` those no
choice was made on. --window replaces both by clips of your own: the
frames A ... B (from 0) of any sequence `m4mesh convert` reads. Prints a
Markdown table and the targets met; exits 1 if a tool fails, a stream
misses its KG or the data is absent, 2 on a malformed --window (a clip
is cut with `m4mesh convert --frames`).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TARGETS = ("0.5", "0.1")
# (name, sequence in the data folder, first frame from 0); 11 frames each.
TUNE = [("horse 0", "horse-gallop", 0), ("horse 19", "horse-gallop", 19), ("horse 34", "horse-gallop", 34),
        ("cow 0", "pcow", 0), ("cow 59", "pcow", 59), ("cow 149", "pcow", 149)]
UNSEEN = [("cow 14", "pcow", 14), ("cow 29", "pcow", 29), ("cow 44", "pcow", 44), ("cow 79", "pcow", 79),
          ("cow 99", "pcow", 99), ("cow 119", "pcow", 119), ("cow 134", "pcow", 134), ("cow 164", "pcow", 164),
          ("cow 179", "pcow", 179), ("cow 193", "pcow", 193),
          ("flag 49", "cloth/flag/flag.pc2", 49), ("flag 99", "cloth/flag/flag.pc2", 99),
          ("flag 149", "cloth/flag/flag.pc2", 149), ("flag 199", "cloth/flag/flag.pc2", 199),
          ("flag 249", "cloth/flag/flag.pc2", 249), ("flag 289", "cloth/flag/flag.pc2", 289)]
FRAMES = 11


def run(command, env=None):
    done = subprocess.run(command, capture_output=True, text=True, env=env)
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)}: exit {done.returncode}\n{done.stderr}")
    return done.stdout


def clips(args, parser):
    if args.window:
        out = []
        for spec in args.window:
            name, _, rest = spec.partition("=")
            parts = rest.rsplit(":", 2)
            if not name or len(parts) != 3:
                parser.error(f"--window {spec}: NAME=PATH:A:B")
            out.append((name, parts[0], f"{parts[1]}:{parts[2]}"))
        return out
    chosen = {"tune": TUNE, "unseen": UNSEEN, "all": TUNE + UNSEEN}[args.set]
    if not os.path.isdir(args.data):
        sys.exit(f"{args.data}: no such folder (the real sequences; --data names another)")
    return [(name, os.path.join(args.data, sequence), f"{first}:{first + FRAMES - 1}") for name, sequence, first in chosen]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data"))
    parser.add_argument("--work", help="keep the clips and streams here (default: a temporary folder, removed)")
    parser.add_argument("--set", choices=("tune", "unseen", "all"), default="all")
    parser.add_argument("--window", action="append", help="NAME=PATH:A:B, frames A ... B of PATH (repeatable)")
    parser.add_argument("--mark", type=float, default=0.8)
    args = parser.parse_args()
    wanted = clips(args, parser)
    m4mesh = os.path.join(args.build, "cli", "m4mesh")
    bench = os.path.join(args.build, "bench", "m4mesh_baselines_bench")
    for tool in (m4mesh, bench):
        if not os.access(tool, os.X_OK):
            sys.exit(f"{tool}: not built (cmake --build {args.build} --target m4mesh m4mesh_baselines_bench)")
    with tempfile.TemporaryDirectory() as temporary:
        work = args.work or temporary
        os.makedirs(work, exist_ok=True)
        rows = []
        for index, (name, path, frames) in enumerate(wanted):
            clip = os.path.join(work, f"clip{index}.m4seq")
            run([m4mesh, "-q", "-y", "convert", path, clip, "--frames", frames])
            rates = {}
            for target in TARGETS:
                stream = os.path.join(work, f"clip{index}-{target}.m4m")
                run([m4mesh, "-q", "-y", "encode3d", clip, "--codec", "auto", "--target-kg", target, "--reorder", "-o", stream])
                facts = json.loads(run([m4mesh, "metrics", clip, stream, "--stream", stream, "--json"]))
                if facts["kg_error_percent"] > float(target):
                    sys.exit(f"{name}: the stream for KG {target} % decodes at KG {facts['kg_error_percent']:.4f} %")
                rates[target] = facts["stream_rate_bpvf"]
            rows.append({"name": name, "path": path, "frames": frames, "clip": clip, "m4mesh": rates})
            print(f"{name}: m4mesh {rates['0.5']:.2f} / {rates['0.1']:.2f} bpvf", file=sys.stderr)
        env = dict(os.environ, M4MESH_BASELINES_SEQUENCES=":".join(row["clip"] for row in rows))
        report = json.loads(run([bench, "--benchmark_filter=Coddyac", "--benchmark_format=json"], env=env))
        ideal = {b["label"]: b for b in report["benchmarks"]}
    met = reached = 0
    print("| clip | frames | m4mesh bpvf (KG 0.5 / 0.1 %) | coddyac-style | m4mesh ÷ coddyac-style |")
    print("|---|---|---|---|---|")
    for row in rows:
        if row["clip"] not in ideal:
            sys.exit(f"{row['clip']}: the baselines bench did not run it")
        mine, theirs, ratios = [], [], []
        for target in TARGETS:
            rate = ideal[row["clip"]][f"coddyac-style_bpvf_kg{target}"]
            mine.append(f"{row['m4mesh'][target]:.2f}")
            if rate != rate:  # NaN: the ideal coder never reaches the target
                theirs.append("—")
                ratios.append("—")
                continue
            ratio = row["m4mesh"][target] / rate
            reached += 1
            met += ratio <= args.mark
            theirs.append(f"{rate:.2f}")
            ratios.append(f"{ratio:.2f}" if ratio <= args.mark else f"**{ratio:.2f}**")
        frames = row["frames"].replace(":", " … ")
        print(f"| {row['name']} | {frames} | {' / '.join(mine)} | {' / '.join(theirs)} | {' / '.join(ratios)} |")
    print(f"\n{met} of {reached} targets the ideal coder reaches are at or below {args.mark}× its rate (in bold: above).")


if __name__ == "__main__":
    main()
