"""The m4mesh Python module: the same streams and MD5s as the command line
on every 3D conformance stream, every codec, and m4mesh.Error on bad input."""

import hashlib
import json
import os
import struct
import subprocess
import threading
import warnings

import numpy as np
import pytest

import m4mesh

M4MESH = os.environ["M4MESH_BINARY"]
SOURCE = os.environ["M4MESH_SOURCE_DIR"]
SUITE = os.path.join(SOURCE, "conformance", "mesh3d")
MANIFEST = json.load(open(os.path.join(SUITE, "manifest.json")))["streams"]
FRAMES = os.path.join(SOURCE, "tests", "data", "tetra-frames")


def stream_of(case):
    with open(os.path.join(SUITE, case["file"]), "rb") as f:
        return f.read()


@pytest.mark.parametrize("case", [c for c in MANIFEST if c["expect"] == "decode"], ids=lambda c: c["id"])
def test_decodes_every_conformance_stream_to_its_md5(case):
    frames, faces = m4mesh.decode(stream_of(case))
    assert frames.dtype == np.float32 and frames.shape[2] == 3 and faces.shape[1] == 3
    assert hashlib.md5(frames.astype("<f4").tobytes()).hexdigest() == case["decoded_md5"]
    one_by_one = m4mesh.frames(stream_of(case))
    streamed = hashlib.md5()
    for frame in one_by_one:
        assert frame.dtype == np.float32 and frame.shape == frames.shape[1:]
        streamed.update(frame.astype("<f4").tobytes())
    assert streamed.hexdigest() == case["decoded_md5"]
    assert np.array_equal(one_by_one.faces, faces)


@pytest.mark.parametrize("case", [c for c in MANIFEST if c["expect"] == "error"], ids=lambda c: c["id"])
def test_rejects_every_bad_conformance_stream_as_the_manifest_says(case):
    for decode in (m4mesh.decode, lambda stream: list(m4mesh.frames(stream))):
        with pytest.raises(m4mesh.Error) as caught:
            decode(stream_of(case))
        assert caught.value.kind == case["error_kind"]
        assert caught.value.element == case["error_element"]
        assert caught.value.frame == case["error_plane"]


@pytest.fixture(scope="module")
def tetra(tmp_path_factory):
    """The test frames as arrays over the bytes of the command line's .m4seq (unaligned: the module must read them so)."""
    path = tmp_path_factory.mktemp("tetra") / "t.m4seq"
    subprocess.run([M4MESH, "convert", FRAMES, str(path)], check=True, capture_output=True)
    data = path.read_bytes()
    vertices, face_count, frame_count = struct.unpack_from("<3I", data, 7)
    faces = np.frombuffer(data, "<u4", face_count * 3, 19).reshape(face_count, 3).astype(np.int32)
    frames = np.frombuffer(data, "<f4", frame_count * vertices * 3, 19 + 12 * face_count).reshape(frame_count, vertices, 3)
    return frames, faces


@pytest.mark.parametrize("codec,options,flags", [
    ("bfs3d", {"bits": 10, "parallelogram": True}, ["--bits", "10", "--parallelogram"]),
    ("affine-octree", {"me": 5}, ["--me", "5"]),
    ("lcc", {"theta_bits": 6, "mode": "download"}, ["--theta-bits", "6", "--mode", "download"]),
    ("cpca-wpt", {"clusters": 2}, ["--clusters", "2"]),
])
def test_encodes_the_same_bytes_as_the_command_line(tetra, tmp_path, codec, options, flags):
    out = tmp_path / "cli.m4m"
    subprocess.run([M4MESH, "encode3d", FRAMES, "--codec", codec, *flags, "-o", str(out)], check=True, capture_output=True)
    frames, faces = tetra
    assert m4mesh.encode(frames, faces, codec=codec, **options) == out.read_bytes()


def test_a_quality_target_and_the_metrics(tetra):
    frames, faces = tetra
    stream = m4mesh.encode(frames, faces, codec="bfs3d", target_kg=0.5, hashes=False)
    decoded, decoded_faces = m4mesh.decode(stream)
    measured = m4mesh.metrics(frames, decoded, decoded_faces)
    assert 0 < measured["kg_error"] <= 0.5
    assert m4mesh.metrics(frames, frames, faces)["kg_error"] == 0


def test_frames_read_from_several_threads_are_each_read_once():
    stream = stream_of(next(c for c in MANIFEST if c["id"] == "bfs3d-01-average"))
    frames = m4mesh.frames(stream)
    read = []

    def reader():
        while True:
            try:
                read.append(next(frames))
            except StopIteration:
                return
            except ValueError:
                pass  # another thread was decoding a frame: try again

    threads = [threading.Thread(target=reader) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(read) == len(m4mesh.decode(stream)[0])


def test_progressive_decoding_ends_at_the_whole_stream():
    stream = stream_of(next(c for c in MANIFEST if c["id"] == "cpca-01-wpt"))
    steps = list(m4mesh.progressive(stream))
    assert [units for units, _, _ in steps] == list(range(1, len(steps) + 1))
    assert steps[-1][1] == len(stream)
    assert np.array_equal(steps[-1][2], m4mesh.decode(stream)[0])
    with pytest.raises(m4mesh.Error, match="progressive"):
        m4mesh.progressive(stream_of(MANIFEST[0]))


def test_reads_2d_planes():
    with open(os.path.join(SOURCE, "conformance", "streams", "p01-hand-3x3.m4m"), "rb") as f:
        planes = m4mesh.read_2d(f.read())
    assert len(planes) == 3 and planes[0]["intra"] and not planes[1]["intra"]
    assert planes[0]["nodes"].shape == (9, 2) and planes[0]["triangles"].shape[1] == 3


def test_runs_the_conformance_suite():
    result = m4mesh.conform(SUITE)
    assert result["failed"] == 0 and result["passed"] == len(MANIFEST)


def test_bad_arguments_raise_m4mesh_error(tetra):
    frames, faces = tetra
    with pytest.raises(m4mesh.Error) as caught:
        m4mesh.encode(frames[:, :, :2], faces)
    assert caught.value.kind == "usage"
    with pytest.raises(m4mesh.Error) as caught:
        m4mesh.encode(frames, faces, codec="nonesuch")
    assert "nonesuch" in str(caught.value)
    with pytest.raises(m4mesh.Error) as caught:
        m4mesh.decode(b"\x00\x00\x01\xc4 not a stream")
    assert caught.value.offset >= 0 or caught.value.kind in ("truncated", "structure")


def test_nan_frames_name_the_frame_and_vertex(tetra):
    frames, faces = tetra
    frames = frames.copy()
    frames[2, 1, 0] = float("nan")
    for target in ({}, {"target_kg": 1}, {"codec": "auto", "target_kg": 1}):
        with pytest.raises(m4mesh.Error) as caught:
            m4mesh.encode(frames, faces, **target)
        assert caught.value.kind == "input" and "frame 2, vertex 1" in str(caught.value)


@pytest.mark.parametrize("target", [{"target_kg": -1}, {"target_kg": 0}, {"target_kg": float("nan")}, {"target_psnr": -5},
                                    {"max_error": 0}, {"max_error": 1, "target_kg": 1}])
def test_a_target_that_is_not_one_is_a_usage_error(tetra, target):
    frames, faces = tetra
    with pytest.raises(m4mesh.Error) as caught:
        m4mesh.encode(frames, faces, **target)
    assert caught.value.kind == "usage"


def test_max_error_bounds_every_decoded_vertex(tetra):
    frames, faces = tetra
    for bound in (0.001, 0.05):
        decoded, _ = m4mesh.decode(m4mesh.encode(frames, faces, codec="bfs3d", max_error=bound))
        assert float(np.linalg.norm(decoded.astype(np.float64) - frames, axis=2).max()) <= bound


def test_auto_keeps_the_smallest_codec_at_the_target(tetra):
    frames, faces = tetra
    stream = m4mesh.encode(frames, faces, codec="auto", target_kg=1)
    decoded, decoded_faces = m4mesh.decode(stream)
    assert m4mesh.metrics(frames, decoded, decoded_faces)["kg_error"] <= 1
    with pytest.raises(m4mesh.Error) as caught:
        m4mesh.encode(frames, faces, codec="auto")
    assert caught.value.kind == "usage"


def test_dir_lists_the_calls():
    assert {"encode", "decode", "frames", "metrics", "progressive", "conform", "plot"} <= set(dir(m4mesh))


@pytest.fixture(scope="module")
def shuffled_sheet():
    """A 6 × 6 sheet of quads under a wave, its vertices numbered at random: no traversal's order."""
    rng = np.random.default_rng(5)
    n = 7
    number = rng.permutation(n * n)
    faces = []
    for y in range(n - 1):
        for x in range(n - 1):
            a, b, c, d = (number[y * n + x], number[y * n + x + 1], number[(y + 1) * n + x + 1], number[(y + 1) * n + x])
            faces += [(a, b, c), (a, c, d)]
    frames = np.zeros((4, n * n, 3), np.float32)
    for f in range(4):
        for y in range(n):
            for x in range(n):
                frames[f, number[y * n + x]] = (x, y, 0.3 * np.sin(x + 0.7 * f))
    return frames, np.array(faces, np.int32)


def test_a_reordered_stream_is_compared_through_the_stream_or_its_faces(shuffled_sheet):
    frames, faces = shuffled_sheet
    plain = m4mesh.metrics(frames, m4mesh.encode(frames, faces, bits=10), faces)
    stream = m4mesh.encode(frames, faces, bits=10, reorder=True)
    with pytest.warns(UserWarning, match="coding order"):
        decoded, decoded_faces = m4mesh.decode(stream)
    assert not np.array_equal(decoded, m4mesh.decode(m4mesh.encode(frames, faces, bits=10))[0])
    for measured in (m4mesh.metrics(frames, stream, faces), m4mesh.metrics(frames, bytearray(stream), faces),
                     m4mesh.metrics(frames, decoded, faces, decoded_faces=decoded_faces)):
        assert measured["kg_error"] == pytest.approx(plain["kg_error"]) and measured["kg_error"] < 1
    with pytest.raises(m4mesh.Error, match="not a stream of this original"):
        m4mesh.metrics(frames, decoded, faces, decoded_faces=decoded_faces[::-1, ::-1].copy())


def test_a_stream_without_reorder_decodes_without_a_warning():
    # The README's example: four vertices the traversal numbers as the input does.
    frames = np.random.default_rng(1).random((10, 4, 3), dtype=np.float32)
    faces = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]], dtype=np.int32)
    stream = m4mesh.encode(frames, faces, codec="bfs3d", bits=12)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        m4mesh.decode(stream)
        for _ in m4mesh.frames(stream):
            pass


def test_streams_are_format_1_0_at_any_blend(shuffled_sheet):
    frames, faces = shuffled_sheet
    streams = [m4mesh.encode(frames, faces, bits=10, position_blend=b) for b in (0, 9, None)]
    assert [s[4] for s in streams] == [0x10] * 3  # the version, after the object start code
    expected = m4mesh.decode(streams[-1])[0]
    assert all(np.array_equal(m4mesh.decode(s)[0], expected) for s in streams[:-1])
    with pytest.raises(ValueError, match="position_blend"):
        m4mesh.encode(frames, faces, position_blend=17)
    with pytest.raises(m4mesh.Error, match="container_version is not an option"):
        m4mesh.encode(frames, faces, container_version=8)


@pytest.mark.parametrize("where", ["original", "decoded"])
def test_metrics_refuse_coordinates_that_are_not_finite(tetra, where):
    frames, faces = tetra
    spoiled = frames.copy()
    spoiled[1, 2, 1] = float("nan") if where == "original" else float("inf")
    with pytest.raises(m4mesh.Error) as caught:
        m4mesh.metrics(spoiled, frames, faces) if where == "original" else m4mesh.metrics(frames, spoiled, faces)
    assert caught.value.kind == "input" and "frame 1, vertex 2 is not a finite point" in str(caught.value)


def test_streams_may_be_any_bytes_like_object(tetra):
    frames, faces = tetra
    stream = m4mesh.encode(frames, faces)
    expected = m4mesh.decode(stream)[0]
    for view in (bytearray(stream), memoryview(stream), np.frombuffer(stream, np.uint8)):
        assert np.array_equal(m4mesh.decode(view)[0], expected)
    for not_bytes in ("a string", 42, np.zeros(4, np.float32)):
        with pytest.raises(TypeError) as caught:
            m4mesh.decode(not_bytes)
        assert len(str(caught.value)) < 200 and "stream:" in str(caught.value)


def test_errors_name_options_as_keywords(tetra):
    frames, faces = tetra
    with pytest.raises(m4mesh.Error) as caught:
        m4mesh.encode(frames, faces, bitz=3)
    assert "bitz is not an option of bfs3d (its options: bits, parallelogram, intra_period)" in str(caught.value)
    with pytest.raises(m4mesh.Error) as caught:
        m4mesh.encode(frames, faces, codec="affine-octree", matrix_bits=8, matrix_range_log2=8)
    assert "--" not in str(caught.value) and "matrix_range_log2" in str(caught.value)
