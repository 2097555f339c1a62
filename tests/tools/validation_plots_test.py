#!/usr/bin/env python3
"""tools/validation_plots.py --quick: the five plots written from stable runs of the CI scenes,
every experimental point of the records in its CSV, a clear error for a missing binary; and
the swell-validate behaviour those plots rely on (clear errors, stopped runs, ensembles).

    /usr/bin/python3 tests/tools/validation_plots_test.py BIN_DIR
"""
import csv
import json
import pathlib
import subprocess
import sys
import tempfile
import unittest

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOOL = ROOT / "tools" / "validation_plots.py"
BIN = pathlib.Path(sys.argv.pop(1) if len(sys.argv) > 1 else ROOT / "build" / "bin")


class ValidationPlots(unittest.TestCase):
    def test_quick_run_writes_the_plots_from_stable_runs(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = pathlib.Path(tmp)
            p = subprocess.run([sys.executable, str(TOOL), "--quick", "--threads", "1",
                                "--bin", str(BIN), "--out", str(out)],
                               capture_output=True, text=True)
            self.assertEqual(p.returncode, 0, p.stderr)
            for name in ("dam_break_front.png", "lobovsky_gauges.png", "lobovsky_p1.png",
                         "solitary_wave.png", "wet_dam_break.png", "shoaling.png"):
                data = (out / name).read_bytes()
                self.assertEqual(data[:8], b"\x89PNG\r\n\x1a\n", name)
                self.assertGreater(len(data), 20_000, name)  # axes, points and lines drawn
            summary = json.loads((out / "validation_plots.json").read_text())
            kinds = [(r["kind"], r["label"]) for r in summary["runs"]]
            self.assertEqual(kinds, [("dam-break", "a/20"), ("lobovsky", "H/15"),
                                     ("solitary-wave", "h/10"), ("wet-dam-break", "h0/20"),
                                     ("shoaling", "h0/10")])
            for r in summary["runs"]:
                self.assertEqual(r["result"]["outcome"], "stable", r["command"])
                self.assertIn("swell-validate", r["command"])
            with open(out / "dam-break_records.csv", newline="") as f:
                series = {row["series"] for row in csv.DictReader(f)}
            self.assertEqual(series, {"a2.25in", "a1.125in"})
            with open(out / "lobovsky_records.csv", newline="") as f:
                rows = list(csv.DictReader(f))
            self.assertEqual({r["gauge"] for r in rows}, {"H1", "H2", "H3", "H4"})
            # H2-H4 also carry the experiment's other series, drawn beside the compared one.
            self.assertEqual({r["gauge"] for r in rows if r["series"] == "repeat"},
                             {"H2", "H3", "H4"})
            # The wet dam break's quick run ends at 1.2 s: every window ends there, and the
            # gauges from 1.5 m on still see the bore.
            wet = summary["runs"][3]["result"]
            self.assertEqual({g["until"] for g in wet["gauge_records"]}, {1.2})
            self.assertGreaterEqual(wet["bore_gauges"], 3)
            with open(out / "wet-dam-break_h0_20.csv", newline="") as f:
                header = next(csv.reader(f))
            self.assertEqual(header, ["t"] + ["h_%g" % x for x in wet["gauges"]])
            # The shoaling wave's records: the six gauges, g0 first; the run's series has each.
            with open(out / "shoaling_records.csv", newline="") as f:
                rows = list(csv.DictReader(f))
            self.assertEqual([r["gauge"] for r in rows][0], "g0")
            self.assertEqual({r["gauge"] for r in rows}, {"g0", "g1", "g3", "g5", "g7", "g9"})
            shoal = summary["runs"][4]["result"]
            self.assertEqual([g["name"] for g in shoal["gauge_records"]],
                             ["g0", "g1", "g3", "g5", "g7", "g9"])
            with open(out / "shoaling_h0_10.csv", newline="") as f:
                header = next(csv.reader(f))
            self.assertEqual(header, ["t"] + ["eta_%g" % x for x in shoal["gauges"]])
            lob = summary["runs"][1]["result"]["gauges"]
            self.assertIsNone(lob[0]["experiment_scatter_over_H"])
            for g in lob[1:]:
                self.assertGreater(g["experiment_scatter_over_H"], 0.0, g["name"])
            self.check_lobovsky_run_up(summary["runs"][1]["result"],
                                       out / "lobovsky_H_15.csv", out / "lobovsky_records.csv")
            self.check_far_wall_pressure(summary["runs"][1]["result"], out / "lobovsky_H_15.csv",
                                         out / "lobovsky_pressure_records.csv")

    def check_far_wall_pressure(self, result, series_csv, records_csv):
        # Sensor P1 (docs/validation.md, Far-wall pressure), recomputed from the CSVs: every series
        # through the same moving average (half width 0.05 in t sqrt(g/H)); the run-up's collapse is
        # the largest smoothed value in [5, 7]; the impact the first one above 0.3.
        sys.path.insert(0, str(ROOT / "tools"))
        import validation_plots  # noqa: E402

        with open(records_csv, newline="") as f:
            records = list(csv.DictReader(f))
        self.assertEqual({r["series"] for r in records},
                         {"experiment", "delta_sph_40", "delta_sph_80", "delta_sph_320"})
        scale = (result["gravity"] / result["H"]) ** 0.5
        with open(series_csv, newline="") as f:
            rows = list(csv.DictReader(f))
        series = {"run": ([float(r["t"]) * scale for r in rows],
                          [float(r["p_P1_over_rho_g_H"]) for r in rows])}
        for name in ("experiment", "delta_sph_320"):
            series[name] = ([float(r["t"]) for r in records if r["series"] == name],
                            [float(r["p"]) for r in records if r["series"] == name])
        p1 = result["far_wall_pressure"]
        # The rule as the JSON states it, which the plot draws by.
        self.assertEqual(p1["smoothing_half_width"], 0.05)
        self.assertEqual(p1["impact_level"], 0.3)
        self.assertEqual(p1["second_peak_window"], [5.0, 7.0])
        for name, (t, p) in series.items():
            s = validation_plots.moving_average(t, p, 0.05)
            window = [(si, ti) for ti, si in zip(t, s) if 5.0 <= ti <= 7.0]
            peak = max(window, key=lambda w: w[0])
            impact = next(ti for ti, si in zip(t, s) if si > 0.3)
            figures = p1 if name == "run" else p1[name]
            # The CSV holds 5 decimals of seconds and of p / (rho g H).
            self.assertAlmostEqual(figures["second_peak_time"], peak[1], delta=0.02, msg=name)
            self.assertAlmostEqual(figures["second_peak"], peak[0], delta=1e-3, msg=name)
            self.assertAlmostEqual(figures["impact_time"], impact, delta=0.02, msg=name)
        # The references' own order: the experiment's collapse comes before delta-SPH's.
        self.assertLess(p1["experiment"]["second_peak_time"],
                        p1["delta_sph_320"]["second_peak_time"])

    def check_lobovsky_run_up(self, result, series_csv, records_csv):
        # The first impact and run-up of the Lobovsky levels, recomputed here from the CSVs:
        # the window ends at the far gauge's (H4's) first record sample above H/2, and each
        # gauge's error is the mean |h_sim - h_record| / H over the record samples in it, the
        # run's level interpolated linearly at each record time.
        H = result["H"]
        with open(records_csv, newline="") as f:
            records = [r for r in csv.DictReader(f) if r["series"] == "record"]
        far = max(records, key=lambda r: float(r["x"]))["gauge"]
        self.assertEqual(result["far_gauge"], far)
        end = next(float(r["t"]) for r in records if r["gauge"] == far and float(r["h"]) > H / 2)
        self.assertAlmostEqual(end, 1.0933, places=4)
        self.assertEqual(result["run_up_window"], [0.0, end])
        self.assertEqual(result["far_gauge_landing_time_record"], end)
        with open(series_csv, newline="") as f:
            rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
        t = [r["t"] for r in rows]

        def level(gauge, time):
            k = next(i for i in range(1, len(t)) if t[i] >= time)
            a, b = rows[k - 1]["h_" + gauge], rows[k]["h_" + gauge]
            return a + (b - a) * (time - t[k - 1]) / (t[k] - t[k - 1])

        worst = 0.0
        for g in result["gauges"]:
            pts = [(float(r["t"]), float(r["h"])) for r in records
                   if r["gauge"] == g["name"] and float(r["t"]) <= end]
            mean = sum(abs(level(g["name"], tr) - hr) for tr, hr in pts) / len(pts) / H
            # The CSV holds 5 decimals of metres and seconds: 1e-4 H is far below a real change.
            self.assertAlmostEqual(g["mean_abs_error_over_H_run_up"], mean, delta=1e-4,
                                   msg=g["name"])
            worst = max(worst, g["mean_abs_error_over_H_run_up"])
        self.assertEqual(result["mean_abs_error_over_H_worst_run_up"], worst)
        lands = next(r["t"] for r in rows if r["h_" + far] > H / 2)
        self.assertAlmostEqual(result["far_gauge_landing_time"], lands, delta=1e-5)

    def test_only_runs_and_plots_the_checks_named(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = pathlib.Path(tmp)
            p = subprocess.run([sys.executable, str(TOOL), "--quick", "--threads", "1",
                                "--only", "dam-break", "--bin", str(BIN), "--out", str(out)],
                               capture_output=True, text=True)
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertEqual(sorted(f.name for f in out.glob("*.png")), ["dam_break_front.png"])
            summary = json.loads((out / "validation_plots.json").read_text())
            self.assertEqual([r["kind"] for r in summary["runs"]], ["dam-break"])
            p = subprocess.run([sys.executable, str(TOOL), "--only", "tsunami", "--bin", str(BIN),
                                "--out", str(out)], capture_output=True, text=True)
            self.assertEqual(p.returncode, 2)
            self.assertIn("--only", p.stderr)

    def test_unwritable_csv_and_records_are_one_clear_line_each(self):
        scene = str(ROOT / "scenes" / "lobovsky_small.json")
        for option in ("--csv", "--records", "--pressure-records"):
            p = subprocess.run([str(BIN / "swell-validate"), "--threads", "1", "lobovsky", scene,
                                "--until", "0.01", option, "/nonexistent/dir/x.csv"],
                               capture_output=True, text=True)
            self.assertEqual(p.returncode, 1, option)
            lines = p.stderr.strip().splitlines()
            self.assertEqual(len(lines), 1, p.stderr)
            self.assertIn(f"{option} /nonexistent/dir/x.csv: cannot write", lines[0])

    def test_a_stopped_run_says_why_on_stderr(self):
        # The detector stops the run (a Courant limit below the surge's): status 3, the report
        # on stdout still, and one line on stderr naming the scene and the stop.
        scene = str(ROOT / "scenes" / "dam_break_small.json")
        p = subprocess.run([str(BIN / "swell-validate"), "--json", "--threads", "1",
                            "--set", "solver.courant_limit=0.15",
                            "--set", "solver.expected_speed=1",
                            "--set", "solver.substep_courant=0", "dam-break", scene],
                           capture_output=True, text=True)
        self.assertEqual(p.returncode, 3, p.stderr)
        report = json.loads(p.stdout.strip().splitlines()[-1])
        self.assertTrue(report["outcome"].startswith("stopped: "), report["outcome"])
        lines = p.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, p.stderr)
        self.assertIn("dam_break_small.json: stopped: ", lines[0])
        self.assertIn("solver.courant_limit 0.15", lines[0])

    def test_an_ensemble_reports_each_member_and_the_spread_of_its_figures(self):
        # swell-validate --ensemble: members with seeds 1..N, the water jittered by 1e-6 l0; each
        # figure's mean, sd and range over the members.
        scene = str(ROOT / "scenes" / "lobovsky_small.json")
        p = subprocess.run([str(BIN / "swell-validate"), "--json", "--threads", "1", "lobovsky",
                            scene, "--until", "0.3", "--ensemble", "3"],
                           capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stderr)
        report = json.loads(p.stdout)
        self.assertEqual(report["outcome"], "stable")
        self.assertEqual(report["ensemble"], 3)
        self.assertEqual(report["jitter"], 1e-6)
        members = report["members"]
        self.assertEqual([m["seed"] for m in members], [1, 2, 3])
        for gauge in ("H1", "H2", "H3", "H4", "worst"):
            name = "mean_abs_error_over_H_" + gauge
            values = [m["mean_abs_error_over_H_worst"] if gauge == "worst" else
                      next(g["mean_abs_error_over_H"] for g in m["gauges"] if g["name"] == gauge)
                      for m in members]
            spread = report[name]
            self.assertAlmostEqual(spread["mean"], sum(values) / 3, places=12, msg=name)
            self.assertEqual(spread["min"], min(values), name)
            self.assertEqual(spread["max"], max(values), name)
            self.assertGreaterEqual(spread["sd"], 0.0, name)
            self.assertEqual(spread["members"], 3, name)
        # The members differ (the jitter reaches the water), each one stable.
        self.assertGreater(len({m["gauges"][0]["mean_abs_error_over_H"] for m in members}), 1)
        self.assertEqual(p.stderr.count("ensemble member"), 3, p.stderr)

    def test_an_ensemble_with_a_stopped_member_says_so(self):
        scene = str(ROOT / "scenes" / "dam_break_small.json")
        p = subprocess.run([str(BIN / "swell-validate"), "--json", "--threads", "1",
                            "--set", "solver.courant_limit=0.15",
                            "--set", "solver.expected_speed=1",
                            "--set", "solver.substep_courant=0", "dam-break", scene,
                            "--ensemble", "2"],
                           capture_output=True, text=True)
        self.assertEqual(p.returncode, 3, p.stderr)
        report = json.loads(p.stdout)
        self.assertTrue(report["outcome"].startswith("stopped: a member stopped"), report)
        self.assertNotIn("aligned_front_error_mean", report)  # no spread of stopped runs
        self.assertTrue(all(m["outcome"].startswith("stopped: ") for m in report["members"]))

    def test_missing_binary_is_one_clear_line(self):
        with tempfile.TemporaryDirectory() as tmp:
            p = subprocess.run([sys.executable, str(TOOL), "--quick", "--bin", tmp,
                                "--out", tmp], capture_output=True, text=True)
            self.assertEqual(p.returncode, 1)
            self.assertEqual(len(p.stderr.strip().splitlines()), 1, p.stderr)
            self.assertIn("no swell-validate", p.stderr)


if __name__ == "__main__":
    unittest.main()
