"""Replay accuracy against cost: swell-play bench over resolution, slice count and kernel width
(sigma) on the surging_small bake; fps against the GPU's height error versus the
double-precision CPU reference.

CSV: replay; docs section: replay; plot: replay_fps_vs_error."""

import os

from . import common as bl

CSVS = ("replay",)
SECTIONS = ("replay",)
PLOTS = ("replay_fps_vs_error",)

WARMUP, ERROR_FRAMES, CPU_FRAMES = 10, 4, 1
WINDOW = "[3 dx, 2 dz)"  # eq. (7)'s cut-off, fixed in the shaders
SWEEPS = [("resolution", "N x N, K = 256", "res"), ("slices", "K at 128 x 128", "slices"),
          ("sigma", "sigma at 128 x 128", "sigma_cells")]


def cases(quick):
    out = [("resolution", {"res": res, "K": 256, "sigma": 2.0}) for res in [128, 256, 512, 1024]]
    out += [("slices", {"res": 128, "K": K, "sigma": 2.0}) for K in [64, 128, 256, 512, 1024]]
    sigmas = [1.0, 2.0, 4.0] if quick else [0.5, 1.0, 2.0, 3.0, 4.0]
    out += [("sigma", {"res": 128, "K": 256, "sigma": s}) for s in sigmas]
    return out


def run(ctx):
    ctx.note_load("replay")
    frames = 150 if ctx.quick else 500
    rows = []
    for sweep, c in cases(ctx.quick):
        n = frames if c["res"] <= 256 else max(30, frames // (c["res"] // 128))
        r = ctx.run([bl.exe("swell-play"), "bench", ctx.cache, "--res", "%dx%d" % (c["res"], c["res"]),
                     "--slices", c["K"], "--sigma", c["sigma"], "--frames", n, "--warmup", WARMUP,
                     "--error-frames", ERROR_FRAMES, "--cpu-frames", CPU_FRAMES, "--json"], 900)
        j = r.json or {}
        ctx.renderer = j.get("renderer", ctx.renderer)
        rows.append({"sweep": sweep, "res": c["res"], "slices": c["K"], "sigma_cells": c["sigma"],
                     "window": WINDOW, "precision": "float32", "frames": n,
                     "fps": j.get("fps"), "frame_ms_median": j.get("frame_ms_median"),
                     "frame_ms_p95": j.get("frame_ms_p95"),
                     "max_abs_error_m": j.get("max_abs_error"), "rms_error_m": j.get("rms_error"),
                     "max_rel_error": j.get("max_rel_error"), "frames_exact": j.get("frames_exact"),
                     "cpu_reference_fps": j.get("cpu_reference_fps"), "outcome": bl.outcome(r)})
    return {"replay": rows}


def cache_text(m):
    """The surging_small cache as the run baked it (machine.json), or as the file holds it."""
    f = (m.get("facts") or {}).get("surging_small") or bl.cache_facts()
    if not f.get("frames"):
        return "`scenes/surging_small.json`"
    return "`scenes/surging_small.json`: %s frames, ~%.0f surface particles each" % (
        bl.fmt(f["frames"]), f["surface_mean"] or 0)


def table(rows, m):
    rp = rows["replay"]
    windows = sorted({r["window"] for r in rp if r.get("window")}) or [WINDOW]
    t = [bl.header(m), "",
         "Cache: `out/bench/surging_small.swell` (baked by tools/bench from %s). Command per row: "
         "`swell-play bench CACHE --res NxN --slices K --sigma S --frames F --warmup %d "
         "--error-frames %d --cpu-frames %d --json`. Errors: GPU heights (float32) against the "
         "double-precision CPU reference, every cell of %d frames. The kernel window is fixed at "
         "eq. (7)'s %s cut-off and the GPU path is float32 only (no float16 or "
         "approximate-exp variant is offered), so the kernel sweep varies sigma, the Gaussian's "
         "width inside that window." % (cache_text(m), WARMUP, ERROR_FRAMES, CPU_FRAMES, ERROR_FRAMES,
                                         ", ".join(windows)), "",
         bl.md_table(rp, [
             ("sweep", "sweep"), ("N x N", lambda r: "%d x %d" % (r["res"], r["res"])),
             ("K", "slices"), ("sigma (cells)", "sigma_cells"), ("precision", "precision"),
             ("fps", "fps"), ("frame ms median / p95", lambda r: "%s / %s" % (
                 bl.fmt(r["frame_ms_median"]), bl.fmt(r["frame_ms_p95"]))),
             ("max error (m)", "max_abs_error_m"), ("rms error (m)", "rms_error_m"),
             ("frame choice", lambda r: "exact" if r["frames_exact"] else "DIFFERS"),
             ("CPU ref. fps", "cpu_reference_fps"), ("outcome", "outcome")]), "",
         "![replay fps against error](images/bench/replay_fps_vs_error.png)"]
    return {"replay": "\n".join(t)}


def plot(rows, out_dir):
    rp = rows["replay"]
    series, ann = [], {}
    for sweep, lab, key in SWEEPS:
        sel = [r for r in rp if r["sweep"] == sweep]
        series.append((lab, [r["fps"] for r in sel], [r["max_abs_error_m"] for r in sel]))
        ann[lab] = [str(r[key]) for r in sel]
    bl.plot(os.path.join(out_dir, "replay_fps_vs_error.png"),
            "Replay: fps against max height error vs CPU double reference",
            "fps (synced)", "max |h_GPU - h_CPU| (m)", series, logx=True, logy=True, annotate=ann)
