"""`pip install .`: the `claspplan` Python package, built by the project's own CMake.

The module `claspplan._claspplan` is the CMake target `claspplan_python` (examples/python), built in
build/pip and copied into the wheel beside the package's Python files. The C++ libraries it links
(ViSP, PCL, FCL, OctoMap, urdfdom, Assimp, CGAL, OpenCV, ...) must be installed first: on Debian 12,
install-deps.sh; elsewhere, the same libraries from the system's packages (docs/python.md).
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    """A module CMake builds: no sources for setuptools to compile."""

    def __init__(self, name: str) -> None:
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        build = Path(os.environ.get("CLASPPLAN_PIP_BUILD_DIR", ROOT / "build" / "pip")).resolve()
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DCLASPPLAN_BUILD_TESTS=OFF",
            # The interpreter pip runs: the module is built for its version and headers.
            f"-DPython_EXECUTABLE={sys.executable}",
        ]
        try:  # pybind11 from pip (an isolated build) rather than the system's
            import pybind11

            configure.append(f"-Dpybind11_DIR={pybind11.get_cmake_dir()}")
        except ImportError:
            pass
        subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(
            ["cmake", "--build", str(build), "--target", "claspplan_python", "-j", jobs],
            check=True,
        )
        built = sorted((build / "python" / "claspplan").glob("_claspplan*.so"))
        if not built:
            sys.exit(f"claspplan: CMake built no module in {build / 'python' / 'claspplan'}: "
                     "is pybind11 installed (Debian: pybind11-dev)?")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], target)


setup(
    package_dir={"": "examples/python/src"},
    packages=["claspplan"],
    package_data={"claspplan": ["_claspplan.pyi", "py.typed"]},
    ext_modules=[CMakeExtension("claspplan._claspplan")],
    cmdclass={"build_ext": CMakeBuild},
)
