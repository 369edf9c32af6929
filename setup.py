"""Builds rayint._rayint with CMake for `pip install .` (pyproject.toml says why setuptools).

The extension is the CMake target `rayint_python` (src/python/CMakeLists.txt), compiled for the
interpreter running this script (sys.executable). Environment:
  RAYINT_CMAKE_BUILD_DIR  an already configured rayint build folder: only its rayint_python target
                          is built there (no second configure); otherwise a fresh folder under
                          setuptools' build_temp is configured with tests, benchmarks and the CLI off.
  CMAKE_BUILD_PARALLEL_LEVEL  as for cmake --build (default 2).
"""
import glob
import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.environ.get("RAYINT_CMAKE_BUILD_DIR")
        if not build:
            build = os.path.abspath(os.path.join(self.build_temp, "cmake"))
            subprocess.check_call([
                "cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                "-DRAYINT_BUILD_TESTS=OFF", "-DRAYINT_BUILD_BENCHMARKS=OFF", "-DRAYINT_BUILD_CLI=OFF",
                "-DRAYINT_BUILD_PYTHON=ON",
                "-DPYTHON_EXECUTABLE=" + sys.executable, "-DPython3_EXECUTABLE=" + sys.executable])
        env = dict(os.environ)
        env.setdefault("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.check_call(["cmake", "--build", build, "--target", "rayint_python"], env=env)
        built = glob.glob(os.path.join(build, "python", "rayint", "_rayint*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one _rayint*.so in {build}/python/rayint, found {built}")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[0], target)


setup(ext_modules=[CMakeExtension("rayint._rayint")], cmdclass={"build_ext": CMakeBuild})
