"""scripts/short_clips.py, run as the rate tables run it, on a clip of the test frames."""

import json
import os
import subprocess
import sys

import pytest

M4MESH = os.environ["M4MESH_BINARY"]
SOURCE = os.environ["M4MESH_SOURCE_DIR"]
BUILD = os.path.dirname(os.path.dirname(M4MESH))
FRAMES = os.path.join(SOURCE, "tests", "data", "tetra-frames")
SCRIPT = os.path.join(SOURCE, "scripts", "short_clips.py")
BENCH = os.path.join(BUILD, "bench", "m4mesh_baselines_bench")
needs_bench = pytest.mark.skipif(not os.access(BENCH, os.X_OK), reason=f"{BENCH} is not built (the sanitizer build has no benchmarks)")


def short_clips(*args):
    return subprocess.run([sys.executable, SCRIPT, "--build", BUILD, *args], capture_output=True, text=True)


@needs_bench
def test_a_clip_has_its_row_with_both_coders(tmp_path):
    done = short_clips("--window", "tetra=" + FRAMES + ":1:3", "--work", str(tmp_path))
    assert done.returncode == 0, done.stderr
    row = next(line for line in done.stdout.splitlines() if line.startswith("| tetra |"))
    cells = [cell.strip() for cell in row.strip("|").split("|")]
    assert cells[1] == "1 … 3"
    mine = [float(x) for x in cells[2].split(" / ")]
    theirs = [float(x) for x in cells[3].split(" / ")]
    ratios = [float(x.strip("*")) for x in cells[4].split(" / ")]
    for target, rate, ideal, ratio in zip(("0.5", "0.1"), mine, theirs, ratios):
        stream = tmp_path / f"clip0-{target}.m4m"
        facts = json.loads(subprocess.run([M4MESH, "metrics", str(tmp_path / "clip0.m4seq"), str(stream), "--stream", str(stream), "--json"],
                                          check=True, capture_output=True, text=True).stdout)
        assert facts["kg_error_percent"] <= float(target)
        assert abs(facts["stream_rate_bpvf"] - rate) < 0.005
        assert abs(rate / ideal - ratio) < 0.01
    assert "targets the ideal coder reaches are at or below 0.8× its rate" in done.stdout


@needs_bench
def test_the_clip_holds_the_frames_asked_for(tmp_path):
    assert short_clips("--window", "tetra=" + FRAMES + ":1:3", "--work", str(tmp_path)).returncode == 0
    done = subprocess.run([M4MESH, "convert", str(tmp_path / "clip0.m4seq"), str(tmp_path / "again.m4seq")], capture_output=True, text=True)
    assert "3 frames of 5 vertices" in done.stderr


@needs_bench
def test_frames_beyond_the_sequence_fail_with_the_reason(tmp_path):
    done = short_clips("--window", "tetra=" + FRAMES + ":2:12", "--work", str(tmp_path))
    assert done.returncode != 0
    assert "has 4 frames, 0 … 3" in done.stderr


def test_a_malformed_window_is_a_usage_error(tmp_path):
    done = short_clips("--window", "tetra=" + FRAMES, "--work", str(tmp_path))
    assert done.returncode == 2
    assert "NAME=PATH:A:B" in done.stderr
