"""The conformance package: conformance/conform.py gives m4mesh conform's
verdict on every stream of both suites for decoders that err in every way
(wrong output, rejecting everything, killed by a signal: SIGKILL, which
no sanitizer runtime preloaded into the test can catch), and conformance/package.py
writes the same archive twice, which runs on its own."""

import os
import pathlib
import re
import subprocess
import sys
import tarfile

import pytest

M4MESH = os.environ["M4MESH_BINARY"]
SOURCE = pathlib.Path(os.environ["M4MESH_SOURCE_DIR"])
CONFORMANCE = SOURCE / "conformance"
SUITES = {"2d": CONFORMANCE, "3d": CONFORMANCE / "mesh3d"}


def verdicts(output):
    """(stream id, pass/FAIL/skip) per table line."""
    rows = []
    for line in output.splitlines():
        fields = line.split()
        if len(fields) >= 3 and fields[1] in ("decode", "reject"):
            rows.append((fields[0], fields[2]))
    return rows


@pytest.mark.parametrize("suite", sorted(SUITES))
@pytest.mark.parametrize("decoder", ["cp {in} {out}", "false {in} {out}", "sh -c 'kill -KILL $$' {in} {out}",
                                     "sh -c 'exit 3' {in} {out}"])
def test_agrees_with_m4mesh_conform(suite, decoder):
    ours = subprocess.run([sys.executable, str(CONFORMANCE / "conform.py"), "--decoder", decoder, "--suite", suite],
                          capture_output=True, text=True)
    theirs = subprocess.run([M4MESH, "conform", str(SUITES[suite]), "--decoder", decoder], capture_output=True, text=True)
    assert verdicts(ours.stdout) == verdicts(theirs.stdout)
    assert len(verdicts(ours.stdout)) > 50
    assert ours.returncode == 1 and theirs.returncode == 1


def test_crashes_fail_streams_to_reject_too():
    result = subprocess.run([sys.executable, str(CONFORMANCE / "conform.py"), "--decoder", "sh -c 'kill -KILL $$' {in} {out}",
                             "--suite", "3d", "--only", "x-*"], capture_output=True, text=True)
    rows = verdicts(result.stdout)
    assert rows and all(status == "FAIL" for _, status in rows)
    assert "killed by signal 9" in result.stdout


def test_only_and_method_skips():
    result = subprocess.run([sys.executable, str(CONFORMANCE / "conform.py"), "--decoder", f"{M4MESH} decode {{in}} -o {{out}}",
                             "--suite", "2d", "--only", "p0*", "--only", "*method1*"], capture_output=True, text=True)
    rows = verdicts(result.stdout)
    assert any(status == "skip" for _, status in rows)
    assert all(status in ("pass", "skip") for _, status in rows)
    assert all(stream.startswith("p0") or "method1" in stream for stream, _ in rows)
    assert result.returncode == 0  # a skipped (informative Method I) stream does not fail the run


@pytest.mark.skipif(not (CONFORMANCE.parent.parent / "shared" / "spec" / "mesh-bitstream.md").exists(),
                    reason="../shared/spec/mesh-bitstream.md is absent: the package carries it")
def test_the_package_is_the_same_twice_and_runs_alone(tmp_path):
    first, second = tmp_path / "first.tar.gz", tmp_path / "second.tar.gz"
    for archive in (first, second):
        subprocess.run([sys.executable, str(CONFORMANCE / "package.py"), "-o", str(archive)], check=True, capture_output=True)
    assert first.read_bytes() == second.read_bytes()
    with tarfile.open(first) as tar:
        names = set(tar.getnames())
        tar.extractall(tmp_path / "unpacked")
    top = "m4mesh-conformance-" + re.search(r"project\(m4mesh VERSION (\S+)", (CONFORMANCE.parent / "CMakeLists.txt").read_text()).group(1)
    assert top == "m4mesh-conformance-1.0.0"
    package = tmp_path / "unpacked" / top
    for name in ("README.md", "conform.py", "manifest.json", "mesh3d/manifest.json", "docs/container3d.md", "docs/decisions.md", "docs/mesh-bitstream.md"):
        assert f"{top}/{name}" in names
    streams = [n for n in names if "/streams/" in n]
    assert len(streams) == len(list((CONFORMANCE / "streams").iterdir())) + len(list((CONFORMANCE / "mesh3d" / "streams").iterdir()))
    result = subprocess.run([sys.executable, str(package / "conform.py"), "--decoder", f"{M4MESH} decode3d {{in}} -o {{out}}", "--suite", "3d",
                             "--only", "bfs3d-*", "--only", "x-1*"], capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    assert verdicts(result.stdout) and all(status == "pass" for _, status in verdicts(result.stdout))
