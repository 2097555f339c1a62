"""Render (docs/render.md): shaded frames per second of swell-play render (Sec. 5) with the cost of
each stage: a synthetic stress cache (real splash particles every frame) with and without
splashes at two sizes, and the surging_small bake (its own few splashes). Runs interleaved,
rep by rep, so drift hits every case.

CSV: render; docs section: render."""

import os

from . import common as bl

CSVS = ("render",)
SECTIONS = ("render",)
PLOTS = ()

SYNTH = {"frames": 120, "surface": 400, "splash": 20}
SECONDS = 4
TARGET_FPS, TARGET_SIZE = 30, "1280x720"


def cases(synth, cache):
    """(label, cache, size, extra arguments)."""
    with_splash = "synthetic, %d splash particles/frame" % SYNTH["splash"]
    return [(with_splash, synth, "1280x720", []), ("synthetic", synth, "1280x720", ["--no-splashes"]),
            (with_splash, synth, "640x360", []), ("synthetic", synth, "640x360", ["--no-splashes"]),
            ("surging_small bake", cache, "1280x720", [])]


def run(ctx):
    ctx.note_load("render")
    synth = ctx.path("render_synth.swell")
    r = ctx.run([bl.exe("swell-cache"), "synth", synth] +
                [a for k, v in SYNTH.items() for a in ("--" + k, v)], 300)
    if r.rc != 0:
        raise SystemExit("tools/bench: swell-cache synth failed: " + r.last_err_line())
    todo = cases(synth, ctx.cache)
    runs, errors = [[] for _ in todo], [None for _ in todo]
    for _ in range(2 if ctx.quick else 5):
        for i, (_, c, size, extra) in enumerate(todo):
            r = ctx.run([bl.exe("swell-play"), "render", c, "--out", ctx.path("render_frames"), "--size", size,
                         "--seconds", SECONDS, "--json"] + extra, 600)
            if r.rc == 0 and r.json:
                runs[i].append(r.json)
            else:
                errors[i] = "exit %s: %s" % (r.rc, r.last_err_line())
    os.remove(synth)
    return {"render": [case_row(case, js, err) for case, js, err in zip(todo, runs, errors)]}


def case_row(case, js, err):
    """Medians over the runs of one case."""
    label, _, size, extra = case
    med = lambda f: bl.median(f(j) for j in js)
    stage = lambda k: med(lambda j: j["stage_gpu_ms"][k])
    timing = lambda k: med(lambda j: j["timing_ms_per_frame"][k])
    fps = [j["shaded_fps"] for j in js]
    return {"cache": label, "size": size.replace("x", " x "), "splashes": "no" if extra else "yes",
            "runs": len(js), "fps_median": med(lambda j: j["shaded_fps"]),
            "fps_min": min(fps) if fps else None, "fps_max": max(fps) if fps else None,
            "frame_ms": timing("draw_synced"), "cpu_ms": timing("draw_cpu"),
            "sky_ms": stage("sky"), "water_ms": stage("water"), "splash_ms": stage("splashes"),
            "replay_ms": med(lambda j: j["stage_gpu_ms"]["slice_lookup"] + j["stage_gpu_ms"]["reconstruct"]),
            "sprites_cpu_ms": timing("splash_sprites_cpu"),
            "sprites_drawn": med(lambda j: j["splash"]["sprites_mean"] - j["splash"]["culled_under_water_mean"]),
            "readback_ms": timing("readback"), "png_ms": timing("png_write"),
            "llvmpipe_threads": js[0].get("llvmpipe_threads") if js else None, "outcome": err or "ok"}


def table(rows, m):
    rr = rows["render"]
    rng = lambda r: "**%s** (%s-%s)" % (bl.fmt(r["fps_median"]), bl.fmt(r["fps_min"]), bl.fmt(r["fps_max"]))
    t = [bl.header(m), "",
         "Command per row (the synthetic cache: `swell-cache synth F --frames %d --surface %d "
         "--splash %d`; the bake: `scenes/surging_small.json`): `swell-play render CACHE --out DIR "
         "--size WxH --seconds %g --json [--no-splashes]`, %d runs per row, interleaved. "
         "**shaded fps** = 1000 / frame ms: replay update, drawing, building the splash sprites "
         "and a glFinish, over the frames without timer queries (readback and PNG writing are "
         "output, listed apart). Stage columns: GL timestamp queries on every 8th frame, each "
         "stage serialised (the splash stage includes building the sprites, which an untimed "
         "frame overlaps with the surface's rasterisation); CPU ms = process CPU time, all "
         "threads, per frame. Medians; target: at least %d shaded fps at %s on llvmpipe." % (
             SYNTH["frames"], SYNTH["surface"], SYNTH["splash"], SECONDS,
             max(r["runs"] for r in rr) if rr else 0, TARGET_FPS, TARGET_SIZE.replace("x", " x ")), "",
         bl.md_table(rr, [
             ("cache", "cache"), ("size", "size"), ("splashes", "splashes"),
             ("shaded fps (range)", rng), ("frame ms", "frame_ms"), ("CPU ms", "cpu_ms"),
             ("sky", "sky_ms"), ("water + sides", "water_ms"), ("splashes", "splash_ms"),
             ("lookup + reconstruct", "replay_ms"), ("sprites drawn", "sprites_drawn"),
             ("sprites built (CPU ms)", "sprites_cpu_ms"), ("readback ms", "readback_ms"),
             ("PNG ms", "png_ms"), ("llvmpipe threads", "llvmpipe_threads"),
             ("outcome", "outcome")])]
    return {"render": "\n".join(t)}


def plot(rows, out_dir):
    """No plot: the render figures are a table."""
    return None
