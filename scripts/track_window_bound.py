#!/usr/bin/python3
"""What window matching can reach on a corpus clip (docs/tracking.md): at
points 16 px apart in frame 0, the best match of a 17 x 17 window of the
coded frame 0 in coded frame t, on the half-pixel grid within 1.5 px of the
truth, and its distance to the truth. Two windows: rigid (a translation,
as shaped by a global motion that is none on a warp clip) and shaped by
the true local motion's linear part (what no tracker knows, its best case).
The half-pixel rounding of the truth is the floor of both.

    /usr/bin/python3 scripts/track_window_bound.py [--set eval|tune] [--only NAME] [--work DIR]
"""
import argparse
import os
import tempfile

import numpy as np

import track_corpus as corpus

RADIUS = 8  # pixels, as the tracker's step 5
SEARCH = 1.5  # pixels around the truth


def bound(motion, video):
    """Mean distance to the truth over frames 1 ... and points in view: (rigid window, shaped window, rounded truth)."""
    frames = corpus.decoded_frames(video)
    reference = corpus.luma(frames[0].astype(float))
    wy, wx = np.mgrid[-RADIUS:RADIUS + 1, -RADIUS:RADIUS + 1].astype(float)
    steps = np.arange(-SEARCH, SEARCH + 0.01, 0.5)
    background = np.zeros(1, bool)
    sums, count = np.zeros(3), 0
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
                errors = []
                for sx, sy in ((wx, wy), (jacobian[0, 0] * wx + jacobian[0, 1] * wy, jacobian[1, 0] * wx + jacobian[1, 1] * wy)):
                    best, at = np.inf, truth
                    for dy in steps:
                        for dx in steps:
                            q = np.rint((truth + [dx, dy]) * 2) / 2
                            cost = np.abs(corpus.bilinear(picture, q[0] + sx, q[1] + sy) - values).mean()
                            if cost < best:
                                best, at = cost, q
                    errors.append(np.hypot(*(at - truth)))
                errors.append(np.hypot(*(np.rint(truth * 2) / 2 - truth)))
                sums += errors
                count += 1
    return sums / count


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--set", choices=("eval", "tune"), default="eval")
    parser.add_argument("--only", default="warp-", help="clips whose name holds this (default: the warp clips)")
    parser.add_argument("--work", help="where the clips go (kept); default a temporary folder")
    args = parser.parse_args()
    work = args.work or tempfile.mkdtemp(prefix="m4mesh-track-bound-")
    os.makedirs(work, exist_ok=True)
    print("| clip | rigid window (px) | shaped by the true motion (px) | half-pixel rounding (px) |")
    print("|---|---|---|---|")
    for kind in corpus.KINDS:
        for seed in corpus.SEEDS[args.set]:
            for crf in corpus.QUALITIES:
                name = f"{args.set}-{kind}-{seed}-crf{crf}"
                if args.only not in name:
                    continue
                motion = corpus.Motion(kind, seed)
                video = os.path.join(work, name + ".mp4")
                if not os.path.exists(video):
                    corpus.write_clip(motion, crf, video)
                rigid, shaped, rounding = bound(motion, video)
                print(f"| {name} | {rigid:.2f} | {shaped:.2f} | {rounding:.2f} |", flush=True)


if __name__ == "__main__":
    main()
