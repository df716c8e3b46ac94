"""Rate–distortion plots of an `m4mesh rd` sweep.

    python3 -m m4mesh.plot rd.csv [more.csv ...] -o rd.png [--title TITLE] [--sequence NAME]
    python3 -m m4mesh.plot rd.csv [more.csv ...] --at-kg 0.5 0.1

Two panels against bits per vertex per frame, one line per codec: the KG
error (percent) and STED, both on log axes (every codec spans decades).
Several CSVs draw together (the reference coders of
`m4mesh_baselines_bench` beside a sweep); with --sequence, rows with a
`sequence` column are drawn only for that sequence. --at-kg prints each
codec's bits per vertex per frame at those KG errors (percent), read on
its lower front: the points no other point beats in both rate and error,
linear between them; "-" where the codec does not reach the error.
"""

import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)


def read_points(path, sequence=None, codecs=None):
    """The rows of an `m4mesh rd` CSV, grouped by codec in file order (added to `codecs`)."""
    codecs = {} if codecs is None else codecs
    needed = ("codec", "bpvf", "kg_percent", "sted")
    with open(path, newline="", encoding="utf-8") as f:
        try:
            reader = csv.DictReader(f)
            fieldnames = reader.fieldnames
            rows = list(reader)
        except (UnicodeDecodeError, csv.Error) as e:
            raise ValueError(f"{path}: not a CSV of `m4mesh rd` (not UTF-8 text in CSV form: {e.reason if hasattr(e, 'reason') else e})") from None
        missing = [key for key in needed if key not in (fieldnames or [])]
        if missing:
            raise ValueError(
                f"{path}: not a CSV of `m4mesh rd`: no column {', '.join(missing)} (it has {', '.join(fieldnames or []) or 'none'})"
            )
        for line, row in enumerate(rows, start=2):
            if sequence is not None and row.get("sequence", sequence) != sequence:
                continue
            try:
                codecs.setdefault(row["codec"], []).append({key: float(row[key]) for key in needed[1:]})
            except (TypeError, ValueError):
                raise ValueError(f"{path}:{line}: a row whose bpvf, kg_percent or sted is not a number") from None
    if not codecs:
        raise ValueError(f"{path}: no rate–distortion points")
    return codecs


def rate_at(points, kg):
    """The bpvf at KG error `kg` on the points' lower front, linear between points; None if not reached."""
    front = []
    for p in sorted(points, key=lambda p: (p["bpvf"], p["kg_percent"])):
        if not front or p["kg_percent"] < front[-1]["kg_percent"]:
            front.append(p)
    for before, after in zip(front, front[1:]):
        if after["kg_percent"] <= kg <= before["kg_percent"]:
            t = (before["kg_percent"] - kg) / (before["kg_percent"] - after["kg_percent"])
            return before["bpvf"] + t * (after["bpvf"] - before["bpvf"])
    return front[0]["bpvf"] if front and front[0]["kg_percent"] <= kg else None


def plot(codecs, output, title=None, width=10.0, height=4.2):
    """Draws the two panels into `output` (PNG, SVG or PDF by its extension)."""
    figure, axes = plt.subplots(1, 2, figsize=(width, height), constrained_layout=True)
    for name, points in codecs.items():
        points = sorted(points, key=lambda p: p["bpvf"])
        rates = [p["bpvf"] for p in points]
        for axis, key in zip(axes, ("kg_percent", "sted")):
            # A lossless point has no place on a log axis.
            kept = [(r, p[key]) for r, p in zip(rates, points) if p[key] > 0]
            if kept:
                axis.plot(*zip(*kept), marker="o", markersize=3, label=name)
    for axis, label in zip(axes, ("KG error (%)", "STED")):
        axis.set_xscale("log")
        axis.set_yscale("log")
        axis.set_xlabel("bits per vertex per frame")
        axis.set_ylabel(label)
        axis.grid(True, which="both", alpha=0.3)
        axis.legend()
    if title:
        figure.suptitle(title)
    figure.savefig(output, dpi=100)
    plt.close(figure)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m m4mesh.plot", description=__doc__.splitlines()[0])
    parser.add_argument("csv", nargs="+", help="`m4mesh rd` CSVs (or any with codec, bpvf, kg_percent and sted columns)")
    parser.add_argument("-o", "--output", help="the picture (.png, .svg or .pdf)")
    parser.add_argument("--at-kg", type=float, nargs="+", metavar="KG", help="print each codec's bpvf at these KG errors (percent)")
    parser.add_argument("--title", help="a title above both panels")
    parser.add_argument("--sequence", help="draw only the rows of this sequence where a CSV names it")
    args = parser.parse_args(argv)
    if not args.output and not args.at_kg:
        parser.error("give -o PICTURE, --at-kg KG …, or both")
    try:
        codecs = {}
        for path in args.csv:
            read_points(path, args.sequence, codecs)
        for name, points in codecs.items() if args.at_kg else ():
            rates = [rate_at(points, kg) for kg in args.at_kg]
            print(f"{name}: " + " / ".join("-" if r is None else f"{r:.2f}" for r in rates) + f" bpvf at KG {' / '.join(f'{kg:g}' for kg in args.at_kg)} %")
        if args.output:
            plot(codecs, args.output, args.title)
    except (OSError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
