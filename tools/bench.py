#!/usr/bin/python3
"""Run time against error (issue 8): bake accuracy against cost, replay accuracy against cost,
compression against error and what the skips save. Writes CSV files and PNG plots to
out/bench/ and regenerates the marked tables in docs/BENCHMARKS.md.

Called by tools/bench (which installs and builds first). --quick: fewer and shorter runs
(under ten minutes on the 2-core project VM); the full variant takes longer (see README)."""

import argparse
import json
import math
import os
import statistics
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import benchlib as bl  # noqa: E402
import swell_cache  # noqa: E402

OUT = os.path.join(bl.ROOT, "out", "bench")
SCENES = os.path.join(bl.ROOT, "scenes")
DOC = os.path.join(bl.ROOT, "docs", "BENCHMARKS.md")


def scene(name):
    return os.path.join(SCENES, name)


def sets(d):
    out = []
    for k, v in d.items():
        out += ["--set", "%s=%s" % (k, v)]
    return out


class Bench:
    def __init__(self, quick, log):
        self.quick = quick
        self.log = log
        self.loads = []

    def note_load(self, what):
        self.loads.append((what, bl.load_average(), time.strftime("%H:%M:%S")))

    def run(self, cmd, timeout=900):
        return bl.run(cmd, timeout=timeout, log=self.log)

    # ---------------------------------------------------------------- bake: dam break
    def dam_break(self):
        self.note_load("dam break")
        a = 0.1
        spacings = [10, 20, 40] if self.quick else [10, 20, 40, 50]
        variants = [("textbook", {})]
        tolerances = [1e-6] if self.quick else [1e-3, 1e-4, 1e-6]
        if not self.quick:
            variants += [("gradient_correction", {"solver.gradient_correction": "true"}),
                         ("symmetric, gamma 0.05", {"solver.symmetric_gradient": "true",
                                                    "solver.relaxation": "0.05"})]
        rows = []
        for per in spacings:
            l0 = a / per
            dt = 0.0005 * (l0 / 0.005)
            for vname, vset in variants:
                for tol in tolerances:
                    if (vname != "textbook" or tol != 1e-6) and per not in (20, 40):
                        continue  # variants and tolerances at a/20 and a/40 only
                    if vname != "textbook" and tol != 1e-6:
                        continue
                    s = {"geometry.particle_spacing": "%.6g" % l0, "solver.dt": "%.6g" % dt,
                         "solver.ppe_tolerance": "%g" % tol}
                    s.update(vset)
                    r = self.run([bl.exe("swell-validate"), "--json", "--threads", "1"] + sets(s) +
                                 ["dam-break", scene("dam_break_small.json")])
                    j = r.json or {}
                    steps = j.get("steps") or 0
                    parts = j.get("particles") or 0
                    rows.append({
                        "resolution": "a/%d" % per, "l0_m": l0, "dt_s": dt, "variant": vname,
                        "ppe_tolerance": tol, "particles": parts, "water": j.get("water"),
                        "steps": steps, "outcome": validate_outcome(r, j),
                        "front_error_mean_a": j.get("front_error_mean"),
                        "front_error_max_a": j.get("front_error_max"),
                        "ppe_iterations_mean": j.get("ppe_iterations_mean"),
                        "wall_s": j.get("wall_seconds", r.wall),
                        "us_per_particle_step": us_per_particle_step(j, steps, parts),
                    })
        return rows

    # ---------------------------------------------------------------- bake: still tank
    def still_tank(self):
        self.note_load("still tank")
        H = 0.1
        steps = 2000 if self.quick else 20000
        settle = 1.0 if self.quick else 2.0
        variants = [("textbook", {})]
        if not self.quick:
            variants += [("gradient_correction", {"solver.gradient_correction": "true"}),
                         ("symmetric, gamma 0.05", {"solver.symmetric_gradient": "true",
                                                    "solver.relaxation": "0.05"})]
        rows = []
        for per in [10, 20, 40]:
            l0 = H / per
            for vname, vset in variants:
                if vname != "textbook" and per == 40:
                    continue
                s = {"geometry.particle_spacing": "%.6g" % l0}
                s.update(vset)
                r = self.run([bl.exe("swell-validate"), "--json", "--threads", "1"] + sets(s) +
                             ["still-tank", scene("still_tank_small.json"), "--steps", str(steps),
                              "--settle", str(settle)])
                j = r.json or {}
                n = j.get("steps") or 0
                parts = j.get("particles") or 0
                ratio = j.get("bottom_pressure_ratio")
                rows.append({
                    "resolution": "H/%d" % per, "l0_m": l0, "variant": variant_name(vname),
                    "particles": parts, "water": j.get("water"), "steps": n,
                    "outcome": validate_outcome(r, j),
                    "bed_pressure_ratio": ratio,
                    "pressure_error": abs(ratio - 1.0) if ratio is not None else None,
                    "max_speed_over_sqrt_gH": j.get("max_speed_over_sqrt_gH"),
                    "escaped": j.get("escaped"),
                    "wall_s": j.get("wall_seconds", r.wall),
                    "us_per_particle_step": us_per_particle_step(j, n, parts),
                })
        return rows

    # ---------------------------------------------------------------- bake: regular waves
    def regular_wave(self):
        self.note_load("regular wave")
        spacings = [0.04, 0.02, 0.2 / 15] if self.quick else [0.04, 0.02, 0.2 / 15, 0.01]
        rows = []
        with open(scene("regular_wave_small.json")) as f:
            sc = json.load(f)
        S, T = sc["piston"]["stroke"], sc["piston"]["period"]
        h = sc["geometry"]["water"][0]["y1"] - sc["geometry"]["water"][0]["y0"]
        for l0 in spacings:
            dt = 0.004 if l0 >= 0.04 else 0.002 if l0 >= 0.02 else 0.001  # frames every 20 ms
            s = {"geometry.particle_spacing": repr(l0), "solver.dt": repr(dt)}
            r = self.run([bl.exe("swell-validate"), "--json", "--threads", "1"] + sets(s) +
                         ["regular-wave", scene("regular_wave_small.json")], 3600)
            j = r.json or {}
            hs, he = j.get("heights") or [None], j.get("height_errors") or [None]
            win = j.get("window")
            rows.append({"resolution": "h/%d" % round(h / l0), "l0_m": l0, "dt_s": dt,
                         "particles": (j.get("water") or 0) + (j.get("fixed") or 0) or None,
                         "water": j.get("water"), "steps": j.get("steps"),
                         "outcome": validate_outcome(r, j),
                         "window_s": "%.1f-%.1f" % tuple(win) if win else None,
                         "H_m": hs[0], "height_error": he[0], "theory_H_m": j.get("height_theory"),
                         "L_m": j.get("wavelength"), "wavelength_error": j.get("wavelength_error"),
                         "theory_L_m": j.get("wavelength_theory"),
                         "wall_s": j.get("wall_seconds", r.wall),
                         "us_per_particle_step": j.get("us_per_particle_step"),
                         "source": "swell-validate regular-wave"})
        note = ("`swell-validate --json --threads 1 --set geometry.particle_spacing=L0 --set solver.dt=DT "
                "regular-wave scenes/regular_wave_small.json`: its default fit window (after the ramp "
                "and the wave's arrival, before reflections)")
        note = ("h = %g m, T = %g s, S = %g cm; %s" % (h, T, 100 * S, note))
        return rows, note

    # ---------------------------------------------------------------- replay
    def bake_replay_cache(self):
        cache = os.path.join(OUT, "surging_small.swell")
        r = self.run([bl.exe("swell-bake"), scene("surging_small.json"), "-o", cache, "--threads", "1",
                      "--json", "-q"], 1800)
        if r.rc != 0:
            raise SystemExit("tools/bench: baking surging_small failed: " + r.last_err_line())
        return cache, r.json

    def replay(self, cache):
        self.note_load("replay")
        frames = 150 if self.quick else 500
        cases = []
        for res in [128, 256, 512, 1024]:
            cases.append(("resolution", {"res": res, "K": 256, "sigma": 2.0}))
        for K in [64, 128, 256, 512, 1024]:
            cases.append(("slices", {"res": 128, "K": K, "sigma": 2.0}))
        for sigma in ([1.0, 2.0, 4.0] if self.quick else [0.5, 1.0, 2.0, 3.0, 4.0]):
            cases.append(("sigma", {"res": 128, "K": 256, "sigma": sigma}))
        rows = []
        renderer = None
        for sweep, c in cases:
            n = frames if c["res"] <= 256 else max(30, frames // (c["res"] // 128))
            r = self.run([bl.exe("swell-play"), "bench", cache, "--res", "%dx%d" % (c["res"], c["res"]),
                          "--slices", c["K"], "--sigma", c["sigma"], "--frames", n, "--warmup", 10,
                          "--error-frames", 4, "--cpu-frames", 1, "--json"], 900)
            j = r.json or {}
            renderer = j.get("renderer", renderer)
            rows.append({"sweep": sweep, "res": c["res"], "slices": c["K"], "sigma_cells": c["sigma"],
                         "window": "[3 dx, 2 dz)", "precision": "float32", "frames": n,
                         "fps": j.get("fps"), "frame_ms_median": j.get("frame_ms_median"),
                         "frame_ms_p95": j.get("frame_ms_p95"),
                         "max_abs_error_m": j.get("max_abs_error"), "rms_error_m": j.get("rms_error"),
                         "max_rel_error": j.get("max_rel_error"), "frames_exact": j.get("frames_exact"),
                         "cpu_reference_fps": j.get("cpu_reference_fps"),
                         "outcome": "ok" if r.rc == 0 else "exit %s: %s" % (r.rc, r.last_err_line())})
        return rows, renderer

    # ---------------------------------------------------------------- replay fidelity
    def paper_cache(self):
        """The paper-scale surging bake (scenes/surging.json), baked once into out/bench/."""
        cache = os.path.join(OUT, "surging.swell")
        if not os.path.exists(cache):
            r = self.run([bl.exe("swell-bake"), scene("surging.json"), "-o", cache, "--json", "-q"], 3600)
            if r.rc != 0:
                raise SystemExit("tools/bench: baking surging failed: " + r.last_err_line())
        return cache

    def fidelity(self, caches):
        """The replay against the simulated surface (swell-play fidelity) next to its speed
        (swell-play bench), over resolution and reconstruction at F = 0, and the mixing error
        of F = 0.3 over sigma; each cache's own water range and steady window."""
        self.note_load("fidelity")
        frames = 100 if self.quick else 300
        rows = []
        for label, cache in caches:
            cases = [(res, rec, 2.0) for rec in ("envelope", "paper")
                     for res in ([64, 128, 256, 512] if self.quick else [64, 128, 256, 512, 1024])]
            cases += [(256, "envelope", sg) for sg in (1.0, 4.0)]
            for res, rec, sigma in cases:
                common = ["--res", "%dx%d" % (res, res), "--reconstruction", rec, "--sigma", sigma, "--json"]
                f = self.run([bl.exe("swell-play"), "fidelity", cache, "--frames", frames,
                              "--mix-times", 4 if self.quick else 12] + common, 1800)
                n = 1000 if res <= 256 else 200
                b = self.run([bl.exe("swell-play"), "bench", cache, "--frames", n, "--warmup", 10,
                              "--error-frames", 2, "--cpu-frames", 0] + common, 1800)
                fj, bj = f.json or {}, b.json or {}
                f0, mix = fj.get("f0", {}), fj.get("mixing", {})
                rows.append({"cache": label, "res": res, "reconstruction": rec, "sigma_cells": sigma,
                             "fps": bj.get("fps"), "f0_rms_l0": f0.get("rms_l0"),
                             "f0_mean_row_max_l0": f0.get("mean_row_max_l0"), "f0_max_l0": f0.get("max_l0"),
                             "f0_crest_loss_mean": f0.get("crest_loss_mean"),
                             "f0_crest_loss_max": f0.get("crest_loss_max"),
                             "mix_rms_l0": mix.get("rms_l0"), "mix_crest_loss_mean": mix.get("crest_loss_mean"),
                             "loop_residual_m": ((fj.get("timeline") or {}).get("loop") or {}).get("residual_m"),
                             "outcome": "ok" if f.rc == 0 and b.rc == 0 else "exit %s/%s: %s" % (
                                 f.rc, b.rc, (f if f.rc else b).last_err_line())})
        return rows

    def continuity(self, cache):
        """Long replays of the paper-scale bake at 128 x 64: frames with flat rows (height spread
        below 5 mm) and the largest per-cell change between consecutive frames against the
        99.9th percentile of the same measure in the steady bake at F = 0; the default against
        today's-main behaviour (whole padded domain, every frame, hard loop, eq. (7) columns)."""
        self.note_load("continuity")
        old = ["--policy", "loop", "--window", "all", "--extent", "domain", "--reconstruction", "paper"]
        cases = [("default (seamless, steady window, water, envelope)", [], 600, 50),
                 ("default", [], 60, 5),
                 ("steady window, hard loop", ["--policy", "loop"], 600, 50),
                 ("before (0ea46e0 defaults)", old, 600, 50),
                 ("before (0ea46e0 defaults)", old, 60, 5)]
        rows = []
        for label, extra, seconds, fps in cases:
            r = self.run([bl.exe("swell-play"), "fidelity", cache, "--res", "128x64", "--fps", fps,
                          "--seam-seconds", seconds, "--frames", 0, "--mix-times", 0, "--json"] + extra, 1800)
            c = (r.json or {}).get("continuity", {})
            rows.append({"replay": label, "seconds": seconds, "fps": fps, "frames": c.get("frames"),
                         "frames_with_flat_rows": c.get("frames_with_flat_rows"), "flat_rows": c.get("flat_rows"),
                         "largest_change_m": c.get("largest_change_m"),
                         "steady_f0_change_p999_m": c.get("steady_f0_change_p999_m"),
                         "largest_over_steady_p999": c.get("largest_over_steady_p999"),
                         "outcome": "ok" if r.rc == 0 else "exit %s: %s" % (r.rc, r.last_err_line())})
        return rows

    # ---------------------------------------------------------------- render (issue 7)
    def render(self, cache):
        """Shaded frames per second (swell-play render, Sec. 5) with the cost of each stage: the
        synthetic stress cache (20 real splash particles per frame, 35,840 sprites before
        culling) with and without splashes at 1280 x 720 and 640 x 360, and the surging_small
        bake (its own few splashes). Runs interleaved, rep by rep, so drift hits every case."""
        self.note_load("render")
        synth = os.path.join(OUT, "render_synth.swell")
        r = self.run([bl.exe("swell-cache"), "synth", synth, "--frames", 120, "--surface", 400,
                      "--splash", 20], 300)
        if r.rc != 0:
            raise SystemExit("tools/bench: swell-cache synth failed: " + r.last_err_line())
        reps = 2 if self.quick else 5
        rdir = os.path.join(OUT, "render_frames")
        cases = [("synthetic, 20 splash particles/frame", synth, "1280x720", []),
                 ("synthetic", synth, "1280x720", ["--no-splashes"]),
                 ("synthetic, 20 splash particles/frame", synth, "640x360", []),
                 ("synthetic", synth, "640x360", ["--no-splashes"]),
                 ("surging_small bake", cache, "1280x720", [])]
        runs = [[] for _ in cases]
        errors = [None for _ in cases]
        for _ in range(reps):
            for i, (_, c, size, extra) in enumerate(cases):
                r = self.run([bl.exe("swell-play"), "render", c, "--out", rdir, "--size", size,
                              "--seconds", 4, "--json"] + extra, 600)
                if r.rc == 0 and r.json:
                    runs[i].append(r.json)
                else:
                    errors[i] = "exit %s: %s" % (r.rc, r.last_err_line())
        rows = []
        for (label, _, size, extra), js, err in zip(cases, runs, errors):
            med = lambda f: statistics.median(f(j) for j in js) if js else None
            stage = lambda k: med(lambda j: j["stage_gpu_ms"][k])
            timing = lambda k: med(lambda j: j["timing_ms_per_frame"][k])
            fps = [j["shaded_fps"] for j in js]
            rows.append({
                "cache": label, "size": size.replace("x", " x "),
                "splashes": "no" if extra else "yes", "runs": len(js),
                "fps_median": med(lambda j: j["shaded_fps"]),
                "fps_min": min(fps) if fps else None, "fps_max": max(fps) if fps else None,
                "frame_ms": timing("draw_synced"), "cpu_ms": timing("draw_cpu"),
                "sky_ms": stage("sky"), "water_ms": stage("water"), "splash_ms": stage("splashes"),
                "replay_ms": med(lambda j: j["stage_gpu_ms"]["slice_lookup"] +
                                 j["stage_gpu_ms"]["reconstruct"]),
                "sprites_cpu_ms": timing("splash_sprites_cpu"),
                "sprites_drawn": med(lambda j: j["splash"]["sprites_mean"] -
                                     j["splash"]["culled_under_water_mean"]),
                "readback_ms": timing("readback"), "png_ms": timing("png_write"),
                "llvmpipe_threads": js[0].get("llvmpipe_threads") if js else None,
                "outcome": err or "ok"})
        os.remove(synth)
        return rows

    # ---------------------------------------------------------------- compression
    def compression(self, cache):
        self.note_load("compression")
        ref = swell_cache.Cache(cache)
        ref_frames = [ref.frame(i) for i in range(len(ref))]
        rows = []
        for enc, flags in [("float32", []), ("float32", ["--no-shuffle", "--no-delta"]),
                           ("quantized16", []), ("quantized16", ["--no-shuffle", "--no-delta"])]:
            name = "%s%s" % (enc, "_nofilter" if flags else "")
            path = os.path.join(OUT, "surging_small.%s.swell" % name)
            r = self.run([bl.exe("swell-cache"), "recode", cache, path, "--encoding", enc] + flags, 300)
            if r.rc != 0:
                rows.append({"encoding": name, "outcome": r.last_err_line()})
                continue
            c = swell_cache.Cache(path)
            dmax, dsq, count = 0.0, 0.0, 0
            for i in range(len(c)):
                s, sp = c.frame(i)
                s0, sp0 = ref_frames[i]
                a = np.array(s + [p[:2] for p in sp], dtype=float).reshape(-1, 2)
                b = np.array(s0 + [p[:2] for p in sp0], dtype=float).reshape(-1, 2)
                if a.size:
                    d = np.abs(a - b)
                    dmax = max(dmax, float(d.max()))
                    dsq += float((d ** 2).sum())
                    count += d.size
            b = self.run([bl.exe("swell-play"), "bench", path, "--reference-cache", cache, "--frames", 50,
                          "--warmup", 5, "--error-frames", 16, "--cpu-frames", 0, "--json"], 600)
            j = b.json or {}
            rows.append({"encoding": enc, "filters": "none" if flags else "shuffle + delta",
                         "bytes": os.path.getsize(path),
                         "ratio_vs_float32_default": os.path.getsize(cache) / os.path.getsize(path),
                         "max_position_error_m": dmax,
                         "rms_position_error_m": math.sqrt(dsq / count) if count else 0.0,
                         "header_max_position_error_m": c.max_position_error,
                         "max_height_error_m": j.get("max_abs_error"),
                         "rms_height_error_m": j.get("rms_error"),
                         "outcome": "ok" if b.rc == 0 else "exit %s: %s" % (b.rc, b.last_err_line())})
            if path != cache:
                os.remove(path)
        return rows

    # ---------------------------------------------------------------- skips
    def skips(self, cache, bake_summary):
        self.note_load("skips")
        rows = []
        reps = 3 if self.quick else 5

        def median_of(cmd, key, n=reps, timeout=600):
            vals, last = [], None
            for _ in range(n):
                r = self.run(cmd, timeout)
                last = r
                if r.json and r.json.get(key) is not None:
                    vals.append(r.json[key])
            return (float(np.median(vals)) if vals else None), last

        # Bake: deep particles never stored.
        s = bake_summary
        all_raw = s["particles_water"] * 8 * s["frames"]
        full = os.path.join(OUT, "surging_small_all_water.swell")
        r = self.run([bl.exe("swell-bake"), scene("surging_small.json"), "-o", full, "--threads", "1",
                      "--json", "-q", "--set", "output.surface_ratio=1.0"], 1800)
        jf = r.json or {}
        rows.append({"stage": "bake", "skip": "deep particles never stored",
                     "with_skip": "%s B cache (%.0f particles/frame, %s B raw)" % (
                         bl.fmt(s["cache_bytes"]), s["kept_mean"], bl.fmt(s["raw_bytes"])),
                     "without": "%s B raw for all %d water particles; storing every water particle with "
                                "n <= n0 (surface_ratio 1.0): %s B cache, %.0f particles/frame" % (
                                    bl.fmt(all_raw), s["particles_water"], bl.fmt(jf.get("cache_bytes")),
                                    jf.get("kept_mean") or 0),
                     "saves": "%.1fx raw bytes; %.1fx cache bytes against surface_ratio 1.0" % (
                         all_raw / s["raw_bytes"], (jf.get("cache_bytes") or 0) / s["cache_bytes"]),
                     "command": "swell-bake scenes/surging_small.json [--set output.surface_ratio=1.0]"})
        if os.path.exists(full):
            os.remove(full)
        # Bake: classification only on stored frames (store every step instead of every 10th).
        every = os.path.join(OUT, "surging_small_every_step.swell")
        base_w, every_w = [], []
        for _ in range(2 if self.quick else 3):
            r1 = self.run([bl.exe("swell-bake"), scene("surging_small.json"), "-o", every, "--threads", "1",
                           "--json", "-q", "--set", "solver.end_time=1.0"], 1800)
            r2 = self.run([bl.exe("swell-bake"), scene("surging_small.json"), "-o", every, "--threads", "1",
                           "--json", "-q", "--set", "solver.end_time=1.0", "--set",
                           "output.frame_interval=0.002"], 1800)
            if r1.json and r2.json:
                base_w.append(r1.json["wall_seconds"] - r1.json["ms_per_step"] * r1.json["steps"] / 1e3)
                every_w.append(r2.json["wall_seconds"] - r2.json["ms_per_step"] * r2.json["steps"] / 1e3)
        if os.path.exists(every):
            os.remove(every)
        if base_w:
            b, e = float(np.median(base_w)), float(np.median(every_w))
            rows.append({"stage": "bake", "skip": "classification (and writing) only on stored frames",
                         "with_skip": "%.3f s outside the solver for 500 steps, 51 frames" % b,
                         "without": "%.3f s with a frame every step (501 frames)" % e,
                         "saves": "%.2f ms per unstored step (%.0f%% of the %.2f ms solver step)" % (
                             1e3 * (e - b) / 450, 100 * (e - b) / 450 / (s["ms_per_step"] / 1e3),
                             s["ms_per_step"]),
                         "command": "swell-bake scenes/surging_small.json --set solver.end_time=1.0 "
                                    "[--set output.frame_interval=0.002]"})
        # Bake: no splash records when none (an empty splash section is a count of 0).
        sizes = {}
        for n in (0, 1):
            p = os.path.join(OUT, "synth_splash%d.swell" % n)
            self.run([bl.exe("swell-cache"), "synth", p, "--frames", 1200, "--surface", 175, "--splash", n], 120)
            sizes[n] = os.path.getsize(p)
            os.remove(p)
        rows.append({"stage": "bake/cache", "skip": "no splash records when none",
                     "with_skip": "%s B for 1,200 frames without splash particles" % bl.fmt(sizes[0]),
                     "without": "%s B with one splash particle per frame" % bl.fmt(sizes[1]),
                     "saves": "%.1f B per frame (%.1f%%)" % ((sizes[1] - sizes[0]) / 1200,
                                                            100 * (sizes[1] - sizes[0]) / sizes[1]),
                     "command": "swell-cache synth F --frames 1200 --surface 175 --splash 0|1"})
        # Replay: A/B pairs, interleaved so that both sides see the same load.
        def ab(cmd_a, cmd_b, keys, n=2 * reps):
            va, vb = {k: [] for k in keys}, {k: [] for k in keys}
            for _ in range(n):
                for cmd, into in ((cmd_a, va), (cmd_b, vb)):
                    r = self.run(cmd, 600)
                    for k in keys:
                        v = r.json
                        for part in k.split("."):
                            v = v.get(part) if isinstance(v, dict) else None
                        if v is not None:
                            into[k].append(v)
            med = lambda v: float(np.median(v)) if v else None
            return {k: med(v) for k, v in va.items()}, {k: med(v) for k, v in vb.items()}

        def saving(a, b, unit="ms/frame"):
            if a is None or b is None:
                return "-"
            return "%.3f %s (%.0f%%)" % (b - a, unit, 100 * (b - a) / b) if b else "-"

        base = [bl.exe("swell-play"), "bench", cache, "--frames", 300, "--warmup", 20, "--error-frames", 1,
                "--cpu-frames", 0, "--json"]
        keys = ["frame_ms_median", "stage_gpu_ms.slice_lookup", "upload_ms"]
        f0, f3 = ab(base + ["-F", "0"], base + ["-F", "0.3"], keys)
        rows.append({"stage": "replay", "skip": "no noise when F = 0 (no fBm noise built, no noise "
                                                "lookup in the slice-lookup pass)",
                     "with_skip": "slice lookup %s ms GPU, frame %s ms, set-up %s ms (F = 0)" % (
                         bl.fmt(f0["stage_gpu_ms.slice_lookup"]), bl.fmt(f0["frame_ms_median"]),
                         bl.fmt(f0["upload_ms"])),
                     "without": "slice lookup %s ms GPU, frame %s ms, set-up %s ms (F = 0.3)" % (
                         bl.fmt(f3["stage_gpu_ms.slice_lookup"]), bl.fmt(f3["frame_ms_median"]),
                         bl.fmt(f3["upload_ms"])),
                     "saves": "slice lookup: %s; whole frame: %s" % (
                         saving(f0["stage_gpu_ms.slice_lookup"], f3["stage_gpu_ms.slice_lookup"], "ms"),
                         saving(f0["frame_ms_median"], f3["frame_ms_median"], "ms")),
                     "command": "swell-play bench CACHE -F 0|0.3 --frames 300 (interleaved)"})
        a0, a1 = ab(base + ["--mode", "ripple", "--angles", "0"], base + ["--mode", "ripple", "--angles", "0.001"],
                    ["frame_ms_median", "stage_gpu_ms.synthesis"])
        rows.append({"stage": "replay", "skip": "no synthesis pass for one unrotated direction",
                     "with_skip": "%s ms/frame (--angles 0)" % bl.fmt(a0["frame_ms_median"]),
                     "without": "%s ms/frame (--angles 0.001; synthesis pass %s ms GPU)" % (
                         bl.fmt(a1["frame_ms_median"]), bl.fmt(a1["stage_gpu_ms.synthesis"])),
                     "saves": saving(a0["frame_ms_median"], a1["frame_ms_median"]),
                     "command": "swell-play bench CACHE --mode ripple --angles 0|0.001 (interleaved)"})
        # Render: the splash pass skips itself for frames without splash particles.
        sp0, sp8 = os.path.join(OUT, "synth_splash0.swell"), os.path.join(OUT, "synth_splash8.swell")
        for p, n in ((sp0, 0), (sp8, 8)):
            self.run([bl.exe("swell-cache"), "synth", p, "--frames", 1200, "--surface", 400, "--splash", n], 300)
        rdir = os.path.join(OUT, "render_skip")
        rend = lambda c, extra=(): [bl.exe("swell-play"), "render", c, "--out", rdir, "--size", "320x180",
                                    "--seconds", "1", "--json"] + list(extra)
        rk = ["shaded_fps", "stage_gpu_ms.splashes", "timing_ms_per_frame.draw_synced",
              "timing_ms_per_frame.splash_sprites_cpu"]
        r0, r8 = ab(rend(sp0), rend(sp8), rk, n=reps)
        rows.append({"stage": "replay/render", "skip": "no splash pass without splashes",
                     "with_skip": "%s ms/frame drawn (no splash particles: pass skipped)" % bl.fmt(
                         r0["timing_ms_per_frame.draw_synced"]),
                     "without": "%s ms/frame drawn with 8 splash particles per frame (14,336 sprites; "
                                "splash pass %s ms GPU, sprites built on the CPU %s ms)" % (
                                    bl.fmt(r8["timing_ms_per_frame.draw_synced"]),
                                    bl.fmt(r8["stage_gpu_ms.splashes"]),
                                    bl.fmt(r8["timing_ms_per_frame.splash_sprites_cpu"])),
                     "saves": saving(r0["timing_ms_per_frame.draw_synced"], r8["timing_ms_per_frame.draw_synced"]),
                     "command": "swell-play render synth_splash0|8.swell --size 320x180 --seconds 1 (interleaved)"})
        # Readback: bench and the on-screen part of render never read back; output does.
        rb = self.run([bl.exe("swell-play"), "render", sp0, "--out", rdir, "--size", "1280x720", "--seconds",
                       "0.2", "--json"], 600)
        fb, _ = median_of(base, "frame_ms_median")
        rbj = (rb.json or {}).get("timing_ms_per_frame", {})
        rows.append({"stage": "replay", "skip": "no readback without output (the height field and the "
                                                "picture stay on the GPU unless written)",
                     "with_skip": "%s ms/frame (bench, 128 x 128, no readback)" % bl.fmt(fb),
                     "without": "readback of a 1280 x 720 picture %s ms/frame, its PNG %s ms/frame" % (
                         bl.fmt(rbj.get("readback")), bl.fmt(rbj.get("png_write"))),
                     "saves": "%s ms/frame of readback (+ %s ms PNG) when nothing is written" % (
                         bl.fmt(rbj.get("readback")), bl.fmt(rbj.get("png_write"))),
                     "command": "swell-play bench CACHE; swell-play render synth_splash0.swell --size 1280x720 "
                                "--seconds 0.2"})
        for p in (sp0, sp8):
            os.remove(p)
        # Replay: frames never selected are never decoded.
        synth = os.path.join(OUT, "synthetic.swell")
        self.run([bl.exe("swell-cache"), "synth", synth, "--frames", 1200, "--surface", 400], 300)
        short, lshort = median_of([bl.exe("swell-play"), "bench", synth, "--frames", 30, "--warmup", 0,
                                   "--error-frames", 1, "--cpu-frames", 0, "--json"], "decode_ms")
        long_, llong = median_of([bl.exe("swell-play"), "bench", synth, "--frames", 1000, "--warmup", 0,
                                  "--error-frames", 1, "--cpu-frames", 0, "--json"], "decode_ms")
        if lshort and lshort.json and llong and llong.json:
            rows.append({"stage": "replay", "skip": "frames never selected are never decoded",
                         "with_skip": "%d of %d frames decoded in %.1f ms (1 s of playback)" % (
                             lshort.json["frames_decoded"], lshort.json["frames_in_cache"], short),
                         "without": "%d frames decoded in %.1f ms (33 s of playback, loops over the cache)" % (
                             llong.json["frames_decoded"], long_),
                         "saves": "%.1f ms and %.0f%% of the frame memory at start-up" % (
                             long_ - short,
                             100 * (1 - lshort.json["frames_decoded"] / llong.json["frames_decoded"])),
                         "command": "swell-play bench out/bench/synthetic.swell --frames 30|1000 --warmup 0"})
        os.remove(synth)
        return rows


def validate_outcome(r, j):
    """The outcome a swell-validate run reports, or its exit status and last error line."""
    return j.get("outcome", "exit %s: %s" % (r.rc, r.last_err_line()))


def us_per_particle_step(j, steps, particles):
    """Solver time per step and particle (us) of a swell-validate run, None if it did not run."""
    return 1e6 * j["solver_seconds"] / steps / particles if steps and particles else None


def variant_name(v):
    return v


def read_csv(path):
    """Rows of an earlier run's CSV with numbers parsed back (empty: None)."""
    import csv
    if not os.path.exists(path):
        return []
    out = []
    with open(path) as f:
        for r in csv.DictReader(f):
            row = {}
            for k, v in r.items():
                if v == "":
                    row[k] = None
                    continue
                try:
                    row[k] = int(v)
                except ValueError:
                    try:
                        row[k] = float(v)
                    except ValueError:
                        row[k] = {"True": True, "False": False}.get(v, v)
            out.append(row)
    return out


def load_note():
    try:
        with open(os.path.join(OUT, "regular_wave.note")) as f:
            return f.read().strip()
    except OSError:
        return ""


def save_note(note):
    with open(os.path.join(OUT, "regular_wave.note"), "w") as f:
        f.write(note)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="fewer, shorter runs (< 10 min)")
    ap.add_argument("--only", default="",
                    help="comma list of sections: bake (or dam_break, still_tank, regular_wave), replay, "
                         "fidelity, compression, skips, render")
    ap.add_argument("--no-docs", action="store_true", help="do not rewrite docs/BENCHMARKS.md")
    args = ap.parse_args()
    only = set(filter(None, args.only.split(",")))
    want = lambda s: not only or s in only
    os.makedirs(OUT, exist_ok=True)
    t_start = time.monotonic()
    log = open(os.path.join(OUT, "commands.log"), "w")
    b = Bench(args.quick, log)
    b.note_load("start")
    variant = "quick" if args.quick else "full"
    results = {}
    print("tools/bench (%s): load average %s; log out/bench/commands.log" % (variant, bl.load_average()),
          flush=True)

    cache, bake_summary = b.bake_replay_cache()
    rw_note = ""
    if want("bake") or want("dam_break"):
        print("== bake: dam break", flush=True)
        results["dam_break"] = b.dam_break()
    if want("bake") or want("still_tank"):
        print("== bake: still tank", flush=True)
        results["still_tank"] = b.still_tank()
    if want("bake") or want("regular_wave"):
        print("== bake: regular waves", flush=True)
        results["regular_wave"], rw_note = b.regular_wave()
    bake_parts = ("dam_break", "still_tank", "regular_wave")
    if any(k in results for k in bake_parts):
        # A partial rerun (--only regular_wave) keeps the other bake tables from the last run.
        for k in bake_parts:
            if k not in results:
                results[k] = read_csv(os.path.join(OUT, k + ".csv"))
        if not rw_note:
            rw_note = load_note()
        save_note(rw_note)
    renderer = None
    if want("replay"):
        print("== replay sweeps", flush=True)
        results["replay"], renderer = b.replay(cache)
    if want("fidelity"):
        print("== replay fidelity", flush=True)
        results["fidelity"] = b.fidelity([("surging (paper scale)", b.paper_cache()),
                                          ("surging_small", cache)])
        results["continuity"] = b.continuity(b.paper_cache())
    if want("compression"):
        print("== compression", flush=True)
        results["compression"] = b.compression(cache)
    if want("skips"):
        print("== skips", flush=True)
        results["skips"] = b.skips(cache, bake_summary)
    if want("render"):
        print("== render", flush=True)
        results["render"] = b.render(cache)
    b.note_load("end")
    if renderer is None:
        r = bl.run([bl.exe("swell-play"), "bench", cache, "--frames", 5, "--warmup", 0, "--error-frames", 1,
                    "--cpu-frames", 0, "--json"], 120)
        renderer = (r.json or {}).get("renderer")
    m = bl.machine(renderer)
    m["variant"] = variant
    m["total_minutes"] = round((time.monotonic() - t_start) / 60, 1)
    m["loads"] = b.loads
    with open(os.path.join(OUT, "machine.json"), "w") as f:
        json.dump(m, f, indent=1)
    for name, rows in results.items():
        bl.write_csv(os.path.join(OUT, name + ".csv"), rows)
    plots(results)
    if not args.no_docs:
        docs(results, m, rw_note)
        import shutil
        img = os.path.join(bl.ROOT, "docs", "images", "bench")
        os.makedirs(img, exist_ok=True)
        for n in ("bake_error_vs_cost", "replay_fps_vs_error", "replay_fidelity_vs_fps",
                  "compression_vs_error"):
            if os.path.exists(os.path.join(OUT, n + ".png")):
                shutil.copy(os.path.join(OUT, n + ".png"), os.path.join(img, n + ".png"))
    print("tools/bench: done in %.1f min; CSV and PNG in out/bench/%s" % (
        m["total_minutes"], "" if args.no_docs else ", tables in docs/BENCHMARKS.md"), flush=True)


def plots(res):
    P = lambda n: os.path.join(OUT, n)
    if "dam_break" in res:
        tb = [r for r in res["dam_break"] if r["variant"] == "textbook" and r["ppe_tolerance"] == 1e-6]
        st = [r for r in res.get("still_tank", []) if r["variant"] == "textbook"]
        rw = res.get("regular_wave", [])
        bl.plot(P("bake_error_vs_cost.png"), "Bake accuracy against cost (textbook MPS)",
                "wall time of the run (s)", "relative error",
                [("dam-break front: mean |dZ| / a", [r["wall_s"] for r in tb],
                  [r["front_error_mean_a"] for r in tb]),
                 ("still tank: |bed pressure / rho g H - 1|", [r["wall_s"] for r in st],
                  [r["pressure_error"] for r in st]),
                 ("regular wave: |H / H_Biesel - 1|", [r["wall_s"] for r in rw],
                  [abs(r["height_error"]) if r.get("height_error") is not None else None for r in rw])],
                logx=True, logy=True,
                annotate={"dam-break front: mean |dZ| / a": [r["resolution"] for r in tb],
                          "still tank: |bed pressure / rho g H - 1|": [r["resolution"] for r in st],
                          "regular wave: |H / H_Biesel - 1|": [r["resolution"] for r in rw]})
    if "replay" in res:
        rp = res["replay"]
        series = []
        ann = {}
        for sweep, lab, key in [("resolution", "N x N, K = 256", "res"), ("slices", "K at 128 x 128", "slices"),
                                ("sigma", "sigma at 128 x 128", "sigma_cells")]:
            rows = [r for r in rp if r["sweep"] == sweep]
            series.append((lab, [r["fps"] for r in rows], [r["max_abs_error_m"] for r in rows]))
            ann[lab] = [str(r[key]) for r in rows]
        bl.plot(P("replay_fps_vs_error.png"), "Replay: fps against max height error vs CPU double reference",
                "fps (synced)", "max |h_GPU - h_CPU| (m)", series, logx=True, logy=True, annotate=ann)
    if "fidelity" in res:
        series, ann = [], {}
        for label in sorted({r["cache"] for r in res["fidelity"]}):
            for rec in ("envelope", "paper"):
                rows = [r for r in res["fidelity"] if r["cache"] == label and r["reconstruction"] == rec
                        and r["sigma_cells"] == 2.0]
                name = "%s, %s" % (label, rec)
                series.append((name, [r["fps"] for r in rows], [r["f0_rms_l0"] for r in rows]))
                ann[name] = [str(r["res"]) for r in rows]
        bl.plot(P("replay_fidelity_vs_fps.png"), "Replay against the simulated surface (F = 0)",
                "fps (synced, N x N)", "RMS error / l0", series, logx=True, logy=True, annotate=ann)
    if "compression" in res:
        c = [r for r in res["compression"] if "bytes" in r]
        bl.plot(P("compression_vs_error.png"), "Cache size against height error (surging_small bake)",
                "cache bytes", "max height error (m), 1e-9 = exact",
                [("max height error", [r["bytes"] for r in c],
                  [max(r["max_height_error_m"] or 0, 1e-9) for r in c]),
                 ("max position error", [r["bytes"] for r in c],
                  [max(r["max_position_error_m"], 1e-9) for r in c])],
                logy=True, annotate={"max height error": ["%s %s" % (r["encoding"], r["filters"]) for r in c]})


def docs(res, m, rw_note):
    head = ("Generated by `tools/bench%s` on %s: %s, %d cores, %s GiB; %s; renderer %s; commit %s. "
            "Load average %s at the start (other engineers' builds share the machine: wall times "
            "are upper bounds). The whole run took %.1f min. CSV and plots: `out/bench/`." % (
                " --quick" if m["variant"] == "quick" else "", m["date"], m["cpu"], m["cores"],
                m["memory_gib"], m["os"], m["renderer"], m["commit"], m["loads"][0][1],
                m["total_minutes"]))
    loads = "; ".join("%s %s (%s)" % (w, l, t) for w, l, t in m["loads"])
    if "dam_break" in res:
        t = [head, "", "Load average by section: " + loads + ".", "",
             "**Dam break against Martin & Moyce** (`swell-validate --json --threads 1 --set "
             "geometry.particle_spacing=L0 --set solver.dt=DT [--set ...] dam-break "
             "scenes/dam_break_small.json`; dt = 0.5 ms x l0 / 5 mm; error over T in [0.8, 3.0] "
             "in units of a; time per particle-step = solver time / steps / all particles):", "",
             bl.md_table(res["dam_break"], [
                 ("resolution", "resolution"), ("variant", "variant"), ("PPE tol.", "ppe_tolerance"),
                 ("particles", "particles"), ("steps", "steps"), ("outcome", lambda r: r["outcome"][:60]),
                 ("mean abs dZ (a)", "front_error_mean_a"), ("max abs dZ (a)", "front_error_max_a"),
                 ("PPE iter.", "ppe_iterations_mean"), ("wall s", "wall_s"),
                 ("us / particle-step", "us_per_particle_step")]), "",
             "**Still tank** (`swell-validate --json --threads 1 --set geometry.particle_spacing=L0 "
             "still-tank scenes/still_tank_small.json --steps N --settle S`; H = 0.1 m, dt = 1 ms; "
             "pressure error = |bed pressure / rho g H - 1|):", "",
             bl.md_table(res["still_tank"], [
                 ("resolution", "resolution"), ("variant", "variant"), ("particles", "particles"),
                 ("steps", "steps"), ("outcome", lambda r: r["outcome"][:60]),
                 ("bed p / rho g H", "bed_pressure_ratio"), ("pressure error", "pressure_error"),
                 ("max speed / sqrt(gH)", "max_speed_over_sqrt_gH"), ("wall s", "wall_s"),
                 ("us / particle-step", "us_per_particle_step")]), "",
             "**Regular waves against Biesel** (`scenes/regular_wave_small.json` with its other "
             "settings; dt 4, 2, 1 ms at l0 >= 40, >= 20, below 20 mm; H at the first gauge "
             "(x = 0.5 m = 2.5 h), L from the phase lag between the first two gauges; %s):" % rw_note, "",
             bl.md_table(res["regular_wave"], [
                 ("resolution", "resolution"), ("particles", "particles"), ("steps", "steps"),
                 ("outcome", lambda r: r["outcome"][:60]), ("window s", "window_s"),
                 ("H (m)", "H_m"), ("H Biesel (m)", "theory_H_m"), ("H error", "height_error"),
                 ("L (m)", "L_m"), ("L theory (m)", "theory_L_m"), ("L error", "wavelength_error"),
                 ("wall s", "wall_s"), ("us / particle-step", "us_per_particle_step")]), "",
             "![bake error against cost](images/bench/bake_error_vs_cost.png)"]
        bl.replace_section(DOC, "bake", "\n".join(t))
    if "replay" in res:
        t = [head, "",
             "Cache: `out/bench/surging_small.swell` (baked by tools/bench from "
             "`scenes/surging_small.json`: 151 frames, ~77 surface particles each). Command per row: "
             "`swell-play bench CACHE --res NxN --slices K --sigma S --frames F --warmup 10 "
             "--error-frames 4 --cpu-frames 1 --json`. Errors: GPU heights (float32) against the "
             "double-precision CPU reference, every cell of 4 frames. The kernel window is fixed at "
             "eq. (7)'s [3 dx, 2 dz) cut-off and the GPU path is float32 only (no float16 or "
             "approximate-exp variant is offered), so the kernel sweep varies sigma, the Gaussian's "
             "width inside that window.", "",
             bl.md_table(res["replay"], [
                 ("sweep", "sweep"), ("N x N", lambda r: "%d x %d" % (r["res"], r["res"])),
                 ("K", "slices"), ("sigma (cells)", "sigma_cells"), ("precision", "precision"),
                 ("fps", "fps"), ("frame ms median / p95", lambda r: "%s / %s" % (
                     bl.fmt(r["frame_ms_median"]), bl.fmt(r["frame_ms_p95"]))),
                 ("max error (m)", "max_abs_error_m"), ("rms error (m)", "rms_error_m"),
                 ("frame choice", lambda r: "exact" if r["frames_exact"] else "DIFFERS"),
                 ("CPU ref. fps", "cpu_reference_fps"), ("outcome", "outcome")]), "",
             "![replay fps against error](images/bench/replay_fps_vs_error.png)"]
        bl.replace_section(DOC, "replay", "\n".join(t))
    if "compression" in res:
        t = [head, "",
             "Cache: the surging_small bake above (float32, shuffle + delta, the swell-bake default), "
             "recoded with `swell-cache recode CACHE OUT --encoding E [--no-shuffle --no-delta]`. "
             "Position error: every stored particle against the float32 original. Height error: "
             "`swell-play bench OUT --reference-cache CACHE --error-frames 16` (GPU replay of the "
             "recoded cache against the CPU reference of the original, 128 x 128, K = 256).", "",
             bl.md_table(res["compression"], [
                 ("encoding", "encoding"), ("filters", "filters"), ("bytes", "bytes"),
                 ("vs default", "ratio_vs_float32_default"),
                 ("max position error (m)", "max_position_error_m"),
                 ("rms position error (m)", "rms_position_error_m"),
                 ("max height error (m)", "max_height_error_m"),
                 ("rms height error (m)", "rms_height_error_m")]), "",
             "Quantized16 moves a particle by at most half a step of the domain / 65535 per axis, "
             "but a particle that crosses a cell's x bin edge enters or leaves eq. (7)'s cut-off "
             "window, where its Gaussian weight is still exp(-1.5^2 / 8) = 0.75 at sigma = 2 "
             "cells: the height error is therefore millimetres, not micrometres, in the cells "
             "where that happens (the rms stays small).", "",
             "![compression against error](images/bench/compression_vs_error.png)"]
        bl.replace_section(DOC, "compression", "\n".join(t))
    if "fidelity" in res:
        pct = lambda k: (lambda r: None if r.get(k) is None else "%.2f %%" % (100 * r[k]))
        t = ["Machine: %s, %s, %s." % (m.get("cpu"), m.get("renderer"), m.get("date")),
             "Command: `tools/bench --only fidelity%s`; each row `swell-play fidelity CACHE --res NxN "
             "--reconstruction R --sigma S --json` and `swell-play bench` with the same options. "
             "f0: F = 0 (every slice one frame) against the frame's envelope over the steady window; "
             "mix: F = 0.3, each real slice's row against its own frame; lengths in l0." % (
                 " --quick" if m.get("variant") == "quick" else ""),
             "",
             bl.md_table(res["fidelity"], [
                 ("cache", "cache"), ("N x N", "res"), ("columns", "reconstruction"), ("sigma", "sigma_cells"),
                 ("fps", "fps"), ("F=0 RMS / l0", "f0_rms_l0"), ("F=0 row max / l0, mean", "f0_mean_row_max_l0"),
                 ("F=0 max / l0, worst", "f0_max_l0"), ("crest loss, mean", pct("f0_crest_loss_mean")),
                 ("crest loss, worst", pct("f0_crest_loss_max")), ("F=0.3 RMS / l0", "mix_rms_l0"),
                 ("F=0.3 crest loss", pct("mix_crest_loss_mean")), ("outcome", "outcome")]),
             "",
             "![replay fidelity against fps](images/bench/replay_fidelity_vs_fps.png)"]
        bl.replace_section(DOC, "fidelity", "\n".join(t))
    if "continuity" in res:
        t = ["Machine: %s, %s, %s." % (m.get("cpu"), m.get("renderer"), m.get("date")),
             "Command: `tools/bench --only fidelity`; each row `swell-play fidelity out/bench/surging.swell "
             "--res 128x64 --fps R --seam-seconds S --frames 0 --mix-times 0 [options]`.",
             "",
             bl.md_table(res["continuity"], [
                 ("replay", "replay"), ("seconds", "seconds"), ("fps", "fps"), ("frames", "frames"),
                 ("frames with flat rows", "frames_with_flat_rows"), ("flat rows", "flat_rows"),
                 ("largest per-cell change (m)", "largest_change_m"),
                 ("steady F=0 99.9th pct (m)", "steady_f0_change_p999_m"),
                 ("ratio", "largest_over_steady_p999"), ("outcome", "outcome")])]
        bl.replace_section(DOC, "continuity", "\n".join(t))
    if "skips" in res:
        t = [head, "",
             "Each row: the same work with and without the skip (medians of repeated runs on the "
             "surging_small cache unless named).", "",
             bl.md_table(res["skips"], [("stage", "stage"), ("skip", "skip"), ("with the skip", "with_skip"),
                                        ("without", "without"), ("saves", "saves"),
                                        ("command", lambda r: "`%s`" % r["command"])])]
        bl.replace_section(DOC, "skips", "\n".join(t))
    if "render" in res:
        rng = lambda r: "**%s** (%s-%s)" % (bl.fmt(r["fps_median"]), bl.fmt(r["fps_min"]),
                                             bl.fmt(r["fps_max"]))
        t = [head, "",
             "Command per row (the synthetic cache: `swell-cache synth F --frames 120 --surface 400 "
             "--splash 20`; the bake: `scenes/surging_small.json`): `swell-play render CACHE --out DIR "
             "--size WxH --seconds 4 --json [--no-splashes]`, %d runs per row, interleaved. "
             "**shaded fps** = 1000 / frame ms: replay update, drawing, building the splash sprites "
             "and a glFinish, over the frames without timer queries (readback and PNG writing are "
             "output, listed apart). Stage columns: GL timestamp queries on every 8th frame, each "
             "stage serialised (the splash stage includes building the sprites, which an untimed "
             "frame overlaps with the surface's rasterisation); CPU ms = process CPU time, all "
             "threads, per frame. Medians; target: at least 30 shaded fps at 1280 x 720 on llvmpipe."
             % (max(r["runs"] for r in res["render"]) if res["render"] else 0), "",
             bl.md_table(res["render"], [
                 ("cache", "cache"), ("size", "size"), ("splashes", "splashes"),
                 ("shaded fps (range)", rng), ("frame ms", "frame_ms"), ("CPU ms", "cpu_ms"),
                 ("sky", "sky_ms"), ("water + sides", "water_ms"), ("splashes", "splash_ms"),
                 ("lookup + reconstruct", "replay_ms"), ("sprites drawn", "sprites_drawn"),
                 ("sprites built (CPU ms)", "sprites_cpu_ms"), ("readback ms", "readback_ms"),
                 ("PNG ms", "png_ms"), ("llvmpipe threads", "llvmpipe_threads"),
                 ("outcome", "outcome")])]
        bl.replace_section(DOC, "render", "\n".join(t))


if __name__ == "__main__":
    main()
