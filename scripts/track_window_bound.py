#!/usr/bin/python3
"""What window matching can reach on a corpus clip (docs/tracking.md): at
points 16 px apart in frame 0, the best match of a 17 x 17 window of the
coded frame 0 in coded frame t, on the half-pixel grid within 1.5 px of the
truth, and its distance to the truth. Two windows: rigid (a translation,
as shaped by a global motion that is none on a warp clip) and shaped by
the true local motion's linear part (what no tracker knows, its best case).
The half-pixel rounding of the truth is the floor of both. The same rigid
window at points 16 px apart on the frame's edges (the tracker's border
nodes), holding only the pixels in the frame, shows what the coded video
lets a border node reach. Last, the share of the coded video's 16 x 16
blocks that are whole-pixel copies of the previous coded frame: content
libx264 held still while the drawn clip moved it.

    /usr/bin/python3 scripts/track_window_bound.py [--set eval|tune] [--only NAME] [--work DIR] [--crf 18,28]
"""
import argparse
import os
import tempfile

import numpy as np

import track_corpus as corpus

RADIUS = 8  # pixels, as the tracker's step 5
SEARCH = 1.5  # pixels around the truth
STEPS = np.arange(-SEARCH, SEARCH + 0.01, 0.5)  # the half-pixel offsets searched


def nearest_match(picture, values, sx, sy, truth):
    """The distance to the truth of the half-pixel position within SEARCH of it where the window (offsets sx, sy,
    reference values) has the least mean absolute difference over its samples in the frame."""
    best, at = np.inf, truth
    for dy in STEPS:
        for dx in STEPS:
            q = np.rint((truth + [dx, dy]) * 2) / 2
            x, y = q[0] + sx, q[1] + sy
            inside = (x >= 0) & (y >= 0) & (x <= corpus.WIDTH) & (y <= corpus.HEIGHT)
            if 2 * inside.sum() < inside.size:
                continue
            cost = np.abs(corpus.bilinear(picture, x[inside], y[inside]) - values[inside]).mean()
            if cost < best:
                best, at = cost, q
    return np.hypot(*(at - truth))


def edge_points():
    """Points 16 px apart on the frame's edges, where the tracker lays its border nodes."""
    right, bottom = corpus.WIDTH - 0.5, corpus.HEIGHT - 0.5
    for x in range(16, corpus.WIDTH - 15, 16):
        yield float(x), 0.0
        yield float(x), bottom
    for y in range(16, corpus.HEIGHT - 15, 16):
        yield 0.0, float(y)
        yield right, float(y)


def edge_bound(motion, reference, t, picture):
    """Sum and count of the rigid window's distances to the truth at the edge points in view in frame t."""
    background = np.zeros(1, bool)
    total, count = 0.0, 0
    for px, py in edge_points():
        truth = np.array(motion.truth(t, np.array([px]), np.array([py]), background)).ravel()
        if not (0 <= truth[0] <= corpus.WIDTH and 0 <= truth[1] <= corpus.HEIGHT):
            continue
        j, i = np.mgrid[-RADIUS:RADIUS + 1, -RADIUS:RADIUS + 1]
        cx, cy = np.floor(px) + i + 0.5, np.floor(py) + j + 0.5
        keep = (cx >= 1) & (cy >= 1) & (cx <= corpus.WIDTH - 1) & (cy <= corpus.HEIGHT - 1)
        values = reference[(cy[keep] - 0.5).astype(int), (cx[keep] - 0.5).astype(int)]
        total += nearest_match(picture, values, cx[keep] - px, cy[keep] - py, truth)
        count += 1
    return total, count


def bound(motion, video):
    """Mean distance to the truth over frames 1 ... and points in view: (rigid window, shaped window, rounded truth,
    rigid window at the frame's edges)."""
    frames = corpus.decoded_frames(video)
    reference = corpus.luma(frames[0].astype(float))
    wy, wx = np.mgrid[-RADIUS:RADIUS + 1, -RADIUS:RADIUS + 1].astype(float)
    background = np.zeros(1, bool)
    sums, count = np.zeros(3), 0
    edge_sum, edge_count = 0.0, 0
    for t in range(1, len(frames)):
        picture = corpus.luma(frames[t].astype(float))
        for oy in range(24, corpus.HEIGHT - 23, 16):
            for ox in range(24, corpus.WIDTH - 23, 16):
                values = reference[oy + wy.astype(int), ox + wx.astype(int)]
                px, py = ox + 0.5, oy + 0.5
                if motion.on_object(px, py):
                    continue
                truth = np.array(motion.truth(t, np.array([px]), np.array([py]), background)).ravel()
                if not (RADIUS + 4 < truth[0] < corpus.WIDTH - RADIUS - 4 and RADIUS + 4 < truth[1] < corpus.HEIGHT - RADIUS - 4):
                    continue
                jacobian = np.zeros((2, 2))
                for axis, (dx, dy) in enumerate(((0.5, 0), (0, 0.5))):
                    ahead = np.array(motion.truth(t, np.array([px + dx]), np.array([py + dy]), background)).ravel()
                    behind = np.array(motion.truth(t, np.array([px - dx]), np.array([py - dy]), background)).ravel()
                    jacobian[:, axis] = ahead - behind
                errors = [nearest_match(picture, values, sx, sy, truth)
                          for sx, sy in ((wx, wy), (jacobian[0, 0] * wx + jacobian[0, 1] * wy, jacobian[1, 0] * wx + jacobian[1, 1] * wy))]
                errors.append(np.hypot(*(np.rint(truth * 2) / 2 - truth)))
                sums += errors
                count += 1
        total, points = edge_bound(motion, reference, t, picture)
        edge_sum, edge_count = edge_sum + total, edge_count + points
    return (*(sums / count), edge_sum / edge_count)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--set", choices=("eval", "tune"), default="eval")
    parser.add_argument("--only", default="warp-", help="clips whose name holds this (default: the warp clips)")
    parser.add_argument("--work", help="where the clips go (kept); default a temporary folder")
    parser.add_argument("--crf", type=corpus.crf_list, default=corpus.QUALITIES, help="libx264 qualities, comma-separated (default 18,28)")
    args = parser.parse_args()
    work = args.work or tempfile.mkdtemp(prefix="m4mesh-track-bound-")
    os.makedirs(work, exist_ok=True)
    print("| clip | rigid window (px) | shaped by the true motion (px) | half-pixel rounding (px) | rigid window at the frame's edges (px) "
          "| blocks held still |")
    print("|---|---|---|---|---|---|")
    for kind in corpus.KINDS:
        for seed in corpus.SEEDS[args.set]:
            for crf in args.crf:
                name = f"{args.set}-{kind}-{seed}-crf{crf}"
                if args.only not in name:
                    continue
                motion = corpus.Motion(kind, seed)
                video = os.path.join(work, name + ".mp4")
                if not os.path.exists(video):
                    corpus.write_clip(motion, crf, video)
                rigid, shaped, rounding, edges = bound(motion, video)
                print(f"| {name} | {rigid:.2f} | {shaped:.2f} | {rounding:.2f} | {edges:.2f} | {100 * corpus.held_still(video):.0f} % |", flush=True)


if __name__ == "__main__":
    main()
