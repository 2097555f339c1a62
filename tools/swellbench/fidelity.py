"""Replay fidelity: the replay against the simulated surface (swell-play fidelity) next to its
speed (swell-play bench), over resolution and reconstruction at F = 0 and the mixing error of
F = 0.3 over sigma, on the paper-scale surging bake and surging_small; and continuity: long
replays of the paper-scale bake checked for flat rows and jumps, the default against 0ea46e0's.

CSV: fidelity, continuity; docs sections: fidelity, continuity; plot: replay_fidelity_vs_fps."""

import os

from . import common as bl

CSVS = ("fidelity", "continuity")
SECTIONS = ("fidelity", "continuity")
PLOTS = ("replay_fidelity_vs_fps",)

RECONSTRUCTIONS = ("envelope", "paper")
SIGMA = 2.0  # the sweeps over resolution; sigma itself is swept at 256 x 256, envelope
CONTINUITY_RES = "128x64"
BEFORE = ["--policy", "loop", "--window", "all", "--extent", "domain", "--reconstruction", "paper"]
CONTINUITY_CASES = [("default (seamless, steady window, water, envelope)", [], 600, 50),
                    ("default", [], 60, 5),
                    ("steady window, hard loop", ["--policy", "loop"], 600, 50),
                    ("before (0ea46e0 defaults)", BEFORE, 600, 50),
                    ("before (0ea46e0 defaults)", BEFORE, 60, 5)]


def run(ctx):
    ctx.note_load("fidelity")
    paper = ctx.paper_cache()
    rows = {"fidelity": fidelity(ctx, [("surging (paper scale)", paper), ("surging_small", ctx.cache)])}
    rows["continuity"] = continuity(ctx, paper)
    return rows


def cases(quick):
    """(res, reconstruction, sigma): resolution x reconstruction at sigma 2, then sigma."""
    sizes = [64, 128, 256, 512] if quick else [64, 128, 256, 512, 1024]
    out = [(res, rec, SIGMA) for rec in RECONSTRUCTIONS for res in sizes]
    return out + [(256, "envelope", sg) for sg in (1.0, 4.0)]


def fidelity(ctx, caches):
    """Each cache's own water range and steady window (swell-play's defaults)."""
    frames = 100 if ctx.quick else 300
    rows = []
    for label, cache in caches:
        for res, rec, sigma in cases(ctx.quick):
            common = ["--res", "%dx%d" % (res, res), "--reconstruction", rec, "--sigma", sigma, "--json"]
            f = ctx.run([bl.exe("swell-play"), "fidelity", cache, "--frames", frames,
                         "--mix-times", 4 if ctx.quick else 12] + common, 1800)
            n = 1000 if res <= 256 else 200
            b = ctx.run([bl.exe("swell-play"), "bench", cache, "--frames", n, "--warmup", 10,
                         "--error-frames", 2, "--cpu-frames", 0] + common, 1800)
            rows.append(fidelity_row(label, res, rec, sigma, f, b))
    return rows


def fidelity_row(label, res, rec, sigma, f, b):
    fj, bj = f.json or {}, b.json or {}
    f0, mix = fj.get("f0", {}), fj.get("mixing", {})
    return {"cache": label, "res": res, "reconstruction": rec, "sigma_cells": sigma,
            "fps": bj.get("fps"), "f0_rms_l0": f0.get("rms_l0"),
            "f0_mean_row_max_l0": f0.get("mean_row_max_l0"), "f0_max_l0": f0.get("max_l0"),
            "f0_crest_loss_mean": f0.get("crest_loss_mean"), "f0_crest_loss_max": f0.get("crest_loss_max"),
            "mix_rms_l0": mix.get("rms_l0"), "mix_crest_loss_mean": mix.get("crest_loss_mean"),
            "loop_residual_m": bl.dig(fj, "timeline.loop.residual_m"),
            "outcome": "ok" if f.rc == 0 and b.rc == 0 else "exit %s/%s: %s" % (
                f.rc, b.rc, (f if f.rc else b).last_err_line())}


def continuity(ctx, cache):
    """Long replays at 128 x 64: frames with flat rows (height spread below 5 mm) and the
    largest per-cell change between consecutive frames against the 99.9th percentile of the
    same measure in the steady bake at F = 0; the default against today's-main behaviour
    (whole padded domain, every frame, hard loop, eq. (7) columns)."""
    ctx.note_load("continuity")
    rows = []
    for label, extra, seconds, fps in CONTINUITY_CASES:
        r = ctx.run([bl.exe("swell-play"), "fidelity", cache, "--res", CONTINUITY_RES, "--fps", fps,
                     "--seam-seconds", seconds, "--frames", 0, "--mix-times", 0, "--json"] + extra, 1800)
        c = (r.json or {}).get("continuity", {})
        rows.append({"replay": label, "seconds": seconds, "fps": fps, "frames": c.get("frames"),
                     "frames_with_flat_rows": c.get("frames_with_flat_rows"), "flat_rows": c.get("flat_rows"),
                     "largest_change_m": c.get("largest_change_m"),
                     "steady_f0_change_p999_m": c.get("steady_f0_change_p999_m"),
                     "largest_over_steady_p999": c.get("largest_over_steady_p999"),
                     "outcome": bl.outcome(r)})
    return rows


def machine_line(m):
    return "Machine: %s, %s, %s." % (m.get("cpu"), m.get("renderer"), m.get("date"))


def table(rows, m):
    out = {}
    if rows.get("fidelity") is not None:
        out["fidelity"] = fidelity_table(rows["fidelity"], m)
    if rows.get("continuity") is not None:
        out["continuity"] = continuity_table(rows["continuity"], m)
    return out


def fidelity_table(rows, m):
    pct = lambda k: (lambda r: None if r.get(k) is None else "%.2f %%" % (100 * r[k]))
    t = [machine_line(m),
         "Command: `tools/bench --only fidelity%s`; each row `swell-play fidelity CACHE --res NxN "
         "--reconstruction R --sigma S --json` and `swell-play bench` with the same options. "
         "f0: F = 0 (every slice one frame) against the frame's envelope over the steady window; "
         "mix: F = 0.3, each real slice's row against its own frame; lengths in l0." % bl.quick_flag(m),
         "",
         bl.md_table(rows, [
             ("cache", "cache"), ("N x N", "res"), ("columns", "reconstruction"), ("sigma", "sigma_cells"),
             ("fps", "fps"), ("F=0 RMS / l0", "f0_rms_l0"), ("F=0 row max / l0, mean", "f0_mean_row_max_l0"),
             ("F=0 max / l0, worst", "f0_max_l0"), ("crest loss, mean", pct("f0_crest_loss_mean")),
             ("crest loss, worst", pct("f0_crest_loss_max")), ("F=0.3 RMS / l0", "mix_rms_l0"),
             ("F=0.3 crest loss", pct("mix_crest_loss_mean")), ("outcome", "outcome")]),
         "",
         "![replay fidelity against fps](images/bench/replay_fidelity_vs_fps.png)"]
    return "\n".join(t)


def continuity_table(rows, m):
    t = [machine_line(m),
         "Command: `tools/bench --only fidelity`; each row `swell-play fidelity out/bench/surging.swell "
         "--res %s --fps R --seam-seconds S --frames 0 --mix-times 0 [options]`." % CONTINUITY_RES,
         "",
         bl.md_table(rows, [
             ("replay", "replay"), ("seconds", "seconds"), ("fps", "fps"), ("frames", "frames"),
             ("frames with flat rows", "frames_with_flat_rows"), ("flat rows", "flat_rows"),
             ("largest per-cell change (m)", "largest_change_m"),
             ("steady F=0 99.9th pct (m)", "steady_f0_change_p999_m"),
             ("ratio", "largest_over_steady_p999"), ("outcome", "outcome")])]
    return "\n".join(t)


def plot(rows, out_dir):
    fid = rows.get("fidelity") or []
    series, ann = [], {}
    for label in sorted({r["cache"] for r in fid}):
        for rec in RECONSTRUCTIONS:
            sel = [r for r in fid if r["cache"] == label and r["reconstruction"] == rec
                   and r["sigma_cells"] == SIGMA]
            name = "%s, %s" % (label, rec)
            series.append((name, [r["fps"] for r in sel], [r["f0_rms_l0"] for r in sel]))
            ann[name] = [str(r["res"]) for r in sel]
    bl.plot(os.path.join(out_dir, "replay_fidelity_vs_fps.png"), "Replay against the simulated surface (F = 0)",
            "fps (synced, N x N)", "RMS error / l0", series, logx=True, logy=True, annotate=ann)
