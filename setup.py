"""pip's build of the package pcl_ncut_seg (see pyproject.toml for its metadata): the project's
CMake builds the library and the module (target pcl_ncut_seg_python_package: no tests, tools,
benchmarks or ROS), and its package directory gives the wheel the compiled _pcl_ncut_seg and the
stub it wrote from the parameter table. The version is CMakeLists.txt's project() VERSION.

Environment: CMAKE_BUILD_PARALLEL_LEVEL (jobs, default 2), CMAKE_ARGS (more -D options);
ccache is used when it is on PATH.
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
TARGET = "pcl_ncut_seg_python_package"


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    match = re.search(r"project\(\s*pcl_ncut_seg\s+VERSION\s+([0-9][0-9.]*)", text)
    if not match:
        sys.exit("setup.py: no project(pcl_ncut_seg VERSION ...) in CMakeLists.txt")
    return match.group(1)


class CMakeBuild(build_ext):
    """Builds the extension with the project's CMake instead of setuptools' compiler."""

    def build_extension(self, ext):
        cmake = shutil.which("cmake")
        if not cmake:
            raise RuntimeError("pcl_ncut_seg needs CMake: apt-get install cmake "
                               "(or bash scripts/install_deps.sh)")
        build_dir = Path(self.build_temp).resolve() / "cmake"
        configure = [
            cmake, "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython3_EXECUTABLE={sys.executable}",
            "-DPCL_NCUT_SEG_BUILD_PYTHON=ON", "-DPCL_NCUT_SEG_BUILD_TESTS=OFF",
            "-DPCL_NCUT_SEG_BUILD_TOOLS=OFF", "-DPCL_NCUT_SEG_BUILD_BENCH=OFF",
            "-DPCL_NCUT_SEG_BUILD_ROS=OFF", "-DPCL_NCUT_SEG_BUILD_FUZZERS=OFF",
        ]
        try:  # pybind11's CMake files: Debian's python3-pybind11, or the build requirement's
            import pybind11
            configure.append(f"-Dpybind11_DIR={pybind11.get_cmake_dir()}")
        except ImportError:
            pass
        env = dict(os.environ)
        if shutil.which("ccache"):
            configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
            env.setdefault("CCACHE_BASEDIR", str(ROOT))  # hits across clones of the repo
        configure += shlex.split(env.get("CMAKE_ARGS", ""))
        subprocess.run(configure, check=True, env=env)
        if not (build_dir / "python" / "CMakeFiles" / f"{TARGET}.dir").is_dir():
            raise RuntimeError("CMake did not set up the Python module: it needs pybind11 and "
                               "Python's headers (apt-get install python3-pybind11 python3-dev; "
                               "see the CMake output above)")
        jobs = env.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.run([cmake, "--build", str(build_dir), "--target", TARGET, "-j", jobs],
                       check=True, env=env)

        package = build_dir / "python" / "pcl_ncut_seg"
        built = sorted(package.glob("_pcl_ncut_seg*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one _pcl_ncut_seg module in {package}, found {built}")
        destination = Path(self.get_ext_fullpath(ext.name))
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], destination)
        shutil.copyfile(package / "__init__.pyi", destination.parent / "__init__.pyi")


setup(
    version=project_version(),
    ext_modules=[Extension("pcl_ncut_seg._pcl_ncut_seg", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own build directory: not CMake's build/ of scripts/test.sh
    options={"build": {"build_base": "build-python"}},
)
