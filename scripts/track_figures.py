#!/usr/bin/python3
"""The figures of docs/tracking.md: `m4mesh track` on the tests' own videos
(kept by running the track tests with M4MESH_TRACK_KEEP) and on a natural
video (tree.avi from Debian's opencv-doc). Prints the table; draws the
per-frame PSNRs and bits to docs/figures/track-*.png.

    /usr/bin/python3 scripts/track_figures.py [BUILD]   (default build/)
"""
import csv
import os
import re
import subprocess
import sys
import tempfile

import matplotlib

from track_corpus import psnr_of_mean as mean  # noqa: E402 (this folder)

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build"))
M4MESH = os.path.join(BUILD, "cli", "m4mesh")
TREE = "/usr/share/doc/opencv-doc/examples/data/tree.avi"


def track(work, name, video, options):
    report = os.path.join(work, name + ".csv")
    subprocess.run([M4MESH, "-q", "-y", "track", video, "-o", os.path.join(work, name + ".m4m"), "--report", report] + options, check=True)
    with open(report) as f:
        rows = list(csv.DictReader(f))
    return rows




def main():
    work = tempfile.mkdtemp(prefix="m4mesh-track-")
    env = dict(os.environ, M4MESH_TRACK_KEEP=work)
    subprocess.run([os.path.join(BUILD, "tests", "m4mesh_tests"), "--gtest_filter=Track.*", "--gtest_brief=1"], check=True, env=env,
                   stdout=subprocess.DEVNULL)
    cases = [
        ("smooth warp, H.264", "smooth-uniform", os.path.join(work, "track-smooth", "video.mp4"), []),
        ("smooth warp, H.264", "smooth-delaunay", os.path.join(work, "track-smooth", "video.mp4"), ["--nodes", "80"]),
        ("object over a still background, mask", "object", os.path.join(work, "track-object", "%03d.png"),
         ["--nodes", "50", "--mask", os.path.join(work, "track-object", "mask.png")]),
        ("tree.avi (natural), frames 0–59", "tree-uniform", TREE, ["--frames", "0:59"]),
        ("tree.avi (natural), frames 0–59", "tree-delaunay", TREE, ["--frames", "0:59", "--nodes", "300"]),
        ("tree.avi (natural), frames 0–59", "tree-previous", TREE, ["--frames", "0:59", "--reference", "previous"]),
    ]
    print("| video | mesh | nodes | bits / later plane | rendering (dB) | mesh MC (dB) | block MC (dB) | I-planes |")
    print("|---|---|---|---|---|---|---|---|")
    results = {}
    for label, name, video, options in cases:
        rows = track(work, name, video, options)
        results[name] = rows
        info = subprocess.run([M4MESH, "info", os.path.join(work, name + ".m4m")], capture_output=True, text=True).stdout
        nodes = re.search(r"(\d+) nodes", info).group(1)
        mesh = "content-based Delaunay" if "--nodes" in options else "uniform 16 × 16"
        if "previous" in options:
            mesh += ", `--reference previous`"
        bits = sum(int(r["bits"]) for r in rows[1:]) / (len(rows) - 1)
        print(f"| {label} | {mesh} | {nodes} | {bits:.0f} | {mean(rows, 'render_psnr'):.2f} | {mean(rows, 'mesh_mc_psnr'):.2f} | "
              f"{mean(rows, 'block_mc_psnr'):.2f} | {sum(r['intra'] == '1' for r in rows)} |")

    for name, title in (("tree-uniform", "tree.avi, uniform 16 × 16 mesh"), ("smooth-uniform", "smooth warp (H.264), uniform 16 × 16 mesh")):
        rows = results[name]
        frames = [int(r["frame"]) for r in rows[1:]]
        fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 5), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
        def column(key):
            return [float(r[key]) if r[key] not in ("", "inf") else float("nan") for r in rows[1:]]  # an I-plane has no motion compensation
        top.plot(frames, column("render_psnr"), label="texture warped by the mesh vs frame")
        top.plot(frames, column("mesh_mc_psnr"), label="mesh motion compensation")
        top.plot(frames, column("block_mc_psnr"), label="block matching, as many vectors")
        top.set_ylabel("luma PSNR (dB)")
        top.set_title(title)
        top.legend(fontsize=8)
        top.grid(alpha=0.3)
        bottom.bar(frames, [int(r["bits"]) for r in rows[1:]], color="grey")
        bottom.set_ylabel("bits")
        bottom.set_xlabel("frame")
        fig.tight_layout()
        out = os.path.join(ROOT, "docs", "figures", f"track-{name}.png")
        fig.savefig(out, dpi=90)
        print(f"wrote {out}", file=sys.stderr)


if __name__ == "__main__":
    main()
