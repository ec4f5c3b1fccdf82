"""Make the reference fixtures of the adhesim-topography tests with the reference libraries.

Run with a Python that has numpy, x3pio (2.0.0), gwyfile (0.3.0) and surfalize (0.19.2) from PyPI:

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install numpy x3pio==2.0.0 gwyfile==0.3.0 surfalize==0.19.2
    cd crates/adhesim-topography/tests/data && /tmp/venv/bin/python make_fixtures.py

The map is 5 columns (x) by 4 rows (y) with z[row, col] = (col + 10 row) nm - 7 nm, so a
transposed or flipped read is caught; x spacing 0.5 um, y spacing 0.25 um. The Rust tests
(tests/integration/reference_files.rs) check the same numbers.
"""
import numpy as np
import x3pio
import gwyfile
from gwyfile.objects import GwyContainer, GwyDataField, GwySIUnit
import surfalize

ny, nx = 4, 5
dx, dy = 0.5e-6, 0.25e-6
rows, cols = np.mgrid[0:ny, 0:nx]
z = ((cols + 10.0 * rows) - 7.0) * 1e-9

# x3p, float64 heights (x3pio default), and int16 heights with one invalid point.
x3pio.write("reference_float64.x3p", z, x_scale=dx, y_scale=dy)
z_missing = z.copy()
z_missing[2, 3] = np.nan
x3pio.write("reference_int16_invalid.x3p", z_missing, x_scale=dx, y_scale=dy,
            z_type=x3pio.DataType.INT16)

# Gwyddion .gwy: channel 0 "Topography" (m), channel 1 "Phase" (deg), a mask on channel 0.
container = GwyContainer()
container["/0/data"] = GwyDataField(z, xreal=nx * dx, yreal=ny * dy,
                                    si_unit_xy=GwySIUnit(unitstr="m"),
                                    si_unit_z=GwySIUnit(unitstr="m"))
container["/0/data/title"] = "Topography"
mask = np.zeros((ny, nx))
mask[1, 2] = 1.0
container["/0/mask"] = GwyDataField(mask, xreal=nx * dx, yreal=ny * dy)
container["/1/data"] = GwyDataField(np.full((ny, nx), 3.0), xreal=nx * dx, yreal=ny * dy,
                                    si_unit_xy=GwySIUnit(unitstr="m"),
                                    si_unit_z=GwySIUnit(unitstr="deg"))
container["/1/data/title"] = "Phase"
container.tofile("reference.gwy")

# Digital Surf .sur through surfalize (int32 heights in um, with a z offset).
surfalize.Surface(z * 1e6, dx * 1e6, dy * 1e6).save("reference.sur")
