#!/usr/bin/python3
"""The tracking benchmark (docs/tracking.md): `m4mesh track` judged on
videos with known motion that nothing in the repository is tuned on, and on
natural videos from Debian's opencv-doc.

The synthetic clips are drawn here from procedural textures (defined at
every point, so pans and zooms reveal new content), moved by a known map
M_t from frame 0 to frame t, and coded by FFmpeg's libx264 at two
qualities. Two sets draw from different seeds: `tune` (for whoever adjusts
the tracker) and `eval` (the one the figures and targets are read on).

    /usr/bin/python3 scripts/track_corpus.py [--set eval|tune|both] [--build build] [--work DIR] [--json OUT] [--only NAME] [--crf 18,28]
        [--figures DIR]

For each clip and mesh (the default uniform 16 x 16 cells, and `--nodes 60`)
it reports the mean and 95th-percentile node error in pixels (over nodes
whose true position is in view: in the frame and, for a background node,
not under the object), the rendering PSNR and the mesh and block motion
compensation PSNRs of `m4mesh track --report`, the bits per P-plane and
the number of I-planes; and per clip how far the coded video itself shows
its content behind the truth in its last frame (libx264's own error). On
natural videos (no truth) it reports the PSNRs and the largest growth of a
triangle's area over its area in the I-plane that laid it out.
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WIDTH, HEIGHT, FRAMES, FPS = 320, 240, 30, 25
QUALITIES = (18, 28)  # libx264 CRF
NATURAL = [("vtest.avi", "/usr/share/doc/opencv-doc/examples/data/vtest.avi", "0:99"),
           ("tree.avi", "/usr/share/doc/opencv-doc/examples/data/tree.avi", "0:59")]
# Default options, then the motion-compensation use (docs/tracking.md): each frame matched against the one before.
MESHES = [("uniform 16x16", []), ("60 nodes", ["--nodes", "60"]),
          ("uniform 16x16, previous", ["--reference", "previous"]), ("60 nodes, previous", ["--nodes", "60", "--reference", "previous"])]


def tag(label):
    """A mesh label as part of a file name."""
    return re.sub(r"[^0-9a-z]+", "-", label.lower()).strip("-")
# kind: (global pan px/frame, zoom over the clip, rotation over the clip (rad), warp amplitude px, object)
KINDS = {
    "warp": dict(pan=(0.0, 0.0), zoom=0.0, rotation=0.0, warp=5.0, object=False),
    "warp-pan": dict(pan=(0.6, -0.3), zoom=0.0, rotation=0.0, warp=4.0, object=False),
    "pan": dict(pan=(2.0, 0.7), zoom=0.0, rotation=0.0, warp=1.5, object=False),
    "zoom": dict(pan=(0.0, 0.0), zoom=0.15, rotation=0.0, warp=2.0, object=False),
    "rotation": dict(pan=(0.0, 0.0), zoom=0.0, rotation=0.10, warp=2.0, object=False),
    "object": dict(pan=(0.5, 0.0), zoom=0.0, rotation=0.0, warp=0.0, object=True),
}
SEEDS = {"tune": (1, 2), "eval": (101, 102)}
FIGURE_CLIP = "eval-warp-pan-101-crf18"
VTEST_PICTURE_AFTER = 30  # the vtest picture: the first I-plane from this frame on, 4 frames later


class Texture:
    """A colour picture defined at every point: sums of sinusoids of 6 to 40 pixels' period."""

    def __init__(self, rng, offset):
        count = 24
        period = np.exp(rng.uniform(np.log(6), np.log(40), count))
        angle = rng.uniform(0, np.pi, count)
        self.frequency = np.stack([np.cos(angle), np.sin(angle)], 1) / period[:, None]
        self.phase = rng.uniform(0, 2 * np.pi, (3, count))
        self.weight = rng.uniform(0.3, 1.0, (3, count)) * (20 / np.sqrt(count))
        self.offset = np.asarray(offset, float)

    def at(self, x, y):
        arguments = 2 * np.pi * (x[..., None] * self.frequency[:, 0] + y[..., None] * self.frequency[:, 1])
        channels = [self.offset[c] + np.sum(self.weight[c] * np.sin(arguments + self.phase[c]), -1) for c in range(3)]
        return np.stack(channels, -1)


class Motion:
    """M_t(p) = G_t(p) + W_t(p): a global similarity G_t (pan, zoom, rotation about the
    frame's centre) and a smooth warp W_t growing over the clip; an object clip adds a
    textured disc moved rigidly over the background."""

    def __init__(self, kind, seed):
        self.kind, self.seed = kind, seed
        p = KINDS[kind]
        rng = np.random.default_rng(seed)
        self.background = Texture(rng, (120, 128, 110))
        self.centre = np.array([WIDTH / 2, HEIGHT / 2])
        self.pan, self.zoom, self.rotation, self.warp = np.array(p["pan"]) * rng.uniform(0.8, 1.2), p["zoom"], p["rotation"], p["warp"]
        count = 4
        period = rng.uniform(90, 200, count)
        angle = rng.uniform(0, np.pi, count)
        self.warp_frequency = np.stack([np.cos(angle), np.sin(angle)], 1) / period[:, None]
        self.warp_phase = rng.uniform(0, 2 * np.pi, (2, count))
        self.warp_weight = self.warp * rng.uniform(0.5, 1.0, (2, count)) / np.sqrt(count)
        self.object = None
        if p["object"]:
            self.object = dict(texture=Texture(rng, (170, 90, 80)), centre=np.array([WIDTH * 0.35, HEIGHT * 0.5]), radius=42.0,
                               velocity=np.array([1.6, -0.5]) * rng.uniform(0.8, 1.2), spin=0.004)

    def progress(self, t):
        return t / (FRAMES - 1)

    def global_map(self, t, x, y, inverse=False):
        s, r = 1 + self.zoom * self.progress(t), self.rotation * self.progress(t)
        c, sn = math.cos(r), math.sin(r)
        shift = self.pan * t
        if not inverse:
            dx, dy = x - self.centre[0], y - self.centre[1]
            return self.centre[0] + s * (c * dx - sn * dy) + shift[0], self.centre[1] + s * (sn * dx + c * dy) + shift[1]
        dx, dy = x - self.centre[0] - shift[0], y - self.centre[1] - shift[1]
        return self.centre[0] + (c * dx + sn * dy) / s, self.centre[1] + (-sn * dx + c * dy) / s

    def local(self, t, x, y):
        arguments = 2 * np.pi * (x[..., None] * self.warp_frequency[:, 0] + y[..., None] * self.warp_frequency[:, 1])
        u = self.progress(t)
        return (u * np.sum(self.warp_weight[0] * np.sin(arguments + self.warp_phase[0]), -1),
                u * np.sum(self.warp_weight[1] * np.sin(arguments + self.warp_phase[1]), -1))

    def background_map(self, t, x, y):
        gx, gy = self.global_map(t, x, y)
        wx, wy = self.local(t, x, y)
        return gx + wx, gy + wy

    def background_inverse(self, t, x, y):
        """p with M_t(p) = (x, y), by fixed-point iteration (the warp's slope is well under 1)."""
        px, py = self.global_map(t, x, y, inverse=True)
        for _ in range(12):
            wx, wy = self.local(t, px, py)
            px, py = self.global_map(t, x - wx, y - wy, inverse=True)
        return px, py

    def object_map(self, t, x, y, inverse=False):
        o = self.object
        a = o["spin"] * t * (-1 if inverse else 1)
        c, s = math.cos(a), math.sin(a)
        shift = o["velocity"] * t
        if inverse:
            x, y = x - shift[0], y - shift[1]
        dx, dy = x - o["centre"][0], y - o["centre"][1]
        rx, ry = o["centre"][0] + c * dx - s * dy, o["centre"][1] + s * dx + c * dy
        return (rx, ry) if inverse else (rx + shift[0], ry + shift[1])

    def on_object(self, x, y):
        """Frame-0 points of the object."""
        return self.object is not None and np.hypot(x - self.object["centre"][0], y - self.object["centre"][1]) <= self.object["radius"]

    def truth(self, t, x, y, on_object):
        """Where frame-0 points (x, y) of the object (where on_object) or of the background lie in frame t."""
        bx, by = self.background_map(t, x, y)
        if self.object is None:
            return bx, by
        ox, oy = self.object_map(t, x, y)
        return np.where(on_object, ox, bx), np.where(on_object, oy, by)

    def covered(self, t, x, y):
        """Frame-t points the object covers."""
        if self.object is None:
            return np.zeros(np.shape(x), bool)
        ox, oy = self.object_map(t, x, y, inverse=True)
        return np.hypot(ox - self.object["centre"][0], oy - self.object["centre"][1]) <= self.object["radius"]

    def origin(self, t, x, y):
        """The frame-0 points that lie at (x, y) in frame t (the visible ones), and whether each is the object's.
        A background point revealed since frame 0 may lie under the object's frame-0 disc: its layer says which it is."""
        bx, by = self.background_inverse(t, x, y)
        if self.object is None:
            return bx, by, np.zeros(np.shape(x), bool)
        ox, oy = self.object_map(t, x, y, inverse=True)
        on = self.covered(t, x, y)
        return np.where(on, ox, bx), np.where(on, oy, by), on

    def frame(self, t):
        y, x = np.mgrid[0:HEIGHT, 0:WIDTH] + 0.5
        bx, by = self.background_inverse(t, x, y)
        picture = self.background.at(bx, by)
        if self.object is not None:
            ox, oy = self.object_map(t, x, y, inverse=True)
            distance = np.hypot(ox - self.object["centre"][0], oy - self.object["centre"][1])
            share = np.clip(self.object["radius"] + 0.5 - distance, 0, 1)[..., None]  # the edge antialiased
            picture = share * self.object["texture"].at(ox, oy) + (1 - share) * picture
        return np.clip(np.rint(picture), 0, 255).astype(np.uint8)


def write_clip(motion, crf, path):
    encoder = subprocess.Popen(["ffmpeg", "-v", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s", f"{WIDTH}x{HEIGHT}", "-r", str(FPS),
                                "-i", "-", "-c:v", "libx264", "-preset", "medium", "-crf", str(crf), "-pix_fmt", "yuv420p", path],
                               stdin=subprocess.PIPE)
    for t in range(FRAMES):
        encoder.stdin.write(motion.frame(t).tobytes())
    encoder.stdin.close()
    if encoder.wait() != 0:
        sys.exit(f"ffmpeg failed on {path}")


def luma(rgb):
    return rgb[..., 0] * 0.299 + rgb[..., 1] * 0.587 + rgb[..., 2] * 0.114


def bilinear(picture, x, y):
    x = np.clip(x - 0.5, 0, picture.shape[1] - 1.001)
    y = np.clip(y - 0.5, 0, picture.shape[0] - 1.001)
    x0, y0 = np.floor(x).astype(int), np.floor(y).astype(int)
    fx, fy = x - x0, y - y0
    top = picture[y0, x0] * (1 - fx) + picture[y0, x0 + 1] * fx
    bottom = picture[y0 + 1, x0] * (1 - fx) + picture[y0 + 1, x0 + 1] * fx
    return top * (1 - fy) + bottom * fy


def decoded_frames(video):
    """A corpus clip as FFmpeg decodes it: frames x rows x columns x RGB."""
    raw = subprocess.run(["ffmpeg", "-v", "error", "-i", video, "-f", "rawvideo", "-pix_fmt", "rgb24", "-"], capture_output=True, check=True).stdout
    return np.frombuffer(raw, np.uint8).reshape(-1, HEIGHT, WIDTH, 3)


def video_lag(motion, video):
    """How far the coded video's last frame shows its content behind M_t: at points 16 px apart (away from the frame's
    edge and the disc's), the shift s with decoded(p) = drawn(p + s) over a 17 x 17 window (Lucas-Kanade), projected on
    the true motion there; the mean in pixels (positive: the content lags)."""
    t = FRAMES - 1
    decoded = luma(decoded_frames(video)[t].astype(float))
    drawn = luma(motion.frame(t).astype(float))
    lags = []
    for y in range(24, HEIGHT - 23, 16):
        for x in range(24, WIDTH - 23, 16):
            px, py = x + 0.5, y + 0.5
            ox, oy, _ = motion.origin(t, np.array([px]), np.array([py]))
            if motion.object is not None:
                cx, cy = motion.object_map(t, motion.object["centre"][0], motion.object["centre"][1])
                if abs(math.hypot(px - cx, py - cy) - motion.object["radius"]) < 12:
                    continue
            true = np.array([px - ox[0], py - oy[0]])
            if np.hypot(*true) < 0.5:
                continue
            wy, wx = np.mgrid[-8:9, -8:9]
            wx, wy = wx + px, wy + py
            window = decoded[(wy - 0.5).astype(int), (wx - 0.5).astype(int)]
            shift = np.zeros(2)
            for _ in range(6):
                here = bilinear(drawn, wx + shift[0], wy + shift[1])
                gx = (bilinear(drawn, wx + shift[0] + 0.5, wy + shift[1]) - bilinear(drawn, wx + shift[0] - 0.5, wy + shift[1]))
                gy = (bilinear(drawn, wx + shift[0], wy + shift[1] + 0.5) - bilinear(drawn, wx + shift[0], wy + shift[1] - 0.5))
                a = np.array([[np.sum(gx * gx), np.sum(gx * gy)], [np.sum(gx * gy), np.sum(gy * gy)]])
                if np.linalg.cond(a) > 1e4:
                    break
                shift += np.linalg.solve(a, [np.sum(gx * (window - here)), np.sum(gy * (window - here))])
            lags.append(shift @ true / np.hypot(*true))
    return float(np.mean(lags))


def held_still(video):
    """The share of the coded video's 16 x 16 blocks (libx264's macroblocks, away from the frame's edge) that are a
    whole-pixel copy, within 2 px, of the previous coded frame: content the encoder held still or moved by whole pixels
    (mean absolute difference under 0.05 grey levels)."""
    frames = [luma(f.astype(float)) for f in decoded_frames(video)]
    copies = blocks = 0
    for before, now in zip(frames, frames[1:]):
        for y in range(16, HEIGHT - 31, 16):
            for x in range(16, WIDTH - 31, 16):
                block = now[y:y + 16, x:x + 16]
                copies += any(np.abs(before[y + dy:y + dy + 16, x + dx:x + dx + 16] - block).mean() < 0.05
                              for dy in range(-2, 3) for dx in range(-2, 3))
                blocks += 1
    return copies / blocks


def decoded_planes(m4mesh, stream):
    """Every plane's (intra, nodes in half pixels, triangles of an I-plane), from `m4mesh decode`'s text."""
    text = os.path.splitext(stream)[0] + ".decoded.txt"
    subprocess.run([m4mesh, "-q", "-y", "decode", stream, "-o", text], check=True, stdout=subprocess.DEVNULL)
    planes, lines = [], open(text).read().split("\n")
    k = 0
    while k < len(lines):
        if lines[k].startswith("plane "):
            intra = lines[k].split()[2] == "I"
            count = int(lines[k + 1].split()[1])
            nodes = np.array([[float(v) for v in lines[k + 2 + n].split()] for n in range(count)])
            k += 2 + count
            triangles = None
            if intra:
                faces = int(lines[k].split()[1])
                triangles = np.array([[int(v) for v in lines[k + 1 + n].split()] for n in range(faces)])
                k += 1 + faces
            planes.append((intra, nodes, triangles))
        else:
            k += 1
    return planes


def node_errors(motion, planes):
    """Per P-plane (frame, distances in pixels between tracked and true node positions), nodes in view only."""
    errors = []
    origin = None
    for t, (intra, nodes, _) in enumerate(planes):
        at = nodes / 2.0
        if intra:
            # A new mesh: its nodes' frame-0 points.
            origin = motion.origin(t, at[:, 0], at[:, 1]) if t > 0 else (at[:, 0], at[:, 1], motion.on_object(at[:, 0], at[:, 1]))
            continue
        tx, ty = motion.truth(t, *origin)
        seen = (tx >= 0) & (tx <= WIDTH) & (ty >= 0) & (ty <= HEIGHT)
        if motion.object is not None:
            seen &= origin[2] | ~motion.covered(t, tx, ty)
        errors.append((t, np.hypot(at[seen, 0] - tx[seen], at[seen, 1] - ty[seen])))
    return errors


def largest_stretch(planes):
    """The largest ratio of a triangle's area to its area in the I-plane that laid it out."""
    largest, mesh, design = 1.0, None, None
    for intra, nodes, triangles in planes:
        if intra:
            mesh, design = triangles, area(nodes, triangles)
            continue
        ratio = area(nodes, mesh) / np.maximum(design, 1e-9)
        largest = max(largest, float(ratio.max()))
    return largest


def area(nodes, triangles):
    a, b, c = nodes[triangles[:, 0]], nodes[triangles[:, 1]], nodes[triangles[:, 2]]
    return np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])) / 8.0  # pixels²


def psnr_of_mean(rows, key):
    """The PSNR of the mean squared error of frames 1 … (as m4mesh track prints it)."""
    errors = [10 ** (-float(r[key]) / 10) for r in rows[1:] if r[key] not in ("", "nan", "inf")]
    return -10 * math.log10(sum(errors) / len(errors)) if errors else float("nan")


def track(m4mesh, video, options, work, name):
    stream, report, texture = os.path.join(work, name + ".m4m"), os.path.join(work, name + ".csv"), os.path.join(work, name + ".png")
    subprocess.run([m4mesh, "-q", "-y", "track", video, "-o", stream, "--report", report, "--texture", texture] + options, check=True)
    with open(report) as f:
        rows = list(csv.DictReader(f))
    planes = decoded_planes(m4mesh, stream)
    return rows, planes


def summary(rows, planes):
    bits = [int(r["bits"]) for r, (intra, _, _) in zip(rows, planes) if not intra]
    return dict(render=psnr_of_mean(rows, "render_psnr"), mesh_mc=psnr_of_mean(rows, "mesh_mc_psnr"), block_mc=psnr_of_mean(rows, "block_mc_psnr"),
                bits_per_p_plane=sum(bits) / max(1, len(bits)), i_planes=sum(intra for intra, _, _ in planes), nodes=len(planes[0][1]))


def crf_list(text):
    return tuple(int(v) for v in text.split(","))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--set", choices=("eval", "tune", "both"), default="eval")
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--work", help="where the clips and streams go (kept); default a temporary folder")
    parser.add_argument("--json", help="write every figure here")
    parser.add_argument("--only", help="clips whose name holds this")
    parser.add_argument("--crf", type=crf_list, default=QUALITIES, help="libx264 qualities, comma-separated (default 18,28; 0 is lossless)")
    parser.add_argument("--figures", help="draw docs/tracking.md's figures into this folder")
    args = parser.parse_args()
    m4mesh = os.path.join(os.path.abspath(args.build), "cli", "m4mesh")
    work = args.work or tempfile.mkdtemp(prefix="m4mesh-track-corpus-")
    os.makedirs(work, exist_ok=True)
    sets = ("tune", "eval") if args.set == "both" else (args.set,)
    results = []
    print("| clip | mesh | nodes | mean error (px) | 95th pct (px) | rendering (dB) | mesh MC (dB) | block MC (dB) | bits / P-plane | I-planes | video's lag (px) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for which in sets:
        for kind in KINDS:
            for seed in SEEDS[which]:
                for crf in args.crf:
                    name = f"{which}-{kind}-{seed}-crf{crf}"
                    if args.only and args.only not in name:
                        continue
                    motion = Motion(kind, seed)
                    video = os.path.join(work, name + ".mp4")
                    if not os.path.exists(video):
                        write_clip(motion, crf, video)
                    lag = video_lag(motion, video)
                    for label, options in MESHES:
                        rows, planes = track(m4mesh, video, options, work, name + "-" + tag(label))
                        per_frame = node_errors(motion, planes)
                        errors = np.concatenate([e for _, e in per_frame])
                        r = dict(clip=name, kind=kind, set=which, crf=crf, mesh=label, mean_error=float(errors.mean()),
                                 p95_error=float(np.percentile(errors, 95)), worst_error=float(errors.max()), video_lag=lag, **summary(rows, planes))
                        r["per_frame"] = dict(error=[[t, float(e.mean())] for t, e in per_frame], rows=rows)
                        results.append(r)
                        print(f"| {name} | {label} | {r['nodes']} | {r['mean_error']:.2f} | {r['p95_error']:.2f} | {r['render']:.2f} | {r['mesh_mc']:.2f} | "
                              f"{r['block_mc']:.2f} | {r['bits_per_p_plane']:.0f} | {r['i_planes']} | {lag:.2f} |", flush=True)
    for name, path, frames in NATURAL:
        if (args.only and args.only not in name) or not os.path.exists(path):
            if not args.only:
                print(f"skip: {path} is absent (Debian's opencv-doc)")
            continue
        for label, options in MESHES:
            rows, planes = track(m4mesh, path, options + ["--frames", frames], work, name + "-" + tag(label))
            stretch = largest_stretch(planes)
            r = dict(clip=f"{name} {frames}", mesh=label, stretch=stretch, per_frame=dict(rows=rows), **summary(rows, planes))
            results.append(r)
            print(f"| {name} frames {frames} | {label} | {r['nodes']} | — | — | {r['render']:.2f} | {r['mesh_mc']:.2f} | {r['block_mc']:.2f} | "
                  f"{r['bits_per_p_plane']:.0f} | {r['i_planes']} (largest area growth {stretch:.2f}x) |", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    if args.figures:
        figures(m4mesh, work, results, args.figures)


def figures(m4mesh, work, results, folder):
    """Per-frame plots of one synthetic and one natural clip, and the tracked mesh on vtest.avi."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    os.makedirs(folder, exist_ok=True)
    for r in results:
        synthetic = "error" in r["per_frame"]
        if not ((synthetic and r["clip"] == FIGURE_CLIP and r["mesh"] == "60 nodes") or (r["clip"].startswith("vtest") and r["mesh"] == MESHES[0][0])):
            continue
        rows = r["per_frame"]["rows"]
        frames = [int(x["frame"]) for x in rows]
        figure, axis = plt.subplots(figsize=(8, 3.6))
        for key, label in (("render_psnr", "rendering"), ("mesh_mc_psnr", "mesh MC"), ("block_mc_psnr", "block MC")):
            axis.plot(frames, [float(x[key]) if x[key] not in ("", "inf") else float("nan") for x in rows], label=label)
        for x in rows[1:]:
            if x["intra"] == "1":
                axis.axvline(int(x["frame"]), color="grey", linewidth=0.6, linestyle=":")
        axis.set_xlabel("frame (dotted: a new I-plane)")
        axis.set_ylabel("luma PSNR (dB)")
        if synthetic:
            errors = axis.twinx()
            errors.plot([t for t, _ in r["per_frame"]["error"]], [e for _, e in r["per_frame"]["error"]], color="black", linewidth=1, label="mean node error")
            errors.set_ylabel("mean node error (px)")
            errors.legend(loc="lower right")
        axis.legend(loc="lower left")
        axis.set_title(f"{r['clip']}, {r['mesh']}")
        name = "track-corpus-synthetic.png" if synthetic else "track-corpus-vtest.png"
        figure.tight_layout()
        figure.savefig(os.path.join(folder, name), dpi=90)
        plt.close(figure)
        if not synthetic:
            # The mesh over the rendering of a P-plane a few frames after an I-plane, walkers in view.
            plane = next(k + 4 for k, x in enumerate(rows) if k >= VTEST_PICTURE_AFTER and x["intra"] == "1")
            stream, texture = os.path.join(work, "vtest.avi-" + tag(MESHES[0][0]) + ".m4m"), os.path.join(work, "vtest.avi-" + tag(MESHES[0][0]) + ".png")
            subprocess.run([m4mesh, "-q", "-y", "render", stream, "--texture", texture, "--plane", str(plane), "--wireframe", "-o",
                            os.path.join(folder, "track-vtest-mesh.png")], check=True)
            print(f"figures: {folder}/track-vtest-mesh.png is plane {plane}")


if __name__ == "__main__":
    main()
