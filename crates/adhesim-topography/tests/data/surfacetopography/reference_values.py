"""Prints SurfaceTopography's values for the fixtures of this folder, as
tests/integration/surfacetopography.rs holds them: grid, physical size (m), rms height (Sq
over the valid points, m), rms gradient (finite differences, rms_gradient), rms mean curvature
(rms_curvature_from_area) and, for maps with invalid points, the same after
SurfaceTopography's harmonic filling (interpolate_undefined_data). Run with SurfaceTopography
1.27.1 installed:

    python reference_values.py

Compressed fixtures (*.gz) are decompressed into a temporary folder first.
"""
import gzip
import os
import shutil
import tempfile

import numpy as np
from SurfaceTopography import open_topography

# "Âµm": SurfaceTopography 1.27.1 decodes the Latin-1 "µm" of ../reference.sur so.
METRES = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "Âµm": 1e-6, "nm": 1e-9, None: 1.0}
# Files that record no size or unit: what the test gives adhesim as well.
GIVEN = {"matrix-5.txt": dict(physical_sizes=(1.0, 2.0)), "example-2d.npy": dict(physical_sizes=(3.0, 4.0))}
FILES = ["x3p-2.x3p", "sur-2.sur.gz", "sur-3.sur.gz", "matrix-3.txt.gz", "matrix-4.txt.gz",
         "gwyddion-export-english.txt", "gwyddion-export-german.txt", "matrix-5.txt", "matrix-6.txt",
         "txt_example.txt", "xyz-1.txt", "xyz-2.txt", "example-2d.npy",
         # adhesim's own fixtures made by gwyfile and surfalize (../README.md)
         "../reference.gwy", "../reference.sur"]


def values(path, name):
    topography = open_topography(path).topography(**GIVEN.get(name, {}))
    scale = METRES[topography.unit]
    heights = topography.heights()
    invalid = int(np.ma.getmaskarray(heights).sum()) if np.ma.isMaskedArray(heights) else 0
    nx, ny = topography.nb_grid_pts
    sx, sy = topography.physical_sizes
    row = dict(file=name, nx=nx, ny=ny, sx=sx * scale, sy=sy * scale, unit=topography.unit, invalid=invalid,
               rms_height=topography.rms_height_from_area() * scale)
    filled = topography.interpolate_undefined_data() if invalid else topography
    row["rms_slope"] = filled.rms_gradient()
    row["rms_curvature"] = filled.rms_curvature_from_area() / scale
    if invalid:
        row["rms_slope_masked"] = topography.rms_gradient()
    return row


with tempfile.TemporaryDirectory() as folder:
    here = os.path.dirname(os.path.abspath(__file__))
    for name in FILES:
        path = os.path.join(here, name)
        if name.endswith(".gz"):
            name = name[:-3]
            with gzip.open(path) as source, open(os.path.join(folder, name), "wb") as target:
                shutil.copyfileobj(source, target)
            path = os.path.join(folder, name)
        print({k: (float(v) if isinstance(v, np.floating) else v) for k, v in values(path, name).items()})
