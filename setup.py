# SPDX-License-Identifier: GPL-3.0-or-later
"""setuptools front end of the CMake build (pyproject.toml declares setuptools as the backend).

build_ext configures the project with the options below in build-pip/ (CONSTRICT_CMAKE_BUILD_DIR
overrides), builds the bindings and the CLI, and puts constrict/_core.<abi>.so and
constrict/bin/constrict into the wheel next to the pure-Python files of python/constrict/.
Offline: only Debian packages (cmake, pybind11-dev, python3-dev, python3-numpy,
python3-setuptools, python3-wheel; scripts/install-deps.sh). CONSTRICT_JOBS sets the parallel
build level (default: all cores).
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
CMAKE_OPTIONS = [
    "-DCMAKE_BUILD_TYPE=Release",
    "-DCONSTRICT_BUILD_TESTS=OFF",
    "-DCONSTRICT_BUILD_BENCH=OFF",
    "-DCONSTRICT_BUILD_CLI=ON",  # python3 -m constrict runs it
    "-DCONSTRICT_BUILD_PYTHON=ON",
]


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    return re.search(r"project\(constrict VERSION ([0-9.]+)", text).group(1)


class CMakeExtension(Extension):
    """The extension CMake builds (no sources for setuptools to compile)."""

    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def run(self):
        for ext in self.extensions:
            self.build_cmake(ext)

    def build_cmake(self, ext):
        cmake = shutil.which("cmake")
        if cmake is None:
            sys.exit("constrict: cmake not found (Debian: apt-get install cmake, or scripts/install-deps.sh)")
        build_dir = Path(os.environ.get("CONSTRICT_CMAKE_BUILD_DIR", ROOT / "build-pip"))
        configure = [cmake, "-S", str(ROOT), "-B", str(build_dir), *CMAKE_OPTIONS,
                     f"-DPython3_EXECUTABLE={sys.executable}"]
        if shutil.which("ccache"):
            configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        jobs = os.environ.get("CONSTRICT_JOBS", str(os.cpu_count() or 1))
        subprocess.run(configure, check=True)
        subprocess.run([cmake, "--build", str(build_dir), "-j", jobs, "--target", "constrict_python",
                        "constrict_python_cli"], check=True)
        stage = build_dir / "python" / "constrict"
        core = next(stage.glob("_core*.so"), None)
        if core is None:
            sys.exit(f"constrict: the build made no {stage}/_core*.so")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(core, target)
        cli = (stage / "bin" / "constrict").resolve()  # the staged link points at build/cli
        exe = target.parent / "bin" / "constrict"
        exe.parent.mkdir(exist_ok=True)
        shutil.copyfile(cli, exe)
        os.chmod(exe, 0o755)


(ROOT / "build-pip").mkdir(exist_ok=True)  # egg_base must exist
setup(
    version=project_version(),
    packages=["constrict"],
    package_dir={"": "python"},
    ext_modules=[CMakeExtension("constrict._core")],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
    # setuptools' own build tree next to CMake's, both ignored by git (/build*).
    options={"build": {"build_base": "build-pip/setuptools"},
             "egg_info": {"egg_base": "build-pip"}},
)
