"""`m4mesh rd` and `python3 -m m4mesh.plot`, run as a user runs them."""

import csv
import json
import os
import subprocess
import sys

import matplotlib.image
from m4mesh import plot
import pytest

M4MESH = os.environ["M4MESH_BINARY"]
SOURCE = os.environ["M4MESH_SOURCE_DIR"]
FRAMES = os.path.join(SOURCE, "tests", "data", "tetra-frames")
COLUMNS = ["codec", "parameter", "bytes", "bpvf", "kg_percent", "psnr_db", "rmse", "sted", "encode_s", "decode_s"]


@pytest.fixture(scope="module")
def sweep(tmp_path_factory):
    out = tmp_path_factory.mktemp("rd") / "rd.csv"
    subprocess.run([M4MESH, "rd", FRAMES, "-o", str(out)], check=True, capture_output=True)
    return out


def test_rows_are_complete(sweep):
    with open(sweep, newline="") as f:
        rows = list(csv.DictReader(f))
    assert rows and list(rows[0].keys()) == COLUMNS
    assert {row["codec"] for row in rows} == {"bfs3d", "affine-octree", "lcc", "cpca-wpt"}
    for row in rows:
        assert all(row[c] != "" for c in COLUMNS)
        assert int(row["bytes"]) > 0 and float(row["bpvf"]) > 0 and float(row["kg_percent"]) >= 0


def test_cpca_wpt_sweeps_with_every_component(sweep):
    # Its noise step alone would stop at 40 components per cluster.
    with open(sweep, newline="") as f:
        rows = [row for row in csv.DictReader(f) if row["codec"] == "cpca-wpt"]
    assert rows and all(row["parameter"].endswith(" --components 4096") for row in rows)


def test_bfs3d_error_falls_with_every_bit(sweep):
    # bfs3d's grid step halves with each bit: its error never grows.
    with open(sweep, newline="") as f:
        rows = [row for row in csv.DictReader(f) if row["codec"] == "bfs3d"]
    bits = [int(row["parameter"].split()[1]) for row in rows]
    kg = [float(row["kg_percent"]) for row in rows]
    assert bits == sorted(bits)
    assert all(b <= a for a, b in zip(kg, kg[1:]))


def test_json_holds_the_same_points(sweep, tmp_path):
    out = tmp_path / "rd.json"
    subprocess.run([M4MESH, "rd", FRAMES, "--codecs", "bfs3d,lcc", "-o", str(out)], check=True, capture_output=True)
    points = json.loads(out.read_text())
    assert {p["codec"] for p in points} == {"bfs3d", "lcc"}
    assert set(points[0].keys()) == set(COLUMNS)


def test_the_points_do_not_depend_on_the_threads(sweep, tmp_path):
    # The fixture ran on every core; one thread measures the same points in the same order (times aside).
    out = tmp_path / "one.csv"
    subprocess.run([M4MESH, "rd", FRAMES, "--threads", "1", "-o", str(out)], check=True, capture_output=True)
    def points(path):
        with open(path, newline="") as f:
            return [{c: row[c] for c in COLUMNS if not c.endswith("_s")} for row in csv.DictReader(f)]
    assert points(out) == points(sweep)


def test_an_unknown_extension_is_a_usage_error(tmp_path):
    result = subprocess.run([M4MESH, "rd", FRAMES, "-o", str(tmp_path / "rd.txt")], capture_output=True, text=True)
    assert result.returncode == 2 and result.stderr.startswith("error: ")
    assert not (tmp_path / "rd.txt").exists()


def test_plot_draws_a_picture(sweep, tmp_path):
    out = tmp_path / "rd.png"
    subprocess.run([sys.executable, "-m", "m4mesh.plot", str(sweep), "-o", str(out), "--title", "tetra"], check=True)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    pixels = matplotlib.image.imread(str(out))
    assert pixels.shape[0] == 420 and pixels.shape[1] == 1000
    assert pixels.std() > 0.01  # not one colour


def test_plot_of_no_points_fails_cleanly(tmp_path):
    empty = tmp_path / "empty.csv"
    empty.write_text(",".join(COLUMNS) + "\n")
    result = subprocess.run([sys.executable, "-m", "m4mesh.plot", str(empty), "-o", str(tmp_path / "x.png")], capture_output=True, text=True)
    assert result.returncode == 1 and "no rate–distortion points" in result.stderr


def test_plot_of_a_csv_not_from_rd_names_the_missing_columns(tmp_path):
    other = tmp_path / "metrics.csv"
    other.write_text("kg_error_percent,rmse\n0.1,0.2\n")
    result = subprocess.run([sys.executable, "-m", "m4mesh.plot", str(other), "-o", str(tmp_path / "x.png")], capture_output=True, text=True)
    assert result.returncode == 1 and "not a CSV of `m4mesh rd`: no column codec, bpvf, kg_percent, sted" in result.stderr


def test_plot_draws_reference_coders_of_one_sequence_beside_a_sweep(sweep, tmp_path):
    # Rows of the baselines benchmark name their sequence: only the asked one's are drawn.
    reference = tmp_path / "baselines.csv"
    reference.write_text(
        "sequence,codec,parameter,bpvf,kg_percent,sted\n"
        "pcow,coddyac-style,8 components,0.2,6.5,0.09\n"
        "pcow,coddyac-style,16 components,0.4,2.3,0.09\n"
        "horse-gallop,coddyac-style,8 components,0.3,2.7,0.30\n"
    )
    codecs = {}
    plot.read_points(str(sweep), "pcow", codecs)
    plot.read_points(str(reference), "pcow", codecs)
    assert [p["bpvf"] for p in codecs["coddyac-style"]] == [0.2, 0.4]
    assert "cpca-wpt" in codecs  # the sweep's rows have no sequence column: all drawn
    out = tmp_path / "both.png"
    subprocess.run([sys.executable, "-m", "m4mesh.plot", str(sweep), str(reference), "--sequence", "pcow", "-o", str(out)], check=True)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_rates_are_read_on_the_lower_front():
    points = [{"bpvf": 1.0, "kg_percent": 1.0}, {"bpvf": 2.0, "kg_percent": 2.0}, {"bpvf": 3.0, "kg_percent": 0.2}, {"bpvf": 5.0, "kg_percent": 0.1}]
    assert plot.rate_at(points, 1.0) == 1.0
    assert plot.rate_at(points, 0.6) == pytest.approx(2.0)  # halfway from (1, 1.0) to (3, 0.2); (2, 2.0) is beaten
    assert plot.rate_at(points, 0.1) == pytest.approx(5.0)
    assert plot.rate_at(points, 0.05) is None
    assert plot.rate_at(points, 4.0) == 1.0


def test_at_kg_prints_every_codec(sweep):
    result = subprocess.run([sys.executable, "-m", "m4mesh.plot", str(sweep), "--at-kg", "5", "0.000001"], capture_output=True, text=True, check=True)
    lines = result.stdout.splitlines()
    assert lines and all(line.endswith("bpvf at KG 5 / 1e-06 %") for line in lines)


def test_plot_of_a_file_that_is_no_text_fails_cleanly(tmp_path):
    binary = tmp_path / "stream.m4m"
    binary.write_bytes(b"\x00\x00\x01\xc4\xff\xfe\x80")
    result = subprocess.run([sys.executable, "-m", "m4mesh.plot", str(binary), "-o", str(tmp_path / "x.png")], capture_output=True, text=True)
    assert result.returncode == 1 and "not a CSV of `m4mesh rd` (not UTF-8 text" in result.stderr and "Traceback" not in result.stderr
