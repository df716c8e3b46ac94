"""The native part of the m4mesh package, m4mesh._native, built by CMake
over the repository around this folder (target m4mesh_python) with what
scripts/install-deps.sh installs; pyproject.toml holds the rest."""

import os
import pathlib
import shutil
import subprocess

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

REPOSITORY = pathlib.Path(__file__).resolve().parent.parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        build.mkdir(parents=True, exist_ok=True)
        launcher = ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"] if shutil.which("ccache") else []
        configure = ["cmake", "-S", str(REPOSITORY), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release", "-DM4MESH_BENCHMARKS=OFF",
                     "-DM4MESH_CGAL=OFF", "-DM4MESH_WEB=OFF", *launcher]
        subprocess.run(configure, check=True, stdout=subprocess.DEVNULL)
        subprocess.run(["cmake", "--build", str(build), "--target", "m4mesh_python", "-j", str(os.cpu_count() or 2)], check=True)
        built = next((build / "python" / "m4mesh").glob("_native*.so"))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


setup(ext_modules=[Extension("m4mesh._native", sources=[])], cmdclass={"build_ext": CMakeBuild})
