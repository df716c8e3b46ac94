"""`m4mesh render`, `render3d` and `demo --gif`: real picture files, as a user opens them."""

import os
import subprocess

import pytest
from PIL import Image

M4MESH = os.environ["M4MESH_BINARY"]

# A uniform I-plane, a P-plane without motion, a P-plane that moves.
TEXT = """m4mesh-decoded 1
plane 0 I uniform cols=5 rows=4 dx=24 dy=20 split=0
nodes 20
""" + "".join(f"{24 * (i % 5)} {20 * (i // 5)}\n" for i in range(20)) + """triangles 24
""" + "".join(
    f"{a} {a + 1} {a + 6}\n{a} {a + 6} {a + 5}\n" for a in [r * 5 + c for r in range(3) for c in range(4)]
) + """plane 1 P range=1
nodes 20
""" + "".join(f"{24 * (i % 5)} {20 * (i // 5)}\n" for i in range(20)) + """plane 2 P range=2
nodes 20
""" + "".join(f"{24 * (i % 5) + (i % 5) * 2} {20 * (i // 5) + (i % 3)}\n" for i in range(20)) + "end\n"


@pytest.fixture(scope="module")
def stream(tmp_path_factory):
    folder = tmp_path_factory.mktemp("render")
    (folder / "in.txt").write_text(TEXT)
    out = folder / "in.m4m"
    subprocess.run([M4MESH, "encode", str(folder / "in.txt"), "-o", str(out)], check=True, capture_output=True)
    return out


def draw(command, source, out, *options):
    subprocess.run([M4MESH, command, str(source), "-o", str(out), *options], check=True, capture_output=True)
    return Image.open(out)


def test_png_of_a_plane(stream, tmp_path):
    picture = draw("render", stream, tmp_path / "p2.png", "--plane", "2", "--wireframe")
    assert picture.format == "PNG" and picture.size == (53, 32)  # nodes up to (104, 62) half pixels: pixels 0 … 52, 0 … 31
    assert len(set(picture.convert("RGB").getdata())) > 2


def test_gif_of_every_plane(stream, tmp_path):
    picture = draw("render", stream, tmp_path / "all.gif", "--fps", "10")
    assert picture.format == "GIF" and picture.n_frames == 3 and picture.info["duration"] == 100
    assert len(set(picture.convert("RGB").getdata())) > 2


def test_zero_motion_shows_the_texture_unwarped(stream, tmp_path):
    texture = tmp_path / "texture.png"
    Image.effect_mandelbrot((40, 30), (-2, -1.2, 1, 1.2), 60).convert("RGB").save(texture)
    still = draw("render", stream, tmp_path / "p0.png", "--plane", "0", "--texture", str(texture))
    zero = draw("render", stream, tmp_path / "p1.png", "--plane", "1", "--texture", str(texture))
    assert list(still.getdata()) == list(zero.getdata())
    moved = draw("render", stream, tmp_path / "p2.png", "--plane", "2", "--texture", str(texture))
    assert list(moved.getdata()) != list(still.getdata())


def test_a_3d_stream_or_a_missing_plane_is_a_usage_error(stream, tmp_path):
    result = subprocess.run([M4MESH, "render", str(stream), "-o", str(tmp_path / "x.png"), "--plane", "9"], capture_output=True, text=True)
    assert result.returncode == 2 and "planes 0 … 2" in result.stderr
    assert not (tmp_path / "x.png").exists()


def test_demo_draws_the_flag(tmp_path):
    out = tmp_path / "flag.gif"
    result = subprocess.run([M4MESH, "demo", "--frames", "12", "--gif", str(out)], check=True, capture_output=True, text=True)
    assert "bit-exact" in result.stdout
    picture = Image.open(out)
    assert picture.n_frames == 12 and picture.size[0] > 200


FRAMES = os.path.join(os.environ["M4MESH_SOURCE_DIR"], "tests", "data", "tetra-frames")


def test_render3d_png_and_gif(tmp_path):
    picture = draw("render3d", FRAMES, tmp_path / "t.png", "--frame", "2", "--size", "128")
    assert picture.format == "PNG" and picture.size == (128, 128)
    assert len(set(picture.convert("RGB").getdata())) > 2
    animation = draw("render3d", FRAMES, tmp_path / "t.gif", "--size", "64")
    assert animation.n_frames == 4 and animation.size == (64, 64)


def test_render3d_compare_puts_the_original_beside_the_error(tmp_path):
    stream = tmp_path / "t.m4m"
    subprocess.run([M4MESH, "encode3d", FRAMES, "--bits", "5", "-o", str(stream)], check=True, capture_output=True)
    picture = draw("render3d", stream, tmp_path / "c.png", "--compare", FRAMES, "--size", "100").convert("RGB")
    assert picture.size == (2 * 100 + 80, 100)
    left = {picture.getpixel((x, y)) for x in range(100) for y in range(100)}
    right = {picture.getpixel((x, y)) for x in range(100, 200) for y in range(100)}
    assert len(left) > 2 and len(right) > 2 and left != right
