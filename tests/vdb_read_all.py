"""Reads a .vdb whole with pyopenvdb.readAll and prints one line per grid: name, type, active
voxels. Exits non-zero when the file cannot be read (used by tests/test_vdb_python.cpp)."""
import sys

import pyopenvdb

grids, _ = pyopenvdb.readAll(sys.argv[1])
for g in grids:
    print(g.name, type(g).__name__, g.activeVoxelCount())
