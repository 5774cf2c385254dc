"""Builds the _mrsv extension with the project's CMake for pip (see pyproject.toml).

setuptools cannot compile the C++ itself (the libraries' options and sources
live in CMakeLists.txt), so the build_ext step configures a CMake tree under
setuptools' build directory, builds the one target _mrsv and copies the
module where setuptools packs it. Needs the Debian packages of tools/setup.sh.
"""
import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        tree = pathlib.Path(self.build_temp).resolve() / "cmake"
        configure = ["cmake", "-S", str(ROOT), "-B", str(tree), "-DCMAKE_BUILD_TYPE=Release",
                     "-DMRSV_PYTHON=ON", f"-DPYTHON_EXECUTABLE={sys.executable}"]
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        subprocess.run(configure, check=True)
        jobs = os.environ.get("MRSV_BUILD_JOBS", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", str(tree), "--target", "_mrsv", "-j", jobs], check=True)
        built = next((tree / "python" / "mrsv").glob("_mrsv*" + self._suffix()))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)

    @staticmethod
    def _suffix():
        import sysconfig

        return sysconfig.get_config_var("EXT_SUFFIX")


setup(
    ext_modules=[Extension("mrsv._mrsv", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # Not build/: that is the project's own CMake tree (tools/setup.sh).
    options={"build": {"build_base": "build-pip"}},
)
