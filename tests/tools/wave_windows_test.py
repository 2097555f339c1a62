#!/usr/bin/env python3
"""tools/wave_windows.py: the runs file, the figures per window and the table of
docs/validation.md, Progressive waves, on made-up reports (the fit itself is swell-validate's,
tested in tests/bake/validation/regular_wave_test.cpp).

    /usr/bin/python3 tests/tools/wave_windows_test.py
"""
import importlib.util
import json
import math
import pathlib
import stat
import sys
import tempfile
import unittest

TOOL = pathlib.Path(__file__).resolve().parents[2] / "tools" / "wave_windows.py"
# The build's bin folder (ctest passes it): one case runs swell-validate on a made-up record.
BIN = pathlib.Path(sys.argv.pop(1)) if len(sys.argv) > 1 else TOOL.parents[1] / "build" / "bin"
spec = importlib.util.spec_from_file_location("wave_windows", TOOL)
ww = importlib.util.module_from_spec(spec)
spec.loader.exec_module(ww)


def report(own, common, gauges=(0.5, 1.0, 1.5)):
    return {"gauges": list(gauges), "height_errors": own, "height_errors_common_window": common,
            "scene": "progressive_wave"}


class WaveWindows(unittest.TestCase):
    def test_runs_file_gives_group_dir_scene_and_sets(self):
        runs = ww.parse_runs("# seeds\nmain_j /k/s1 scenes/w.json seed=1 geometry.jitter=1e-6\n\n"
                             "main_u /k/u scenes/w.json  # as shipped\n")
        self.assertEqual(len(runs), 2)
        self.assertEqual(runs[0], {"group": "main_j", "dir": "/k/s1", "scene": "scenes/w.json",
                                   "sets": ["seed=1", "geometry.jitter=1e-6"]})
        self.assertEqual(runs[1]["sets"], [])

    def test_a_bad_line_names_its_number(self):
        for text in ("main_j /k/s1\n", "a b c seed\n"):
            with self.assertRaisesRegex(ValueError, "line 1"):
                ww.parse_runs(text)

    def test_figures_read_the_nearest_and_farthest_gauge_in_the_windows_key(self):
        # Gauges out of order: the nearest is x = 0.5 (index 1), the farthest x = 1.5 (index 0).
        r = report([-0.02, 0.01, 0.04], [0.1, -0.03, 0.0], gauges=(1.5, 0.5, 1.0))
        own = ww.figures(r, "height_errors")
        self.assertAlmostEqual(own["first"], 0.01)
        self.assertAlmostEqual(own["worst"], 0.04)
        self.assertAlmostEqual(own["lost"], 1.0 - 0.98 / 1.01)
        common = ww.figures(r, "height_errors_common_window")
        self.assertAlmostEqual(common["first"], -0.03)
        self.assertAlmostEqual(common["lost"], 1.0 - 1.1 / 0.97)

    def test_the_fitted_loss_reads_the_line_through_all_gauges(self):
        # A wave losing 2 % per metre at every gauge: the fit and the ratio agree.
        x = (0.5, 1.0, 1.5, 2.0)
        decaying = [0.98 ** (g - 0.5) - 1.0 for g in x]
        f = ww.figures(report(decaying, decaying, gauges=x), "height_errors")
        self.assertAlmostEqual(f["lost_fit"], 1.0 - 0.98 ** 1.5)
        self.assertAlmostEqual(f["lost"], 1.0 - 0.98 ** 1.5)
        # Undamped but the last gauge 6 % low: the line through four gauges takes
        # (x_4 - mean) / sum (x - mean)^2 x span = 0.75 x 1.5 / 1.25 = 0.9 of it, the ratio all.
        low = [0.0, 0.0, 0.0, -0.06]
        f = ww.figures(report(low, low, gauges=x), "height_errors")
        self.assertAlmostEqual(f["lost_fit"], 1.0 - 0.94 ** 0.9)
        self.assertAlmostEqual(f["lost"], 0.06)

    def test_table_gives_mean_sd_and_range_per_group_and_window(self):
        groups = {"main_j": [report([0.01, 0.0, 0.0], [0.02, 0.0, 0.0]),
                             report([-0.03, 0.0, 0.0], [0.06, 0.0, 0.0])],
                  "main_u": [report([-0.011, 0.0, 0.0], [-0.012, 0.0, 0.0])]}
        rows = ww.table(groups).splitlines()
        self.assertEqual(len(rows), 2 + 4)
        self.assertIn("| main_j | own | 2 | -1.0 +- 2.8 % (-3.0 to +1.0) |", rows[2])
        self.assertIn("| main_j | common | 2 | +4.0 +- 2.8 % (+2.0 to +6.0) |", rows[3])
        self.assertIn("| main_u | own | 1 | -1.1 % |", rows[4])
        # Reports without linear theory's record read "-" in the last two columns, as the
        # common window always does.
        self.assertTrue(all(r.endswith("| - | - |") for r in rows[2:]))

    def test_the_loss_against_linear_theory_is_read_in_the_own_window_only(self):
        a = dict(report([0.0, 0.0, 0.0], [0.0, 0.0, 0.0]), decay_total_fit_against_theory_record=0.02,
                 decay_total_fit_against_theory_record_standard_error=0.015)
        b = dict(report([0.0, 0.0, 0.0], [0.0, 0.0, 0.0]), decay_total_fit_against_theory_record=0.06,
                 decay_total_fit_against_theory_record_standard_error=0.025)
        rows = ww.table({"deep_j": [a, b]}).splitlines()
        self.assertTrue(rows[2].startswith("| deep_j | own |"))
        # The loss's spread, then the records' own standard errors: their mean and range.
        self.assertTrue(rows[2].endswith("| +4.0 +- 2.8 % (+2.0 to +6.0) | 2.0 % (1.5 to 2.5) |"))
        self.assertTrue(rows[3].startswith("| deep_j | common |"))
        self.assertTrue(rows[3].endswith("| - | - |"))
        self.assertTrue(ww.table({"one": [a]}).splitlines()[2].endswith("| +2.0 % | 1.5 % |"))

    def test_one_period_at_a_time_reads_each_periods_height(self):
        # A 1 s wave of height 0.02 m until t = 3 s, then 0.03 m, sampled every 10 ms; a sine, so
        # the sample at t = 3 s, which both periods next to it fit, is 0 either way.
        with tempfile.TemporaryDirectory() as d:
            path = pathlib.Path(d) / "w.probes.csv"
            lines = ["time,front_x,gauge_0.5,gauge_1.13"]
            for i in range(0, 601):
                t = 0.01 * i
                H = 0.02 if t < 3.0 else 0.03
                lines.append("%g,nan,%.9g,0" % (t, 0.5 * H * math.sin(2 * math.pi * (t - 1.0)) + 0.001))
            path.write_text("\n".join(lines) + "\n")
            t, eta = ww.read_gauge(path, 0.5)
            self.assertEqual(len(t), 601)
            got = ww.per_period(t, eta, 1.0, 1.0, 5.5, 0.025)
            self.assertEqual(len(got), 4)  # 1-2, 2-3, 3-4, 4-5 s; 5-6 s ends after 5.5 s
            for value, want in zip(got, (-0.2, -0.2, 0.2, 0.2)):
                self.assertAlmostEqual(value, want, places=6)
            with self.assertRaisesRegex(ValueError, "no column gauge_0.8"):
                ww.read_gauge(path, 0.8)
            # The table: the record's own window of the gauge at 0.5 m, its period from the run.
            rep = dict(report([0.0, 0.0], [0.0, 0.0], gauges=(0.5, 1.13)),
                       gauge_windows=[[1.0, 5.5], [2.0, 5.5]], height_theory=0.025)
            run = {"group": "g", "dir": d, "scene": "w.json", "sets": []}
            rows = ww.period_table({"g": [rep]}, {"g": [run]}, 0.5, period=lambda r: 1.0).splitlines()
            self.assertEqual(rows[0], "| group | records | period 1 | period 2 | period 3 | period 4 |")
            self.assertEqual(rows[2], "| g | 1 | -20.0 % | -20.0 % | +20.0 % | +20.0 % |")

    def test_a_records_own_piston_period_overrides_the_scenes(self):
        run = {"group": "g", "dir": "d", "scene": "scenes/progressive_wave.json", "sets": []}
        scene = json.loads((ww.ROOT / run["scene"]).read_text())
        self.assertEqual(ww.piston_period(run), scene["piston"]["period"])
        self.assertEqual(ww.piston_period(dict(run, sets=["seed=2", "piston.period=0.8"])), 0.8)

    def test_a_failing_refit_is_an_error_naming_the_command(self):
        with tempfile.TemporaryDirectory() as d:
            fake = pathlib.Path(d) / "fake-validate"
            fake.write_text("#!/bin/sh\necho 'the record ends at t = 4.98 s' >&2\nexit 1\n")
            fake.chmod(fake.stat().st_mode | stat.S_IEXEC)
            run = {"group": "g", "dir": d, "scene": "scenes/progressive_wave.json", "sets": ["seed=2"]}
            with self.assertRaisesRegex(RuntimeError, "--set seed=2 regular-wave .*ends at t = 4.98"):
                ww.refit(str(fake), run)
            runs = pathlib.Path(d) / "runs.txt"
            runs.write_text("g %s scenes/progressive_wave.json\n" % d)
            self.assertEqual(ww.main([str(runs), "--validate", str(fake)]), 1)

    def test_swell_validate_and_the_tool_read_the_same_loss_along_the_line(self):
        # A made-up record of scenes/progressive_wave.json's gauges: Biesel's wave losing 1 % per
        # metre, its last gauge 6 % lower still. swell-validate --probes fits it (nothing baked);
        # its decay_total_fit, the tool's lost_fit and the line through the made-up heights
        # agree, and the endpoint ratio reads more.
        validate = BIN / "swell-validate"
        if not validate.exists():
            self.skipTest("no %s (build first)" % validate)
        scene = json.loads((ww.ROOT / "scenes/progressive_wave.json").read_text())
        x = scene["output"]["gauges"]
        T, H, L = scene["piston"]["period"], 0.0294, 1.26
        amp = [H * 0.99 ** g * (0.94 if g == max(x) else 1.0) for g in x]
        with tempfile.TemporaryDirectory() as d:
            lines = ["time,front_x," + ",".join("gauge_%g" % g for g in x)]
            for i in range(0, 971):
                t = 0.01 * i
                lines.append("%.2f,nan," % t + ",".join(
                    "%.9g" % (0.5 * a * math.cos(2 * math.pi * (g / L - t / T))) for a, g in zip(amp, x)))
            (pathlib.Path(d) / "progressive_wave.probes.csv").write_text("\n".join(lines) + "\n")
            j = ww.refit(str(validate), {"group": "g", "dir": d, "scene": "scenes/progressive_wave.json",
                                         "sets": []})
        f = ww.figures(j, "height_errors")
        want = ww.fitted_loss(x, [a / amp[0] - 1.0 for a in amp])
        self.assertAlmostEqual(j["decay_total_fit"], want, places=4)
        self.assertAlmostEqual(f["lost_fit"], want, places=4)
        self.assertAlmostEqual(j["decay_total"], 1.0 - amp[-1] / amp[0], places=4)
        self.assertGreater(j["decay_total"], j["decay_total_fit"])
        # Against linear theory's record in the same tank and windows.
        self.assertAlmostEqual(j["decay_total_fit_against_theory_record"],
                               1.0 - (1.0 - j["decay_total_fit"]) / (1.0 - j["theory_record_decay_total_fit"]))


if __name__ == "__main__":
    unittest.main()
