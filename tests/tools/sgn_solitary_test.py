#!/usr/bin/env python3
"""tools/sgn_solitary.py: the SGN reference that docs/validation.md, Solitary wave, quotes for
the solitary-wave check.

The solver is checked against the SGN equations' own exact solitary wave, which must travel
unchanged at sqrt(g (h + a)); a mistyped term of the equations changes its height or speed.

    /usr/bin/python3 tests/tools/sgn_solitary_test.py
"""
import contextlib
import importlib.util
import io
import math
import pathlib
import unittest

TOOL = pathlib.Path(__file__).resolve().parents[2] / "tools" / "sgn_solitary.py"
spec = importlib.util.spec_from_file_location("sgn_solitary", TOOL)
sgn = importlib.util.module_from_spec(spec)
spec.loader.exec_module(sgn)

H, DEPTH = 0.04, 0.2


class SgnSolitary(unittest.TestCase):
    def test_the_exact_sgn_solitary_wave_keeps_its_height_speed_and_width(self):
        k = sgn.sgn_k(H, DEPTH)
        crests, drift = sgn.evolve(H, DEPTH, k, [0.5, 1.0, 1.5], cells_per_depth=10.0)
        for a, _, width in crests:
            self.assertAlmostEqual(a / H, 1.0, delta=2e-4)
            self.assertAlmostEqual(width / sgn.half_height_duration(H, DEPTH, k), 1.0, delta=1e-3)
        speed = 1.0 / (crests[-1][1] - crests[0][1])
        self.assertAlmostEqual(speed / math.sqrt(sgn.G * (DEPTH + H)), 1.0, delta=2e-4)
        self.assertLess(abs(drift), 1e-12)

    def test_boussinesqs_wave_is_narrower_than_the_sgn_wave_of_its_height(self):
        # k_Boussinesq / k_SGN = sqrt((h + a) / h): the stroke's wave is not the SGN wave.
        self.assertAlmostEqual(sgn.boussinesq_k(H, DEPTH) / sgn.sgn_k(H, DEPTH), math.sqrt(1.2), places=12)
        self.assertAlmostEqual(sgn.goring_stroke(H, DEPTH), 0.20656, places=5)

    def test_goring_wave_loses_height_and_a_lower_wave_loses_less(self):
        gauges = [1.0, 2.0]
        high = sgn.goring_record(H, DEPTH, gauges, cells_per_depth=10.0)
        low = sgn.goring_record(0.25 * H, DEPTH, gauges, cells_per_depth=10.0)
        self.assertGreater(high["lost"], 0.003)
        self.assertLess(high["amplitude_over_height"][0], 1.0)
        # It widens towards the SGN wave of its height, wider than Boussinesq's by sqrt(1 + A / h).
        self.assertGreater(high["width_errors"][-1], high["width_errors"][0])
        self.assertGreaterEqual(low["lost"], 0.0)
        self.assertLess(low["lost"], 0.5 * high["lost"])
        self.assertLess(abs(high["mass_drift"]), 1e-12)

    def test_gauges_inside_the_stroke_are_refused(self):
        with self.assertRaises(ValueError):
            sgn.goring_record(H, DEPTH, [0.05, 1.0], cells_per_depth=10.0)
        with self.assertRaises(ValueError):
            sgn.goring_record(H, DEPTH, [2.0, 1.0], cells_per_depth=10.0)

    def test_command_line_names_the_bad_option(self):
        for argv, option in ((["--height", "0.5"], "--height"), (["--depth", "nan"], "--depth"),
                             (["--cells", "1"], "--cells"), (["--gauges", "2,x"], "--gauges"),
                             (["--gauges", "3,2"], "--gauges")):
            err = io.StringIO()
            with contextlib.redirect_stderr(err), self.assertRaises(SystemExit) as e:
                sgn.main(argv)
            self.assertEqual(e.exception.code, 2, argv)
            self.assertIn(option, err.getvalue().splitlines()[-1], argv)


if __name__ == "__main__":
    unittest.main()
