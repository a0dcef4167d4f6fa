"""CTest's driver of the Python tests: pytest on the files given.

Exits 77 (CTest: skipped) with a message when pytest or numpy is missing; the module itself
must import (PYTHONPATH: the build directory of the module), else the tests fail.
"""
import sys

# Guarded: processes a test spawns (Dask's workers) import this file again as __mp_main__.
if __name__ == "__main__":
    try:
        import numpy  # noqa: F401
        import pytest
    except ImportError as missing:
        print(f"Python tests skipped: {missing.name} is missing "
              "(apt-get install python3-pytest python3-numpy)")
        sys.exit(77)

    sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", *sys.argv[1:]]))
