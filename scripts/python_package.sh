#!/usr/bin/env bash
# The Python package as a user installs it: builds a wheel with pip (pyproject.toml: setuptools
# running the project's CMake, library and module only), installs it into a fresh venv that
# sees Debian's packages (numpy, pytest, open3d) and runs python/tests against that
# installation, not the build tree; checks the metadata, that `pip install .` works too, and
# that `pip uninstall` leaves nothing behind.
#
#   bash scripts/python_package.sh
#
# Environment: PYTHON (default /usr/bin/python3: Debian's numpy and pybind11 belong to it),
# JOBS (parallel jobs, default 2), BUILD_DIR (a CMake build with the tools, default build:
# when it has the pcl_ncut_seg tool, the tests that compare with the tool run too).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
PYTHON="${PYTHON:-/usr/bin/python3}"
BUILD_DIR="${BUILD_DIR:-build}"
export CMAKE_BUILD_PARALLEL_LEVEL="${JOBS:-2}"
export PIP_NO_INPUT=1 PIP_DISABLE_PIP_VERSION_CHECK=1

WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
say() { echo "python_package: $*"; }
fail() { echo "python_package: FAILED: $*" >&2; exit 1; }

VERSION="$(sed -n 's/^project(pcl_ncut_seg VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)"
[ -n "$VERSION" ] || fail "no version in CMakeLists.txt"

say "building the wheel"
"$PYTHON" -m venv --system-site-packages "$WORK/build-venv"
"$WORK/build-venv/bin/pip" wheel --no-build-isolation --no-deps -w "$WORK/dist" . \
  >"$WORK/wheel.log" 2>&1 || { cat "$WORK/wheel.log"; fail "pip wheel"; }
WHEEL="$(ls "$WORK"/dist/pcl_ncut_seg-"$VERSION"-*.whl)"
say "built $(basename "$WHEEL")"

say "installing it into a fresh venv"
VENV="$WORK/venv"
"$PYTHON" -m venv --system-site-packages "$VENV"
"$VENV/bin/pip" install --no-index "$WHEEL"   # numpy: Debian's, through the system site
cd "$WORK" # away from the sources: the package is the installed one
SITE="$("$VENV/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
"$VENV/bin/python" - "$SITE" "$VERSION" <<'PY'
import importlib.metadata as md
import os
import sys

import pcl_ncut_seg

site, version = sys.argv[1:]
assert pcl_ncut_seg.__file__.startswith(site + os.sep), pcl_ncut_seg.__file__
meta = md.metadata("pcl_ncut_seg")
assert meta["Version"] == version == pcl_ncut_seg.__version__, (meta["Version"], version)
assert meta["License"] == "BSD-3-Clause" and meta["Requires-Python"], meta
assert "numpy" in (md.requires("pcl_ncut_seg") or []), md.requires("pcl_ncut_seg")
assert "# pcl_ncut_seg" in meta["Description"] and meta["Summary"], "no long description"
assert "License :: OSI Approved :: BSD License" in meta.get_all("Classifier")
for name in ("py.typed", "__init__.pyi"):
    assert os.path.isfile(os.path.join(os.path.dirname(pcl_ncut_seg.__file__), name)), name
print(f"python_package: pcl_ncut_seg {version} imports from {os.path.dirname(pcl_ncut_seg.__file__)}")
PY

say "running python/tests against the installed package"
TOOL_ENV=()
if [ -x "$ROOT/$BUILD_DIR/tools/pcl_ncut_seg" ]; then
  TOOL_ENV=("PCL_NCUT_SEG_TOOL=$ROOT/$BUILD_DIR/tools/pcl_ncut_seg")
fi
env "${TOOL_ENV[@]}" PCL_NCUT_SEG_SOURCE_DIR="$ROOT" \
  "$VENV/bin/python" -m pytest -q -p no:cacheprovider "$ROOT/python/tests"

say "pip uninstall"
"$VENV/bin/pip" uninstall -y pcl_ncut_seg
left="$(find "$SITE" -maxdepth 1 -iname 'pcl_ncut_seg*')"
[ -z "$left" ] || fail "left behind by pip uninstall: $left"
if "$VENV/bin/python" -c 'import pcl_ncut_seg' 2>/dev/null; then
  fail "pcl_ncut_seg still imports after pip uninstall"
fi

say "pip install . into another venv"
cd "$ROOT"
"$PYTHON" -m venv --system-site-packages "$WORK/venv2"
"$WORK/venv2/bin/pip" install --no-build-isolation --no-index . >"$WORK/install.log" 2>&1 \
  || { cat "$WORK/install.log"; fail "pip install ."; }
(cd "$WORK" && "$WORK/venv2/bin/python" -c 'import numpy, pcl_ncut_seg
labels = pcl_ncut_seg.segment(numpy.random.default_rng(1).normal(size=(500, 3)), segments=2)
assert labels.shape == (500,) and labels.max() == 2, labels')

say "all passed"
