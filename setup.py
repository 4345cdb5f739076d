"""Builds the `spinfold` package with the project's own CMake (target spinfold_python) and copies
what it assembles in <build>/python/spinfold into the wheel. Used by
`pip install --no-build-isolation .`; the CMake build alone gives the same package in build/python."""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

ROOT = Path(__file__).resolve().parent


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(spinfold VERSION ([0-9.]+)", text).group(1)


class CMakeBuildPy(build_py):
    """The pure-Python files and the compiled module, both from the CMake build."""

    def run(self):
        build_dir = Path(os.environ.get("SPINFOLD_PIP_BUILD_DIR", ROOT / "build-pip"))
        configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                     "-DSPINFOLD_TESTS=OFF", f"-DPython_EXECUTABLE={sys.executable}"]
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        subprocess.check_call(configure)
        subprocess.check_call(["cmake", "--build", str(build_dir), "--target", "spinfold_python",
                               "-j", str(os.cpu_count() or 1)])
        target = Path(self.build_lib) / "spinfold"
        target.mkdir(parents=True, exist_ok=True)
        for file in (build_dir / "python" / "spinfold").iterdir():
            if file.is_file():
                shutil.copy2(file, target / file.name)


class BinaryDistribution(Distribution):
    def has_ext_modules(self):  # a platform wheel: the package holds a compiled module
        return True


setup(version=project_version(), cmdclass={"build_py": CMakeBuildPy}, distclass=BinaryDistribution)
