"""The native part of the m4mesh package, m4mesh._native, built by CMake
over the repository around this folder (target m4mesh_python) with what
scripts/install-deps.sh installs; pyproject.toml holds the rest.

The module is built for the Python that runs this (pip's). It reuses the
repository's build/ when that holds the module for this Python (after
scripts/demo.sh: seconds), else builds in a folder of its own outside the
tree, kept for the next install (M4MESH_PYTHON_BUILD, default
~/.cache/m4mesh/python-TAG). CMake's progress goes to the terminal, where
pip would hide it; nothing is written into the source tree."""

import atexit
import importlib.util
import os
import pathlib
import shutil
import subprocess
import sys
import sysconfig
import tempfile

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

REPOSITORY = pathlib.Path(__file__).resolve().parent.parent
SUFFIX = sysconfig.get_config_var("EXT_SUFFIX")
TAG = sysconfig.get_config_var("SOABI") or f"py{sys.version_info.major}{sys.version_info.minor}"

# What building and running the module needs of this Python, with a way out for each.
MISSING = [name for name in ("numpy", "wheel") if importlib.util.find_spec(name) is None]
if MISSING:
    sys.exit(f"m4mesh: {sys.executable} lacks {' and '.join(MISSING)}, which the package needs to build and run. Offline, Debian's "
             "python3-numpy and python3-wheel serve /usr/bin/python3: /usr/bin/python3 -m venv --system-site-packages env && "
             "env/bin/pip install --no-build-isolation --no-index ./python")


def progress_stream():
    """The terminal, where pip shows only a spinner; else standard error (pip -v shows it)."""
    try:
        return open("/dev/tty", "w")
    except OSError:
        return sys.stderr


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        out = progress_stream()
        ready = REPOSITORY / "build" / "python" / "m4mesh" / f"_native{SUFFIX}"
        if ready.exists():
            build = REPOSITORY / "build"
            print(f"m4mesh: bringing the module of {build} up to date", file=out, flush=True)
        else:
            build = pathlib.Path(os.environ.get("M4MESH_PYTHON_BUILD", pathlib.Path.home() / ".cache" / "m4mesh" / f"python-{TAG}"))
            build.mkdir(parents=True, exist_ok=True)
            print(f"m4mesh: building the module for {sys.executable} with CMake in {build} (kept for the next install; from nothing "
                  "about 5 minutes on 2 cores)", file=out, flush=True)
            launcher = ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"] if shutil.which("ccache") else []
            configure = ["cmake", "-S", str(REPOSITORY), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release", "-DM4MESH_BENCHMARKS=OFF",
                         "-DM4MESH_CGAL=OFF", "-DM4MESH_WEB=OFF", f"-DM4MESH_PYTHON={sys.executable}", *launcher]
            subprocess.run(configure, check=True, stdout=subprocess.DEVNULL)
        subprocess.run(["cmake", "--build", str(build), "--target", "m4mesh_python", "-j", str(os.cpu_count() or 2)], check=True,
                       stdout=out, stderr=subprocess.STDOUT)
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(build / "python" / "m4mesh" / f"_native{SUFFIX}", target)


# setuptools' own folders (build/, m4mesh.egg-info) outside the source tree.
scratch = tempfile.mkdtemp(prefix="m4mesh-setup-")
atexit.register(shutil.rmtree, scratch, True)
setup(ext_modules=[Extension("m4mesh._native", sources=[])], cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": os.path.join(scratch, "build")}, "egg_info": {"egg_base": scratch}})
