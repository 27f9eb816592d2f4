"""Runs one file of the prtkit Python tests under pytest, for CTest (tests/python/CMakeLists.txt).

Exit 77 (CTest: skipped) when pytest, numpy or the module is missing, or when every test of the
file skipped (conftest.py), so a machine without them never reports these tests as passed.
"""

import sys

try:
    import pytest
except ImportError as e:
    print(f"skipped: pytest is not installed ({e}); Debian: python3-pytest")
    sys.exit(77)

for module, package in (("numpy", "python3-numpy"), ("prtkit", "the module: build it")):
    try:
        __import__(module)
    except ImportError as e:
        print(f"skipped: {module} is not importable ({e}); {package}")
        sys.exit(77)

sys.exit(pytest.main(["-p", "no:cacheprovider", "-q", "-rs", *sys.argv[1:]]))
