"""Build glue for `pip install --no-build-isolation .`: setuptools drives the project's CMake
build of the extension oscidrum._core (target oscidrum_python) and packages it with the
pure-Python sources of python/oscidrum. Only Debian's packages are needed (cmake, a C++20
compiler, libboost-dev, pybind11-dev, python3-dev, python3-setuptools, python3-wheel); no PyPI.

Environment: CMAKE_BUILD_PARALLEL_LEVEL (jobs, default: all cores), OSCIDRUM_CMAKE_ARGS (extra
configure arguments, space separated).
"""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def version():
    text = (ROOT / "include" / "oscidrum" / "version.hpp").read_text()
    return re.search(r'version\s*=\s*"([^"]+)"', text).group(1)


class CMakeExtension(Extension):
    """An extension whose sources CMake knows (python/CMakeLists.txt)."""

    def __init__(self, name, target):
        super().__init__(name, sources=[])
        self.target = target


class CMakeBuild(build_ext):
    """Configure the project with only the Python module enabled, build its target and copy the
    extension to where setuptools expects it."""

    def build_extension(self, ext):
        destination = Path(self.get_ext_fullpath(ext.name)).resolve()
        build_dir = Path(self.build_temp).resolve() / "cmake"
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build_dir),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DOSCIDRUM_BUILD_PYTHON=ON",
            "-DOSCIDRUM_BUILD_TESTS=OFF",
            "-DOSCIDRUM_BUILD_CLI=OFF",
            "-DOSCIDRUM_BUILD_BENCH=OFF",
            f"-DPython3_EXECUTABLE={sys.executable}",
        ]
        if shutil.which("ninja") and not (build_dir / "CMakeCache.txt").exists():
            configure += ["-G", "Ninja"]
        configure += os.environ.get("OSCIDRUM_CMAKE_ARGS", "").split()
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", ext.target,
                        "--parallel", jobs], check=True)
        built = sorted((build_dir / "python" / "oscidrum").glob("_core*"))
        if not built:
            raise RuntimeError(f"CMake built no _core module in {build_dir}/python/oscidrum")
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], destination)


setup(
    version=version(),
    ext_modules=[CMakeExtension("oscidrum._core", "oscidrum_python")],
    cmdclass={"build_ext": CMakeBuild},
    # build/ is the CMake build tree of scripts/build.sh: keep setuptools' files apart.
    options={"build": {"build_base": "build-pip"}},
    package_data={"oscidrum": ["*.pyi", "py.typed"]},
    zip_safe=False,
)
