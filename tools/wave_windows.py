#!/usr/bin/env python3
"""Kept regular-wave records fitted again, each gauge over its own window and over the common
one: the table and plot of docs/validation.md, Progressive waves.

Each line of RUNS names one kept record (`swell-validate regular-wave SCENE --keep DIR`):

    GROUP  DIR  SCENE  [KEY=VALUE ...]

GROUP gathers records into one row of the table (a jittered ensemble, or unjittered
variants); DIR holds SCENE's probes CSV; the KEY=VALUE pairs are the --set values the record
was baked with, so the fit reads the same scene. Each record is fitted with `swell-validate
--json [--set KEY=VALUE ...] regular-wave SCENE --probes DIR/<name>.probes.csv` (nothing is
baked) and the table gives, per group and per window, the height error at the first gauge,
the worst gauge and the height lost over the gauges (1 - H(last) / H(first), and along the
least-squares line of ln H through all gauges), and, in each gauge's own window, that line's
loss against linear theory's record of the same piston in the same tank, as mean +- sd (range),
and that loss's standard error as each record reads it from its own fluctuations, as mean
(range): where the records are members of one ensemble, what one record predicts for their sd.
The plot draws linear theory's record too.

    /usr/bin/python3 tools/wave_windows.py RUNS [--plot PNG] [--periods X]
        [--validate build/bin/swell-validate]

--periods X also fits the gauge at x = X (m) one period at a time over its own window (the
same harmonic fit: a cos wt + b sin wt + c at the piston's period) and gives each group's
height error per period, mean +- sd.

--plot draws one panel per group whose name ends in `_j` (jittered members: mean +- sd as a
band), with the records of every group named like it with `_u...` in place of `_j` (NAME_u,
NAME_uv: unjittered records) as crosses.
"""
import argparse
import json
import math
import pathlib
import statistics
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
WINDOWS = (("own", "height_errors"), ("common", "height_errors_common_window"))
AGAINST_THEORY = "decay_total_fit_against_theory_record"


def parse_runs(text):
    """Lines GROUP DIR SCENE [KEY=VALUE ...] -> dicts; blank lines and # comments skipped."""
    runs = []
    for number, line in enumerate(text.splitlines(), 1):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        parts = line.split()
        if len(parts) < 3 or any("=" not in p for p in parts[3:]):
            raise ValueError("line %d: want GROUP DIR SCENE [KEY=VALUE ...], got %r" % (number, line))
        runs.append({"group": parts[0], "dir": parts[1], "scene": parts[2], "sets": parts[3:]})
    return runs


def refit(validate, run):
    """swell-validate --probes on one kept record: its JSON report."""
    probes = probes_path(run)
    cmd = [validate, "--json"] + [a for s in run["sets"] for a in ("--set", s)]
    cmd += ["regular-wave", run["scene"], "--probes", str(probes)]
    done = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    if done.returncode != 0:
        raise RuntimeError("%s: %s" % (" ".join(cmd), done.stderr.strip()))
    return json.loads(done.stdout)


def fitted_loss(x, errors):
    """1 - exp(b (max x - min x)), b the least-squares slope of ln H against x over all gauges
    (H / H_Biesel = 1 + error): the height lost across the gauges along the line through them,
    swell-validate's decay_total_fit."""
    b = statistics.linear_regression(x, [math.log(1.0 + e) for e in errors]).slope
    return 1.0 - math.exp(b * (max(x) - min(x)))


def figures(report, key):
    """Height error at the nearest gauge, the worst |error|, 1 - H(farthest) / H(nearest) and
    the loss across the gauges along the line ln H = a + b x through all of them."""
    errors, x = report[key], report["gauges"]
    near, far = x.index(min(x)), x.index(max(x))
    return {"first": errors[near], "worst": max(abs(e) for e in errors),
            "lost": 1.0 - (1.0 + errors[far]) / (1.0 + errors[near]),
            "lost_fit": fitted_loss(x, errors)}


def spread(values):
    """'mean +- sd (min to max)' in per cent; one value alone as itself."""
    pct = [100.0 * v for v in values]
    if len(pct) == 1:
        return "%+.1f %%" % pct[0]
    return "%+.1f +- %.1f %% (%+.1f to %+.1f)" % (statistics.mean(pct), statistics.stdev(pct),
                                                min(pct), max(pct))


def own_window_figure(report, window, key):
    """A figure swell-validate reads over each gauge's own window only: the loss along the line
    against linear theory's record of the same piston in the same tank (AGAINST_THEORY), or its
    standard error from the record's own fluctuations (AGAINST_THEORY + "_standard_error"). None
    for the common window or a report without it."""
    if window != "own":
        return None
    return report.get(key)


def mean_and_range(values):
    """'mean % (min to max)' in per cent; one value alone as itself."""
    pct = [100.0 * v for v in values]
    if len(pct) == 1:
        return "%.1f %%" % pct[0]
    return "%.1f %% (%.1f to %.1f)" % (statistics.mean(pct), min(pct), max(pct))


def table(groups):
    """Markdown rows: group, window, records, H at the first gauge, worst gauge, lost (the
    two-gauge ratio, the line through all gauges, and that line against linear theory's
    record in the same tank, own windows only), and each record's standard error of the last
    (its mean and range over the records: what one record predicts for their spread)."""
    rows = ["| group | window | records | H at the first gauge | worst gauge | lost, last / first "
            "gauge | lost, line through all gauges | the line's loss against linear theory's record "
            "| its standard error, one record |",
            "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for name, reports in groups.items():
        for window, key in WINDOWS:
            f = [figures(r, key) for r in reports]
            theory = [own_window_figure(r, window, AGAINST_THEORY) for r in reports]
            errors = [own_window_figure(r, window, AGAINST_THEORY + "_standard_error")
                      for r in reports]
            rows.append("| %s | %s | %d | %s | %s | %s | %s | %s | %s |" % (
                name, window, len(f), spread([v["first"] for v in f]),
                spread([v["worst"] for v in f]), spread([v["lost"] for v in f]),
                spread([v["lost_fit"] for v in f]),
                "-" if None in theory else spread(theory),
                "-" if None in errors else mean_and_range(errors)))
    return "\n".join(rows)


def probes_path(run):
    return pathlib.Path(run["dir"]) / (pathlib.Path(run["scene"]).stem + ".probes.csv")


def read_gauge(path, x):
    """Times and elevations of the gauge at x (column gauge_<x> as swell-bake writes it)."""
    import csv
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    column = "gauge_%g" % x
    if not rows or column not in rows[0]:
        raise ValueError("%s: no column %s" % (path, column))
    return [float(r["time"]) for r in rows], [float(r[column]) for r in rows]


def per_period(t, eta, period, start, end, height):
    """H / height - 1 of the harmonic fit over each whole period from start up to end."""
    import numpy as np
    t, eta = np.asarray(t), np.asarray(eta)
    w = 2.0 * np.pi / period
    out = []
    k = 0
    while start + (k + 1) * period <= end + 1e-9:
        a = start + k * period
        m = (t >= a) & (t <= a + period)
        design = np.c_[np.cos(w * t[m]), np.sin(w * t[m]), np.ones(int(m.sum()))]
        c = np.linalg.lstsq(design, eta[m], rcond=None)[0]
        out.append(2.0 * np.hypot(c[0], c[1]) / height - 1.0)
        k += 1
    return out


def piston_period(run):
    """The piston's period (s): the scene's, or the record's --set piston.period."""
    for kv in run["sets"]:
        key, value = kv.split("=", 1)
        if key == "piston.period":
            return float(value)
    return float(json.loads((ROOT / run["scene"]).read_text())["piston"]["period"])


def period_table(groups, runs_by_group, x, period=piston_period):
    """Markdown rows: each group's height error per period at the gauge at x; period(run)
    gives each record's piston period."""
    lines, width = [], 0
    for name, reports in groups.items():
        series = []
        for report, run in zip(reports, runs_by_group[name]):
            g = report["gauges"].index(x) if x in report["gauges"] else None
            if g is None:
                raise ValueError("%s: no gauge at x = %g" % (run["scene"], x))
            start, end = report["gauge_windows"][g]
            t, eta = read_gauge(probes_path(run), x)
            series.append(per_period(t, eta, period(run), start, end, report["height_theory"]))
        n = min(len(v) for v in series)
        width = max(width, n)
        cells = [spread([v[i] for v in series]) for i in range(n)]
        lines.append("| %s | %d | %s |" % (name, len(series), " | ".join(cells)))
    head = "| group | records | %s |" % " | ".join("period %d" % (i + 1) for i in range(width))
    return "\n".join([head, "| --- " * (width + 2) + "|"] + lines)


def plot(groups, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    panels = [g for g in groups if g.endswith("_j")]
    # At least 9 inches wide, so that one panel leaves room for the title and the legend.
    fig, axs = plt.subplots(1, len(panels), figsize=(max(9.0, 5.0 * len(panels)), 5.4),
                            sharey=True, squeeze=False)
    for ax, name in zip(axs[0], panels):
        members = groups[name]
        x = members[0]["gauges"]
        stem = name[:-len("_j")]
        crosses = [r for g, rs in groups.items() if g.startswith(stem + "_u") for r in rs]
        for (window, key), colour in zip(WINDOWS, ("C0", "C1")):
            lab = "each gauge's own window" if window == "own" else "common window"
            by_gauge = [[100.0 * r[key][i] for r in members] for i in range(len(x))]
            mean = [statistics.mean(v) for v in by_gauge]
            sd = [statistics.stdev(v) if len(v) > 1 else 0.0 for v in by_gauge]
            ax.fill_between(x, [m - s for m, s in zip(mean, sd)], [m + s for m, s in zip(mean, sd)],
                            color=colour, alpha=0.2)
            ax.plot(x, mean, "-", color=colour, label="%s: jittered members, mean +- sd" % lab)
            for i, r in enumerate(crosses):
                ax.plot(x, [100.0 * v for v in r[key]], "x", color=colour, ms=6,
                        label="%s: unjittered records" % lab if i == 0 else None)
        if "theory_record_height_errors" in members[0]:
            # What the own windows make of linear theory's undamped record of the same piston
            # (the same for every member): where a perfect solver would read.
            ax.plot(x, [100.0 * v for v in members[0]["theory_record_height_errors"]], "--",
                    color="k", lw=1.0, label="linear theory's record, each gauge's own window")
        ax.axhspan(-5, 5, color="0.93", zorder=0)
        ax.axhline(0, color="k", lw=0.6)
        ax.set_title("%s (%s), %d members" % (stem, members[0]["scene"], len(members)), fontsize=9)
        ax.set_xlabel("gauge x (m)")
        ax.grid(alpha=0.3)
    axs[0][0].set_ylabel("H / H_Biesel - 1 (%)")
    handles, labels = axs[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=2, fontsize=8)
    fig.suptitle("Regular waves: height at each gauge over each gauge's own window and over the\n"
                 "common window; grey: the 5 % target", fontsize=10)
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    fig.savefig(path, dpi=80)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("runs", help="file of lines GROUP DIR SCENE [KEY=VALUE ...]")
    ap.add_argument("--plot", help="write the plot to this PNG")
    ap.add_argument("--periods", type=float, metavar="X",
                    help="also fit the gauge at x = X (m) one period at a time")
    ap.add_argument("--validate", default=str(ROOT / "build" / "bin" / "swell-validate"))
    a = ap.parse_args(argv)
    groups, runs_by_group = {}, {}
    try:
        for run in parse_runs(pathlib.Path(a.runs).read_text()):
            groups.setdefault(run["group"], []).append(refit(a.validate, run))
            runs_by_group.setdefault(run["group"], []).append(run)
        print(table(groups))
        if a.periods is not None:
            print()
            print(period_table(groups, runs_by_group, a.periods))
    except (OSError, ValueError, KeyError, RuntimeError) as e:
        print("wave_windows: %s" % e, file=sys.stderr)
        return 1
    if a.plot:
        plot(groups, a.plot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
