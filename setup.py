"""`pip install --no-build-isolation .`: the Python module (docs/python.md) built by CMake from this
tree, with Debian's pybind11, NumPy and compilers; nothing is downloaded.

The module is configured and built in build-pip/ (or in the CMake build folder FRESNEL_BUILD_DIR
names, e.g. build/, to reuse what `make` built), with FRESNEL_JOBS parallel jobs (default: the
cores); the package is python/fresnel with that module in it.
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
VERSION = re.search(r"project\(fresnel VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text()).group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = pathlib.Path(os.environ.get("FRESNEL_BUILD_DIR", ROOT / "build-pip")).resolve()
        jobs = os.environ.get("FRESNEL_JOBS", str(os.cpu_count() or 1))
        if not (build / "CMakeCache.txt").exists():
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), *generator, "-DCMAKE_BUILD_TYPE=Release",
                            "-DFRESNEL_TESTS=OFF", "-DFRESNEL_BENCH=OFF", "-DFRESNEL_VIEWER=OFF",
                            f"-DPython_EXECUTABLE={sys.executable}"], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "fresnel_python", "-j", jobs], check=True)
        built = sorted((build / "python" / "fresnel").glob("_fresnel*.so"))
        if not built:
            raise RuntimeError(f"CMake built no module in {build}/python/fresnel")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)


setup(
    name="fresnel",
    version=VERSION,
    description="Physically based rendering of glTF, OBJ and scene files: GPU rasteriser, CPU path tracer, NumPy images",
    packages=["fresnel"],
    package_dir={"": "python"},
    package_data={"fresnel": ["__init__.pyi", "py.typed"]},
    ext_modules=[CMakeExtension("fresnel._fresnel")],
    cmdclass={"build_ext": CMakeBuild},
    install_requires=["numpy"],
    python_requires=">=3.9",
    zip_safe=False,
)
