#!/usr/bin/env python3
"""Plots of the bake against the experiments it is validated on (docs/validation.md):
the dam-break surge front against Martin & Moyce (1952), raw and on the experiment's time
origin, the Lobovsky et al. (2014) water levels at gauges H1..H4, a solitary wave's records
at five gauges against the stroke's wave under the Serre-Green-Naghdi equations
(tools/sgn_solitary.py), a dam breaking onto a wet bed against Stoker's shallow-water solution
and a solitary wave shoaling up a beach against Grilli et al. (1994)'s gauges, each at several
resolutions, from swell-validate runs of the shipped scenes.

    /usr/bin/python3 tools/validation_plots.py [--bin build/bin] [--out out/validation]
        [--threads N] [--quick]
        [--only dam-break|lobovsky|solitary-wave|wet-dam-break|shoaling]...

Writes OUT/dam_break_front.png, OUT/lobovsky_gauges.png, OUT/lobovsky_p1.png (the same runs'
far-wall pressure against Buchner (2002) and Marrone et al. (2011)), OUT/solitary_wave.png,
OUT/wet_dam_break.png, OUT/shoaling.png and OUT/validation_plots.json (each run's command, its
swell-validate JSON, the commit). --quick runs the CI resolutions only (a/20, H/15, h/10, h0/20
to 1.2 s, h0/10; about a minute and a half) instead of a/20, a/50, a/80, H/15, H/30, H/60, h/10,
h/20, h/40, h0/20, h0/40 and the shoaling wave at h0/10, h0/20, h0/40 (about 50 minutes with one
thread, most of it the two h/40 runs).
The experimental points come from `swell-validate ... --records`, i.e. the very records the
checks compare with. Exit status 1 with one line on stderr when a run fails.
"""
import argparse
import csv
import json
import pathlib
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import sgn_solitary  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]

# (label, scene, --set overrides): the shipped scenes and finer spacings of the same scenes.
DAM_BREAK = [
    ("a/20", "dam_break_small.json", []),
    ("a/50", "dam_break.json", []),
    ("a/80", "dam_break_small.json",
     ["geometry.particle_spacing=0.00125", "solver.dt=0.000125"]),
]
LOBOVSKY = [
    ("H/15", "lobovsky_small.json", []),
    ("H/30", "lobovsky.json", []),
    # The jet the far wall throws back passes Courant 0.5 at this spacing and step: the
    # solver's sub-steps (solver.substep_courant 0.5, under the default limit 0.8) follow it.
    ("H/60", "lobovsky.json", ["geometry.particle_spacing=0.005", "solver.dt=0.0004"]),
]
SOLITARY = [
    ("h/10", "solitary_wave_small.json", []),
    ("h/20", "solitary_wave.json", []),
    ("h/40", "solitary_wave.json", ["geometry.particle_spacing=0.005"]),
]
WET_DAM_BREAK = [
    ("h0/20", "wet_dam_break_small.json", []),
    ("h0/40", "wet_dam_break.json", []),
]
# --quick: the CI scene to 1.2 s (the windows end there; three gauges still see the bore).
WET_DAM_BREAK_QUICK = [("h0/20", "wet_dam_break_small.json", ["solver.end_time=1.2"])]
SHOALING = [
    ("h0/10", "shoaling_small.json", ["geometry.particle_spacing=0.044", "solver.dt=0.003"]),
    ("h0/20", "shoaling_small.json", []),
    ("h0/40", "shoaling.json", []),
]
# in the order run and plotted
KINDS = ("dam-break", "lobovsky", "solitary-wave", "wet-dam-break", "shoaling")
COLOURS = ["tab:blue", "tab:orange", "tab:green"]
GAUGE_COLOURS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown"]


def fail(message):
    print(f"validation_plots: {message}", file=sys.stderr)
    sys.exit(1)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def run(binary, threads, kind, label, scene, sets, out):
    """One swell-validate run; returns (command, its JSON, series rows, records rows)."""
    stem = f"{kind}_{label.replace('/', '_')}"
    series, records = out / f"{stem}.csv", out / f"{kind}_records.csv"
    cmd = [str(binary / "swell-validate"), "--json"]
    if threads:
        cmd += ["--threads", str(threads)]
    for s in sets:
        cmd += ["--set", s]
    with_records = kind in ("dam-break", "lobovsky", "shoaling")  # the others: with theory
    cmd += [kind, str(ROOT / "scenes" / scene), "--csv", str(series)]
    if with_records:
        cmd += ["--records", str(records)]
    pressure = out / f"{kind}_pressure_records.csv"  # the far wall's sensor P1
    if kind == "lobovsky":
        cmd += ["--pressure-records", str(pressure)]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        last = (p.stderr.strip().splitlines() or ["(no message on stderr)"])[-1]
        fail(f"{kind} {label} ({scene}) failed with status {p.returncode}: {last}")
    result = json.loads(p.stdout.strip().splitlines()[-1])
    return {"label": label, "command": " ".join(cmd), "result": result,
            "series": read_csv(series),
            "records": read_csv(records) if with_records else [],
            "pressure_records": read_csv(pressure) if kind == "lobovsky" else []}


def plot_dam_break(runs, path):
    records = runs[0]["records"]
    exp = {}
    for r in records:
        exp.setdefault(r["series"], ([], []))
        exp[r["series"]][0].append(float(r["T"]))
        exp[r["series"]][1].append(float(r["Z"]))
    markers = {"a2.25in": ("s", "Martin & Moyce, a = 2.25 in"),
               "a1.125in": ("o", "Martin & Moyce, a = 1.125 in")}
    fig, (raw, aligned) = plt.subplots(1, 2, figsize=(11, 4.6), sharey=True)
    for ax in (raw, aligned):
        for name, (T, Z) in exp.items():
            m, text = markers.get(name, ("x", name))
            ax.plot(T, Z, m, mfc="none", color="black", label=text)
        ax.axvspan(0.8, 3.0, color="0.93", zorder=0)
        ax.set_xlim(0.0, 3.4)
        ax.set_ylim(1.0, 4.6)
        ax.set_xlabel("T = t sqrt(2 g / a)")
        ax.grid(alpha=0.3)
    for run_, colour in zip(runs, COLOURS):
        T = [float(r["T"]) for r in run_["series"]]
        Z = [float(r["Z"]) for r in run_["series"]]
        res = run_["result"]
        raw.plot(T, Z, color=colour,
                 label=f"{run_['label']}: mean |dZ| {res['front_error_mean']:.3f} a")
        for name, style in (("a225", "-"), ("a1125", "--")):
            shift = res[f"aligned_shift_T_{name}"]
            aligned.plot([t + shift for t in T], Z, style, color=colour,
                         label=(f"{run_['label']}: mean {res['aligned_front_error_mean']:.3f} a,"
                                f" max {res['aligned_front_error_max']:.3f} a"
                                if name == "a225" else None))
    raw.set_ylabel("Z = z / a (surge front)")
    raw.set_title("raw: t = 0 at the gate release\n", fontsize=10)
    aligned.set_title("shifted onto each record's first point\n(solid: the a = 2.25 in record's, "
                      "dashed: the 1.125 in record's)", fontsize=10)
    scatter = runs[0]["result"]
    aligned.text(0.05, 4.45, f"the records against each other: mean "
                 f"{scatter['experiment_scatter_mean']:.3f} a, max "
                 f"{scatter['experiment_scatter_max']:.3f} a", fontsize=8, va="top")
    raw.legend(fontsize=8, loc="lower right")
    aligned.legend(fontsize=8, loc="lower right")
    fig.suptitle("Dam break, column 2a high: surge front (grey: compared window T in [0.8, 3])")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_lobovsky(runs, path):
    H = runs[0]["result"]["H"]
    # The first impact and run-up ends where the record's water lands on the far gauge.
    run_up_end = runs[0]["result"]["run_up_window"][1]
    gauges = {}
    for r in runs[0]["records"]:
        g = gauges.setdefault(r["gauge"], {"x": float(r["x"]), "record": ([], []),
                                           "repeat": ([], [])})
        g[r["series"]][0].append(float(r["t"]))
        g[r["series"]][1].append(float(r["h"]) / H)
    fig, axes = plt.subplots(2, 2, figsize=(11, 7), sharex=True)
    for ax, (name, g) in zip(axes.flat, gauges.items()):
        ax.plot(*g["record"], ".", color="black", ms=4, label="Lobovsky et al. 2014 (compared)")
        if g["repeat"][0]:
            scatter = next(e for e in runs[0]["result"]["gauges"]
                           if e["name"] == name)["experiment_scatter_over_H"]
            ax.plot(*g["repeat"], "x", color="0.45", ms=3,
                    label=f"its other series: mean |dh| {100 * scatter:.1f} % H")
        for run_, colour in zip(runs, COLOURS):
            t = [float(r["t"]) for r in run_["series"]]
            h = [float(r[f"h_{name}"]) / H for r in run_["series"]]
            err = next(e for e in run_["result"]["gauges"] if e["name"] == name)
            ax.plot(t, h, color=colour, lw=1.2,
                    label=f"{run_['label']}: mean |dh| {100 * err['mean_abs_error_over_H']:.1f} % H"
                          f" (run-up {100 * err['mean_abs_error_over_H_run_up']:.1f} %)")
        ax.axvline(0.9, color="0.5", ls=":", lw=1)
        ax.axvline(run_up_end, color="0.3", ls="--", lw=1)
        ax.axvspan(0.0, 1.5, color="0.95", zorder=0)
        ax.set_xlim(0.0, 1.6)
        ax.set_title(f"{name}, x = {g['x']:.4g} m")
        ax.set_ylabel("h / H")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper left")
    for ax in axes[1]:
        ax.set_xlabel("t (s)")
    fig.suptitle("Lobovsky et al. (2014) dam break, H = 0.3 m: water level at the gauges\n(grey: compared "
                 f"window [0, 1.5] s; dotted: 0.9 s; dashed: {run_up_end:.3f} s, the first impact "
                 "and run-up's end)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def moving_average(t, p, half_width):
    """The mean of the samples within half_width of each sample's t (t sorted), as
    swell-validate smooths a wall-pressure series (wall_pressure.h)."""
    out, lo, hi, total = [], 0, 0, 0.0
    for ti in t:
        while hi < len(t) and t[hi] <= ti + half_width:
            total += p[hi]
            hi += 1
        while t[lo] < ti - half_width:
            total -= p[lo]
            lo += 1
        out.append(total / (hi - lo))
    return out


def plot_far_wall_pressure(runs, path):
    """The far wall's pressure at Buchner's sensor P1 against the experiment and Marrone et
    al. (2011)'s delta-SPH (docs/validation.md, Far-wall pressure), every series smoothed the
    same way."""
    refs = {}
    for r in runs[0]["pressure_records"]:
        s = refs.setdefault(r["series"], ([], []))
        s[0].append(float(r["t"]))
        s[1].append(float(r["p"]))
    p1 = runs[0]["result"]["far_wall_pressure"]
    half = p1["smoothing_half_width"]  # the app's rule, so the lines are what it read
    fig, ax = plt.subplots(figsize=(11, 4.8))
    t, p = refs["experiment"]
    ax.plot(t, moving_average(t, p, half), color="black", lw=1.4,
            label=f"Buchner 2002 (experiment): collapse at {p1['experiment']['second_peak_time']:.2f}")
    for name, style in (("delta_sph_40", ":"), ("delta_sph_80", "-."), ("delta_sph_320", "--")):
        t, p = refs[name]
        ref = p1[name]
        ax.plot(t, moving_average(t, p, half), style, color="tab:red", lw=1.1,
                label=f"Marrone et al. 2011, delta-SPH H/{name.rsplit('_', 1)[1]}: collapse at "
                      f"{ref['second_peak_time']:.2f}")
    for run_, colour in zip(runs, COLOURS):
        res = run_["result"]
        scale = (res["gravity"] / res["H"]) ** 0.5
        t = [float(r["t"]) * scale for r in run_["series"]]
        p = [float(r["p_P1_over_rho_g_H"]) for r in run_["series"]]
        own = res["far_wall_pressure"]
        ax.plot(t, p, color=colour, lw=0.4, alpha=0.35)
        ax.plot(t, moving_average(t, p, half), color=colour, lw=1.4,
                label=f"{run_['label']}: collapse at {own['second_peak_time']:.2f}, mean |dp| "
                      f"{own['delta_sph_320']['mean_abs_error']:.3f} against delta-SPH H/320")
    ax.axvspan(*p1["second_peak_window"], color="0.95", zorder=0)
    ax.set_xlim(2.0, 7.4)
    ax.set_ylim(-0.1, 1.2)
    ax.set_xlabel("t sqrt(g / H)")
    ax.set_ylabel("p / (rho g H)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    ax.set_title("Far-wall pressure at sensor P1 (Lobovsky tank, Buchner's tank at half size); "
                 f"every line a {2 * half:g} moving average\n(faint: the runs unsmoothed; "
                 "grey: where the run-up's collapse is looked for)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_solitary(runs, path):
    fig, axes = plt.subplots(len(runs), 1, figsize=(11, 3.0 * len(runs) + 0.6), sharex=True,
                             squeeze=False)
    references = {}
    for ax, run_ in zip(axes[:, 0], runs):
        res = run_["result"]
        H, h, gauges = res["height"], res["depth"], tuple(res["gauges"])
        if (H, h, gauges) not in references:  # the same wave at every resolution: run once
            references[(H, h, gauges)] = sgn_solitary.goring_series(H, h, gauges)
        t_ref, eta_ref = references[(H, h, gauges)]
        t = [float(r["t"]) for r in run_["series"]]
        for g, (crest, colour) in enumerate(zip(res["crests"], GAUGE_COLOURS)):
            x = crest["x"]
            eta = [float(r[f"eta_{x:g}"]) - crest["still_level"] for r in run_["series"]]
            ax.plot(t, eta, color=colour, lw=1.0,
                    label=f"x = {x:g} m: A = {crest['amplitude_over_height']:.2f} H")
            ax.plot(t_ref, eta_ref[:, g], "--", color=colour, lw=0.8)
        ax.set_ylabel("eta - still level (m)")
        ax.set_ylim(-0.15 * H, 1.15 * H)
        ax.grid(alpha=0.3)
        ax.set_title(f"{run_['label']}: celerity {100 * res['celerity_error']:+.1f} % of "
                     f"sqrt(g (h + A)), {100 * res['decay_total']:.1f} % of the crest lost over "
                     f"{res['distance_over_depth']:.0f} h, width {100 * res['mean_width_error']:+.0f} %",
                     fontsize=10)
        ax.legend(fontsize=7, loc="upper right", ncol=5)
    axes[-1, 0].set_xlabel("t (s)")
    axes[-1, 0].set_xlim(1.5, max(float(r["t"]) for r in runs[0]["series"]))
    fig.suptitle("Solitary wave, H / h = 0.2: records (solid) against Goring's wave under the "
                 "SGN equations (dashed)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def stoker_depth(theory, h0, h1, dx, t):
    """Stoker's depth (m) at x - x0 = dx (m), time t (s), from the theory swell-validate reports
    (its bore's speed S, the state (h2, u2) behind it, c0 and c2): the same piecewise solution
    as StokerDamBreak::depth (bake/validation/include/swell/bake/validation/wet_dam_break.h)."""
    if t <= 0.0:
        return h0 if dx < 0.0 else h1
    xi = dx / t
    if xi <= -theory["c0"]:
        return h0
    if xi <= theory["u2"] - theory["c2"]:
        return (2.0 * theory["c0"] - xi) ** 2 / (9.0 * theory["gravity"])
    return theory["h2"] if xi <= theory["bore_speed"] else h1


def plot_wet_dam_break(runs, path):
    gauge_colours = [f"C{k}" for k in range(10)]
    fig, axes = plt.subplots(len(runs), 1, figsize=(12, 3.4 * len(runs) + 0.6), sharex=True,
                             squeeze=False)
    for ax, run_ in zip(axes[:, 0], runs):
        res = run_["result"]
        h0, h1, gate, theory = res["h0"], res["h1"], res["gate"], res["theory"]
        t = [float(r["t"]) for r in run_["series"]]
        for g, colour in zip(res["gauge_records"], gauge_colours * 2):
            x = g["x"]
            h = [float(r[f"h_{x:g}"]) / h0 for r in run_["series"]]
            ax.plot(t, h, color=colour, lw=1.0,
                    label=f"x - x0 = {x - gate:+.2f} m: {100 * g['mean_abs_error_over_h0']:.1f} %")
            # Theory up to the end of the gauge's window, where a reflection may arrive; a bar
            # marks that end.
            t_ref = [k * g["until"] / 400 for k in range(401)]
            h_ref = [stoker_depth(theory, h0, h1, x - gate, s) / h0 for s in t_ref]
            ax.plot(t_ref, h_ref, "--", color=colour, lw=0.8)
            ax.plot([g["until"]], [h_ref[-1]], "|", color=colour, ms=10, mew=1.5)
        ax.axvspan(0.0, res["compared_from"], color="0.93", zorder=0)
        ax.set_ylabel("h / h0")
        ax.set_ylim(0.0, 1.05)
        ax.grid(alpha=0.3)
        plateau = res["plateau_depth_error"]
        ax.set_title(f"{run_['label']}: bore {100 * res['bore_speed_error']:+.1f} % of Stoker's "
                     f"{theory['bore_speed']:.3f} m/s, depth behind it "
                     + (f"{100 * plateau:+.1f} %" if plateau is not None else "not read")
                     + f", worst gauge {100 * res['mean_abs_error_over_h0_worst']:.1f} % of h0",
                     fontsize=10)
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0),
                  title="mean |h - h_Stoker| / h0", title_fontsize=7)
    axes[-1, 0].set_xlabel("t (s)")
    axes[-1, 0].set_xlim(0.0, max(float(r["t"]) for r in runs[0]["series"]))
    res = runs[0]["result"]
    fig.suptitle(f"Dam break onto a wet bed, h1 / h0 = {res['h1_over_h0']:.2g}: depth at the "
                 "gauges (solid) against Stoker's solution\n(dashed, to the end of each gauge's "
                 "window, marked |; grey: before the windows open)", fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_shoaling(runs, path):
    """Each gauge's record (points) and the runs (lines) on the experiment's clock: the run's
    t / sqrt(h0 / g) plus its clock offset (g0's crests aligned), eta over the still level the
    check measured (each gauge's still_level), / h0."""
    gauges = {}
    for r in runs[0]["records"]:
        g = gauges.setdefault(r["gauge"], (float(r["x_over_h0"]), [], []))
        g[1].append(float(r["t"]))
        g[2].append(float(r["eta"]))
    fig, axes = plt.subplots(2, 3, figsize=(13, 7))
    for ax, (name, (x_over_h0, t_rec, eta_rec)) in zip(axes.flat, gauges.items()):
        ax.plot(t_rec, eta_rec, ".", color="black", ms=3, label="Grilli et al. 1994")
        for run_, colour in zip(runs, COLOURS):
            res = run_["result"]
            h0 = res["depth"]
            tau = (h0 / res["gravity"]) ** 0.5
            err = next(e for e in res["gauge_records"] if e["name"] == name)
            column = f"eta_{err['x']:g}"
            t = [float(r["t"]) for r in run_["series"]]
            eta = [float(r[column]) for r in run_["series"]]
            level = err["still_level"]
            ax.plot([s / tau + res["clock_offset"] for s in t], [(e - level) / h0 for e in eta],
                    color=colour, lw=1.1,
                    label=f"{run_['label']}: crest {err['crest_over_h0']:.3f}, "
                          f"mean |d eta| {err['mean_abs_error_over_h0']:.3f}")
        ax.set_xlim(5.0, 25.0) if name == "g0" else ax.set_xlim(36.5, 47.5)
        ax.set_ylim(-0.06, 0.4)
        ax.set_title(f"{name}: {x_over_h0:g} h0 from the toe", fontsize=10)
        ax.set_xlabel("t sqrt(g / h0)")
        ax.set_ylabel("eta / h0")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper left")
    fig.suptitle("Solitary wave H / h0 = 0.2 up a 1:34.7 beach: gauges against Grilli et al. "
                 "(1994) (points), clocks aligned on g0's crest", fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", default=str(ROOT / "build" / "bin"))
    ap.add_argument("--out", default=str(ROOT / "out" / "validation"))
    ap.add_argument("--threads", type=int, default=0, help="swell-validate --threads (0: all)")
    ap.add_argument("--quick", action="store_true",
                    help="CI resolutions only (a/20, H/15, h/10, h0/20 to 1.2 s, h0/10)")
    ap.add_argument("--only", choices=KINDS, action="append",
                    help="this check's plot only (repeatable; default: all five)")
    args = ap.parse_args()
    if args.threads < 0:
        fail(f"--threads {args.threads}: must be 0 (all) or more")
    binary, out = pathlib.Path(args.bin), pathlib.Path(args.out)
    if not (binary / "swell-validate").is_file():
        fail(f"--bin {binary}: no swell-validate there (run tools/build)")
    out.mkdir(parents=True, exist_ok=True)
    # kind -> (its cases, the quick run's, its plot, the plot's file)
    checks = {"dam-break": (DAM_BREAK, DAM_BREAK[:1], plot_dam_break, "dam_break_front.png"),
              "lobovsky": (LOBOVSKY, LOBOVSKY[:1], plot_lobovsky, "lobovsky_gauges.png"),
              "solitary-wave": (SOLITARY, SOLITARY[:1], plot_solitary, "solitary_wave.png"),
              "wet-dam-break": (WET_DAM_BREAK, WET_DAM_BREAK_QUICK, plot_wet_dam_break,
                                "wet_dam_break.png"),
              "shoaling": (SHOALING, SHOALING[:1], plot_shoaling, "shoaling.png")}
    runs, written = [], []
    for kind in KINDS:
        if args.only and kind not in args.only:
            continue
        full, quick, plot, name = checks[kind]
        rs = [run(binary, args.threads, kind, *c, out) for c in (quick if args.quick else full)]
        plot(rs, out / name)
        written.append(str(out / name))
        if kind == "lobovsky":  # and the far wall's pressure from the same runs
            plot_far_wall_pressure(rs, out / "lobovsky_p1.png")
            written.append(str(out / "lobovsky_p1.png"))
        runs += [{"kind": kind, "label": r["label"], "command": r["command"],
                  "result": r["result"]} for r in rs]
    commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip() or "unknown"
    summary = {"commit": commit, "quick": args.quick, "runs": runs}
    (out / "validation_plots.json").write_text(json.dumps(summary, indent=1) + "\n")
    print(f"wrote {', '.join(written)}, {out / 'validation_plots.json'}")


if __name__ == "__main__":
    main()
