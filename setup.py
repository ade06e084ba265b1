"""Builds the `talus` extension module through the project's CMake, for `pip install .`.

pyproject.toml holds the metadata; this file only teaches setuptools' build_ext to run CMake
(target talus_python) and to copy the module it builds into the wheel. Environment:

- TALUS_CMAKE_BUILD_DIR: build in this CMake build folder (configured here if it is not yet),
  e.g. the `build/` of scripts/test.sh, so that an installed package costs no second build of
  the library; unset: a Release build of the library and module alone in setuptools' own
  temporary folder (build-pip/ in the checkout).
- CMAKE_BUILD_PARALLEL_LEVEL: compile jobs (default: the number of cores).
"""
import os
import pathlib
import re
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    """The version of CMakeLists.txt's project() call: one version for C++ and Python."""
    match = re.search(r"project\(talus VERSION ([0-9][0-9.]*)", (ROOT / "CMakeLists.txt").read_text())
    if match is None:
        raise RuntimeError("setup.py: no `project(talus VERSION x.y.z` in CMakeLists.txt")
    return match.group(1)


class CMakeBuild(build_ext):
    """build_ext that configures (when needed) and builds the CMake target talus_python."""

    def build_extension(self, ext):
        given = os.environ.get("TALUS_CMAKE_BUILD_DIR")
        build_dir = (pathlib.Path(given) if given else pathlib.Path(self.build_temp) / "cmake").resolve()
        if not (build_dir / "CMakeCache.txt").exists():
            self.spawn(["cmake", "-S", str(ROOT), "-B", str(build_dir),
                        "-DCMAKE_BUILD_TYPE=Release", "-DBUILD_TESTING=OFF",
                        "-DTALUS_BUILD_EXPERIMENTS=OFF", "-DTALUS_BUILD_BENCHMARKS=OFF",
                        "-DTALUS_BUILD_NOTEBOOKS=OFF", "-DTALUS_BUILD_PYTHON=ON",
                        f"-DPython3_EXECUTABLE={sys.executable}"])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        self.spawn(["cmake", "--build", str(build_dir), "--target", "talus_python", "-j", jobs])
        # The module for this interpreter's ABI: a build folder configured for another Python
        # holds a module this one cannot import.
        built = build_dir / "python" / ("talus" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not built.exists():
            raise RuntimeError(f"setup.py: {built} was not built: is {build_dir} configured "
                               f"for another Python than {sys.executable}?")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        self.copy_file(str(built), str(target))


(ROOT / "build-pip").mkdir(exist_ok=True)
setup(
    version=project_version(),
    ext_modules=[Extension("talus", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' default `build/` is the CMake build folder of scripts/test.sh: keep apart,
    # with the egg-info setuptools writes on the way (build-pip/ is ignored by git).
    options={"build": {"build_base": "build-pip"}, "egg_info": {"egg_base": "build-pip"}},
)
