#!/usr/bin/env python3
"""tools/packing_density.py: the lattice sums that docs/validation.md, Lattice constants, quotes.

The surface row's asymmetry is checked against the closed form that tests/bake/kernel_test.cpp
pins for the solver's latticeConstants().flatSurfaceAsymmetry (re = 2.1 l0), so the tool and the
solver measure the same thing.

    /usr/bin/python3 tests/tools/packing_density_test.py
"""
import importlib.util
import math
import pathlib
import unittest

TOOL = pathlib.Path(__file__).resolve().parents[2] / "tools" / "packing_density.py"
spec = importlib.util.spec_from_file_location("packing_density", TOOL)
pd = importlib.util.module_from_spec(spec)
spec.loader.exec_module(pd)


class PackingDensity(unittest.TestCase):
    def test_surface_row_asymmetry_matches_the_solvers_closed_form(self):
        re = 2.1
        w1, w2, w4 = (pd.mps(r, re) for r in (1.0, math.sqrt(2.0), 2.0))
        n0 = 4.0 * (w1 + w2 + w4)  # shells at 1, sqrt 2, 2 with 4 sites each
        rows = pd.surface_rows(re, pd.mps)
        self.assertAlmostEqual(rows[0][1], (w1 + 2.0 * w2 + 2.0 * w4) / n0, places=12)
        # Missing above it: (0, 1), (+-1, 1) and (0, 2); the asymmetry weighs (0, 2) twice.
        self.assertAlmostEqual(rows[0][0], (n0 - (w1 + 2.0 * w2 + w4)) / n0, places=12)

    def test_rows_beyond_the_radius_are_full(self):
        for re in (2.1, 2.8):
            n, f = pd.surface_rows(re, pd.mps)[2]
            self.assertAlmostEqual(n, 1.0, places=12)
            self.assertAlmostEqual(f, 0.0, places=12)
        # 2.8 l0 reaches two rows up: the second row misses (0, 2), (+-1, 2).
        re = 2.8
        n0 = pd.density([(i, j) for i in range(-8, 9) for j in range(-8, 9)], re, pd.mps)
        missing = pd.mps(2.0, re) + 2.0 * pd.mps(math.sqrt(5.0), re)
        self.assertAlmostEqual(pd.surface_rows(re, pd.mps)[1][0], 1.0 - missing / n0, places=12)

    def test_area_ratio_is_one_for_a_square_lattice_density(self):
        # A hexagonal packing of unit area per particle against the square lattice: 2.8 l0
        # needs 1.6 % less area (the still tank's volume loss), 3.0 l0 the same area.
        self.assertAlmostEqual(pd.area_ratio(2.8, pd.mps), 0.9842, places=4)
        self.assertAlmostEqual(pd.area_ratio(3.0, pd.mps), 1.0000, places=4)


if __name__ == "__main__":
    unittest.main()
