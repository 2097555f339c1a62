#!/usr/bin/env python3
"""tools/swellbench: bake checks as ensembles (tools/bench --members N). A case's row is the
members' mean with the sample sd of its error figures, the table reads 'mean ± sd', a member
that did not stay stable names itself in the row's outcome, and --members is checked.

    /usr/bin/python3 tests/tools/bench_ensemble_test.py
"""
import contextlib
import io
import pathlib
import statistics
import sys
import tempfile
import unittest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from swellbench import bake, cli, common  # noqa: E402


class Result:
    """What Context.run returns: the exit status, the wall time and the parsed JSON."""

    def __init__(self, j, wall=6.0):
        self.rc, self.wall, self.timed_out, self.json, self.err = 0, wall, False, j, ""

    def last_err_line(self):
        return ""


def dam_member(seed, aligned, outcome="stable"):
    return {"seed": seed, "outcome": outcome, "steps": 457, "particles": 1712, "water": 800,
            "solver_seconds": 1.0 + seed, "front_error_mean": 0.25, "front_error_max": 0.33,
            "aligned_front_error_mean": aligned, "aligned_front_error_max": 2 * aligned,
            "aligned_shift_T": 0.2, "ppe_iterations_mean": 18.0}


class Combine(unittest.TestCase):
    def test_mean_and_sample_sd_of_the_spread_fields_only(self):
        rows = [{"resolution": "a/20", "steps": 10, "err": 0.1, "cost": 1.0, "outcome": "stable"},
                {"resolution": "a/20", "steps": 12, "err": 0.3, "cost": 3.0, "outcome": "stable"},
                {"resolution": "a/20", "steps": 14, "err": 0.5, "cost": 2.0, "outcome": "stable"}]
        row = common.combine(rows, ("err",))
        self.assertEqual(row["members"], 3)
        self.assertAlmostEqual(row["err"], 0.3)
        self.assertAlmostEqual(row["err_sd"], statistics.stdev([0.1, 0.3, 0.5]))
        self.assertAlmostEqual(row["cost"], 2.0)
        self.assertNotIn("cost_sd", row)
        self.assertEqual(row["steps"], 12)
        self.assertEqual(row["resolution"], "a/20")
        self.assertEqual(row["outcome"], "stable")

    def test_a_member_that_stopped_names_itself_and_missing_figures_stay_out(self):
        rows = [{"err": 0.2, "outcome": "stable"}, {"err": None, "outcome": "stopped at step 9"},
                {"err": 0.4, "outcome": "stable"}]
        row = common.combine(rows, lambda k: k == "err")
        self.assertEqual(row["outcome"], "member 2: stopped at step 9")
        self.assertAlmostEqual(row["err"], 0.3)
        self.assertAlmostEqual(row["err_sd"], statistics.stdev([0.2, 0.4]))

    def test_table_reads_mean_plus_minus_sd(self):
        row = common.combine([{"err": 0.1}, {"err": 0.3}], ("err",))
        table = common.md_table([row, {"err": 0.25}], [("error", "err")])
        self.assertIn("| 0.2 ± 0.14 |", table)
        self.assertIn("| 0.25 |", table)  # a single record: no spread


class Validate(unittest.TestCase):
    def run_dam_break(self, members, answer):
        with tempfile.TemporaryDirectory() as tmp:
            ctx = common.Context(quick=True, log=None, out=tmp, members=members)
            commands = []

            def fake_run(cmd, timeout=900):
                commands.append([str(c) for c in cmd])
                return Result(answer)

            ctx.run = fake_run
            rows = [r for r in bake.dam_break(ctx) if r["resolution"] == "a/20"]
        return commands, rows

    def test_members_run_as_one_ensemble_and_give_mean_and_sd(self):
        answer = {"outcome": "stable", "ensemble": 3,
                  "members": [dam_member(1, 0.04), dam_member(2, 0.05), dam_member(3, 0.06)]}
        commands, rows = self.run_dam_break(3, answer)
        self.assertTrue(all(c[-2:] == ["--ensemble", "3"] for c in commands), commands[0])
        swell = next(r for r in rows if r["scheme"] == bake.DEFAULT_SCHEME)
        self.assertEqual(swell["members"], 3)
        self.assertAlmostEqual(swell["aligned_front_error_mean_a"], 0.05)
        self.assertAlmostEqual(swell["aligned_front_error_mean_a_sd"], 0.01)
        self.assertAlmostEqual(swell["aligned_front_error_max_a_sd"], 0.02)
        self.assertAlmostEqual(swell["wall_s"], 2.0)  # the run's 6 s over its three members
        self.assertAlmostEqual(swell["us_per_particle_step"], 1e6 * 3.0 / 457 / 1712)
        self.assertEqual(swell["outcome"], "stable")

    def test_one_member_is_one_unjittered_record(self):
        commands, rows = self.run_dam_break(1, dam_member(0, 0.04))
        self.assertTrue(all("--ensemble" not in c for c in commands))
        self.assertNotIn("members", rows[0])
        self.assertAlmostEqual(rows[0]["aligned_front_error_mean_a"], 0.04)
        self.assertNotIn("aligned_front_error_mean_a_sd", rows[0])

    def test_worst_lobovsky_gauge_is_the_one_with_the_largest_mean(self):
        def member(h1, h2):
            gauges = [{"name": "H1", "x": 0.3, "mean_abs_error_over_H": h1, "mean_signed_error_over_H": 0.0,
                       "experiment_scatter_over_H": None},
                      {"name": "H2", "x": 0.865, "mean_abs_error_over_H": h2, "mean_signed_error_over_H": 0.0,
                       "experiment_scatter_over_H": 0.0515}]
            return {"outcome": "stable", "steps": 10, "particles": 100, "solver_seconds": 1.0,
                    "gauges": gauges, "mean_abs_error_over_H_worst": max(h1, h2), "window": [0, 1.5],
                    "mean_abs_error_over_H_worst_run_up": h2 / 2, "far_gauge_landing_time": 0.9 + h1,
                    "far_wall_pressure": {"second_peak_time": 6.0 + h1,
                                          "delta_sph_320": {"mean_abs_error": h2}}}
        with tempfile.TemporaryDirectory() as tmp:
            ctx = common.Context(quick=True, log=None, out=tmp, members=2)
            ctx.run = lambda cmd, timeout=900: Result({"outcome": "stable",
                                                        "members": [member(0.09, 0.02), member(0.01, 0.06)]})
            row = bake.lobovsky(ctx)[0]
        # Gauge means H1 0.05, H2 0.04: H1 is the worst gauge; the worst figure is the members'
        # mean of their own worst gauges (0.09 and 0.06), as swell-validate --ensemble gives it.
        self.assertEqual(row["worst_gauge"], "H1")
        self.assertAlmostEqual(row["H1_mean_abs_error_over_H"], 0.05)
        self.assertAlmostEqual(row["worst_mean_abs_error_over_H"], 0.075)
        self.assertIn("H1_mean_abs_error_over_H_sd", row)
        # The experiment's own scatter rides along where a gauge has a second series, in the table.
        self.assertAlmostEqual(row["H2_experiment_scatter_over_H"], 0.0515)
        self.assertIsNone(row["H1_experiment_scatter_over_H"])
        # The first impact and run-up: its worst gauge with a spread, and when the water lands on
        # the far gauge.
        self.assertAlmostEqual(row["run_up_worst_mean_abs_error_over_H"], 0.02)
        self.assertIn("run_up_worst_mean_abs_error_over_H_sd", row)
        self.assertAlmostEqual(row["far_gauge_landing_s"], 0.95)
        # The far wall's pressure: the collapse's time and the error, with spreads.
        self.assertAlmostEqual(row["p1_collapse_t"], 6.05)
        self.assertIn("p1_collapse_t_sd", row)
        self.assertAlmostEqual(row["p1_mean_abs_error_delta_sph"], 0.04)
        table = bake.lobovsky_table([row])
        self.assertIn("P1: run-up's collapse", table)
        self.assertIn("worst over the first impact and run-up", table)
        self.assertIn("lands on the far gauge (s)", table)
        self.assertIn("H2: experiment's two series", table)
        self.assertNotIn("H1: experiment's two series", table)

    def test_a_partial_bake_run_refuses_to_blank_the_other_tables(self):
        # tools/bench --only lobovsky rewrites the one block of bake tables with the other parts'
        # rows read back from out/bench/: where they are missing or empty it stops first.
        with tempfile.TemporaryDirectory() as tmp:
            chosen = cli.selected({"lobovsky"})
            self.assertEqual(chosen, {"bake": ["lobovsky"]})
            with self.assertRaises(SystemExit) as e:
                cli.missing_bake_rows(chosen, False, tmp)
            self.assertIn("dam_break", str(e.exception))
            self.assertIn("--no-docs", str(e.exception))
            cli.missing_bake_rows(chosen, True, tmp)  # --no-docs: nothing to lose
            for part in bake.CSVS:  # an empty CSV (a run that wrote no rows) is no better
                with open(pathlib.Path(tmp) / (part + ".csv"), "w") as f:
                    f.write("\n")
            with self.assertRaises(SystemExit):
                cli.missing_bake_rows(chosen, False, tmp)
            for part in bake.CSVS:
                common.write_csv(str(pathlib.Path(tmp) / (part + ".csv")), [{"resolution": "x"}])
            cli.missing_bake_rows(chosen, False, tmp)
            cli.missing_bake_rows(cli.selected({"bake"}), False, str(pathlib.Path(tmp) / "none"))

    def test_lobovsky_gauges_are_the_columns_with_a_position(self):
        # The run-up's and the worst gauge's figures end like a gauge's error but are not gauges.
        row = {"H1_x_m": 0.3, "H1_mean_abs_error_over_H": 0.02, "H4_x_m": 1.36,
               "H4_mean_abs_error_over_H": 0.06, "run_up_worst_mean_abs_error_over_H": 0.065,
               "worst_mean_abs_error_over_H": 0.06}
        self.assertEqual(bake.gauge_names([row]), ["H1", "H4"])
        self.assertNotIn("run_up_worst -", bake.lobovsky_text([row]))

    def test_regular_wave_rows_say_which_window_the_heights_were_read_over(self):
        # swell-validate reports gauge_windows and reads each gauge's height over its own window
        # ("own"); a stored row without H_window, from a report without gauge_windows, reads as
        # "common".
        j = {"outcome": "stable", "kh": 1.0, "gauges": [0.5, 0.8], "window": [7.6, 9.7],
             "heights": [0.029], "height_errors": [-0.01], "height_theory": 0.0294,
             "gauge_windows": [[3.6, 9.7], [7.6, 9.7]], "decay_total": 0.04, "decay_total_fit": 0.0217}
        with tempfile.TemporaryDirectory() as tmp:
            ctx = common.Context(quick=True, log=None, out=tmp, members=0)
            ctx.run = lambda cmd, timeout=900: Result(j)
            rows = bake.regular_wave(ctx)
        self.assertTrue(rows)
        self.assertTrue(all(r["H_window"] == "own" for r in rows))
        old = {k: v for k, v in rows[0].items() if k != "H_window"}
        table = bake.regular_wave_table([rows[0], old]).splitlines()
        self.assertIn("| 7.6-9.7 | own |", table[2])
        self.assertIn("| 7.6-9.7 | common |", table[3])
        # The loss along the line through all gauges rides along as its own column.
        self.assertAlmostEqual(rows[0]["decay_total_fit"], 0.0217)
        self.assertIn("lost over the gauges", table[0])
        self.assertIn("0.0217", table[2])

    def test_standing_wave_rows_per_scheme_with_spread_and_table(self):
        def member(err, decay):
            return {"outcome": "stable", "steps": 6000, "particles": 1762, "water": 1250, "l0": 0.02,
                    "solver_seconds": 15.0, "period_theory": 1.1818, "period": 1.1818 * (1 + err),
                    "period_error": err, "decay_per_period": decay, "first_amplitude_over_theory": 1.1}
        with tempfile.TemporaryDirectory() as tmp:
            ctx = common.Context(quick=True, log=None, out=tmp, members=2)
            commands = []

            def fake_run(cmd, timeout=900):
                commands.append([str(c) for c in cmd])
                return Result({"outcome": "stable", "members": [member(-0.01, 0.04), member(-0.02, 0.08)]})
            ctx.run = fake_run
            rows = bake.standing_wave(ctx)
        # Quick: the h/25 scene only, both schemes, each an ensemble.
        self.assertEqual(len(rows), 2)
        self.assertTrue(all("standing-wave" in c and c[-2:] == ["--ensemble", "2"] for c in commands))
        self.assertTrue(any("solver.scheme=textbook" in c for c in commands[1]))
        self.assertEqual(rows[0]["resolution"], "h/25")
        self.assertAlmostEqual(rows[0]["period_error"], -0.015)
        self.assertAlmostEqual(rows[0]["decay_per_period"], 0.06)
        self.assertIn("decay_per_period_sd", rows[0])
        self.assertIn("| -0.015 ± 0.0071 |", bake.standing_wave_table(rows))

    def test_solitary_wave_rows_per_scheme_with_spread_and_table(self):
        def member(err, decay):
            return {"outcome": "stable", "steps": 6000, "particles": 4742, "water": 3250, "l0": 0.02,
                    "solver_seconds": 35.0, "celerity_theory": 1.5344, "celerity": 1.5344 * (1 + err),
                    "celerity_error": err, "first_amplitude_over_height": 0.86, "decay_total": decay,
                    "mean_width_error": 0.17}
        with tempfile.TemporaryDirectory() as tmp:
            ctx = common.Context(quick=True, log=None, out=tmp, members=2)
            commands = []

            def fake_run(cmd, timeout=900):
                commands.append([str(c) for c in cmd])
                return Result({"outcome": "stable", "members": [member(0.02, 0.20), member(0.04, 0.24)]})
            ctx.run = fake_run
            rows = bake.solitary_wave(ctx)
        # Quick: the h/10 scene only, both schemes, each an ensemble.
        self.assertEqual(len(rows), 2)
        self.assertTrue(all("solitary-wave" in c and c[-2:] == ["--ensemble", "2"] for c in commands))
        self.assertTrue(any("solver.scheme=textbook" in c for c in commands[1]))
        self.assertEqual(rows[0]["resolution"], "h/10")
        self.assertAlmostEqual(rows[0]["celerity_error"], 0.03)
        self.assertAlmostEqual(rows[0]["decay_total"], 0.22)
        self.assertIn("celerity_error_sd", rows[0])
        self.assertIn("| 0.03 ± 0.014 |", bake.solitary_wave_table(rows))
        self.assertIn("scenes/solitary_wave_small.json", bake.solitary_wave_text())
        self.assertIn("solitary_wave", bake.CSVS)  # a part of its own: tools/bench --only solitary_wave


    def test_wet_dam_break_rows_per_scheme_with_spread_and_table(self):
        def member(err, worst):
            return {"outcome": "stable", "steps": 4000, "particles": 8512, "water": 5600, "l0": 0.005,
                    "solver_seconds": 38.0, "theory": {"bore_speed": 0.939}, "bore_speed": 0.939 * (1 + err),
                    "bore_speed_error": err, "plateau_depth_error": -0.024,
                    "mean_abs_error_over_h0_worst": worst}
        with tempfile.TemporaryDirectory() as tmp:
            ctx = common.Context(quick=True, log=None, out=tmp, members=2)
            commands = []

            def fake_run(cmd, timeout=900):
                commands.append([str(c) for c in cmd])
                return Result({"outcome": "stable", "members": [member(-0.02, 0.03), member(-0.03, 0.04)]})
            ctx.run = fake_run
            rows = bake.wet_dam_break(ctx)
        # Quick: the h0/20 scene only, both schemes, each an ensemble.
        self.assertEqual(len(rows), 2)
        self.assertTrue(all("wet-dam-break" in c and c[-2:] == ["--ensemble", "2"] for c in commands))
        self.assertTrue(any("wet_dam_break_small.json" in a for a in commands[0]))
        self.assertTrue(any("solver.scheme=textbook" in c for c in commands[1]))
        self.assertEqual(rows[0]["resolution"], "h0/20")
        self.assertAlmostEqual(rows[0]["bore_speed_error"], -0.025)
        self.assertAlmostEqual(rows[0]["bore_speed_theory_m_s"], 0.939)
        self.assertAlmostEqual(rows[0]["mean_abs_error_over_h0_worst"], 0.035)
        self.assertIn("bore_speed_error_sd", rows[0])
        self.assertIn("| -0.025 ± 0.0071 |", bake.wet_dam_break_table(rows))
        self.assertIn("scenes/wet_dam_break_small.json", bake.wet_dam_break_text())
        self.assertIn("wet_dam_break", bake.CSVS)  # a part of its own: tools/bench --only wet_dam_break

    def test_shoaling_rows_per_scheme_with_spread_and_table(self):
        def member(crest, worst):
            return {"outcome": "stable", "steps": 8000, "particles": 17988, "water": 12940, "l0": 0.022,
                    "solver_seconds": 150.0, "incident_crest_error": -0.08, "crest_error_worst": crest,
                    "mean_abs_error_over_h0_worst": worst, "travel_time_error": 0.02}
        with tempfile.TemporaryDirectory() as tmp:
            ctx = common.Context(quick=True, log=None, out=tmp, members=2)
            commands = []

            def fake_run(cmd, timeout=900):
                commands.append([str(c) for c in cmd])
                return Result({"outcome": "stable", "members": [member(-0.2, 0.02), member(-0.3, 0.03)]})
            ctx.run = fake_run
            rows = bake.shoaling(ctx)
        # Quick: the h0/20 scene only, both schemes, each an ensemble.
        self.assertEqual(len(rows), 2)
        self.assertTrue(all("shoaling" in c and c[-2:] == ["--ensemble", "2"] for c in commands))
        self.assertTrue(any("shoaling_small.json" in a for a in commands[0]))
        self.assertTrue(any("solver.scheme=textbook" in c for c in commands[1]))
        self.assertEqual(rows[0]["resolution"], "h0/20")
        self.assertAlmostEqual(rows[0]["crest_error_worst"], -0.25)
        self.assertAlmostEqual(rows[0]["mean_abs_error_over_h0_worst"], 0.025)
        self.assertIn("crest_error_worst_sd", rows[0])
        self.assertIn("| -0.25 ± 0.071 |", bake.shoaling_table(rows))
        self.assertIn("scenes/shoaling_small.json", bake.shoaling_text())
        self.assertIn("shoaling", bake.CSVS)  # a part of its own: tools/bench --only shoaling


class Members(unittest.TestCase):
    def parse(self, argv):
        with contextlib.redirect_stderr(io.StringIO()):
            return cli.parse_args(argv)

    def test_defaults_and_range(self):
        self.assertEqual(self.parse(["--quick"]).members, 1)
        self.assertEqual(self.parse([]).members, 3)
        self.assertEqual(self.parse(["--quick", "--members", "4"]).members, 4)
        for bad in (["--members", "0"], ["--members", "65"], ["--docs-only", "--members", "2"]):
            with self.assertRaises(SystemExit, msg=bad):
                self.parse(bad)


if __name__ == "__main__":
    unittest.main()
