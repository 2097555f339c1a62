"""What each skipped stage saves, measured: the same work with and without the skip (medians of
repeated runs; replay A/B pairs interleaved so that both sides see the same load). One function
per skip; every count in a row's text is taken from the runs' JSON or from the command's
parameters.

CSV: skips; docs section: skips."""

import os

from . import common as bl

CSVS = ("skips",)
SECTIONS = ("skips",)
PLOTS = ()

SHORT_BAKE = "solver.end_time=1.0"  # classification skip: a 1 s bake ...
EVERY_STEP = "output.frame_interval=0.002"  # ... with a frame every (2 ms) step
SYNTH_FRAMES = 1200  # synthetic caches: frames, surface particles (splash / bake caches)
SPLASH_SURFACE, RENDER_SURFACE = 175, 400
SPLASHES = 8  # splash particles per frame, render skip
RENDER_SIZE, READBACK_SIZE = "320x180", "1280x720"
DECODE_FRAMES = (30, 1000)  # frames replayed: short and long (loops over the cache)
BENCH = ["--frames", 300, "--warmup", 20, "--error-frames", 1, "--cpu-frames", 0, "--json"]


def reps(ctx):
    return 3 if ctx.quick else 5


def run(ctx):
    ctx.note_load("skips")
    rows = [deep_particles(ctx), classification(ctx), splash_records(ctx), noise(ctx), synthesis(ctx)]
    sp0, sp8 = synth(ctx, "synth_splash0.swell", RENDER_SURFACE, 0), synth(ctx, "synth_splash8.swell",
                                                                           RENDER_SURFACE, SPLASHES)
    rows += [splash_pass(ctx, sp0, sp8), readback(ctx, sp0)]
    for p in (sp0, sp8):
        os.remove(p)
    rows.append(decode(ctx))
    return {"skips": [r for r in rows if r]}


# ---------------------------------------------------------------- helpers
def bake(ctx, out, *settings):
    """swell-bake scenes/surging_small.json into out, 1 thread, --set each setting."""
    cmd = [bl.exe("swell-bake"), bl.scene("surging_small.json"), "-o", out, "--threads", "1", "--json", "-q"]
    for s in settings:
        cmd += ["--set", s]
    return ctx.run(cmd, 1800)


def synth(ctx, name, surface, splash=None, frames=SYNTH_FRAMES):
    p = ctx.path(name)
    ctx.run([bl.exe("swell-cache"), "synth", p, "--frames", frames, "--surface", surface] +
            ([] if splash is None else ["--splash", splash]), 300)
    return p


def bench(ctx, cache, *extra):
    return [bl.exe("swell-play"), "bench", cache] + BENCH + list(extra)


def median_of(ctx, cmd, key, n):
    """Median of key over n runs of cmd, and the last run."""
    runs = [ctx.run(cmd, 600) for _ in range(n)]
    return bl.median(r.json.get(key) for r in runs if r.json), runs[-1]


def ab(ctx, cmd_a, cmd_b, keys, n):
    """Medians of keys ("a.b" for nested) over n interleaved runs of cmd_a and cmd_b."""
    va, vb = {k: [] for k in keys}, {k: [] for k in keys}
    for _ in range(n):
        for cmd, into in ((cmd_a, va), (cmd_b, vb)):
            j = ctx.run(cmd, 600).json
            for k in keys:
                into[k].append(bl.dig(j, k))
    return {k: bl.median(v) for k, v in va.items()}, {k: bl.median(v) for k, v in vb.items()}


def saving(a, b, unit="ms/frame"):
    if a is None or b is None:
        return "-"
    return "%.3f %s (%.0f%%)" % (b - a, unit, 100 * (b - a) / b) if b else "-"


def row(stage, skip, with_skip, without, saves, command):
    return {"stage": stage, "skip": skip, "with_skip": with_skip, "without": without, "saves": saves,
            "command": command}


# ---------------------------------------------------------------- bake
def deep_particles(ctx):
    """Deep particles never stored: the cache against all water particles (raw) and against a
    bake that stores every water particle with n <= n0 (surface_ratio 1.0)."""
    s = ctx.bake_summary
    all_raw = s["particles_water"] * 8 * s["frames"]
    full = ctx.path("surging_small_all_water.swell")
    jf = bake(ctx, full, "output.surface_ratio=1.0").json or {}
    if os.path.exists(full):
        os.remove(full)
    return row("bake", "deep particles never stored",
               "%s B cache (%.0f particles/frame, %s B raw)" % (
                   bl.fmt(s["cache_bytes"]), s["kept_mean"], bl.fmt(s["raw_bytes"])),
               "%s B raw for all %d water particles; storing every water particle with "
               "n <= n0 (surface_ratio 1.0): %s B cache, %.0f particles/frame" % (
                   bl.fmt(all_raw), s["particles_water"], bl.fmt(jf.get("cache_bytes")), jf.get("kept_mean") or 0),
               "%.1fx raw bytes; %.1fx cache bytes against surface_ratio 1.0" % (
                   all_raw / s["raw_bytes"], (jf.get("cache_bytes") or 0) / s["cache_bytes"]),
               "swell-bake scenes/surging_small.json [--set output.surface_ratio=1.0]")


def outside_solver(j):
    return j["wall_seconds"] - j["ms_per_step"] * j["steps"] / 1e3


def classification(ctx):
    """Classification (and writing) only on stored frames: a short bake storing every 10th
    step against the same bake storing every step; the difference per unstored step."""
    every = ctx.path("surging_small_every_step.swell")
    pairs = []
    for _ in range(2 if ctx.quick else 3):
        r1, r2 = bake(ctx, every, SHORT_BAKE), bake(ctx, every, SHORT_BAKE, EVERY_STEP)
        if r1.json and r2.json:
            pairs.append((r1.json, r2.json))
    if os.path.exists(every):
        os.remove(every)
    if not pairs:
        return None
    b, e = bl.median(outside_solver(p[0]) for p in pairs), bl.median(outside_solver(p[1]) for p in pairs)
    j1, j2 = pairs[-1]
    unstored = j2["frames"] - j1["frames"]
    step_ms = ctx.bake_summary["ms_per_step"]
    return row("bake", "classification (and writing) only on stored frames",
               "%.3f s outside the solver for %d steps, %d frames" % (b, j1["steps"], j1["frames"]),
               "%.3f s with a frame every step (%d frames)" % (e, j2["frames"]),
               "%.2f ms per unstored step (%.0f%% of the %.2f ms solver step)" % (
                   1e3 * (e - b) / unstored, 100 * (e - b) / unstored / (step_ms / 1e3), step_ms),
               "swell-bake scenes/surging_small.json --set %s [--set %s]" % (SHORT_BAKE, EVERY_STEP))


def splash_records(ctx):
    """No splash records when none: an empty splash section is a count of 0."""
    sizes = {}
    for n in (0, 1):
        p = synth(ctx, "synth_splash%d.swell" % n, SPLASH_SURFACE, n)
        sizes[n] = os.path.getsize(p)
        os.remove(p)
    return row("bake/cache", "no splash records when none",
               "%s B for %s frames without splash particles" % (bl.fmt(sizes[0]), bl.fmt(SYNTH_FRAMES)),
               "%s B with one splash particle per frame" % bl.fmt(sizes[1]),
               "%.1f B per frame (%.1f%%)" % ((sizes[1] - sizes[0]) / SYNTH_FRAMES,
                                              100 * (sizes[1] - sizes[0]) / sizes[1]),
               "swell-cache synth F --frames %d --surface %d --splash 0|1" % (SYNTH_FRAMES, SPLASH_SURFACE))


# ---------------------------------------------------------------- replay
def noise(ctx):
    """No fBm noise built and no noise lookup when F = 0 (against F = 0.3)."""
    keys = ["frame_ms_median", "stage_gpu_ms.slice_lookup", "upload_ms"]
    f0, f3 = ab(ctx, bench(ctx, ctx.cache, "-F", "0"), bench(ctx, ctx.cache, "-F", "0.3"), keys, 2 * reps(ctx))
    side = lambda v, F: "slice lookup %s ms GPU, frame %s ms, set-up %s ms (F = %s)" % (
        bl.fmt(v["stage_gpu_ms.slice_lookup"]), bl.fmt(v["frame_ms_median"]), bl.fmt(v["upload_ms"]), F)
    return row("replay", "no noise when F = 0 (no fBm noise built, no noise lookup in the slice-lookup pass)",
               side(f0, "0"), side(f3, "0.3"),
               "slice lookup: %s; whole frame: %s" % (
                   saving(f0["stage_gpu_ms.slice_lookup"], f3["stage_gpu_ms.slice_lookup"], "ms"),
                   saving(f0["frame_ms_median"], f3["frame_ms_median"], "ms")),
               "swell-play bench CACHE -F 0|0.3 --frames %d (interleaved)" % frames_of(BENCH))


def synthesis(ctx):
    """No synthesis pass for one unrotated direction (--angles 0 against 0.001)."""
    a0, a1 = ab(ctx, bench(ctx, ctx.cache, "--mode", "ripple", "--angles", "0"),
                bench(ctx, ctx.cache, "--mode", "ripple", "--angles", "0.001"),
                ["frame_ms_median", "stage_gpu_ms.synthesis"], 2 * reps(ctx))
    return row("replay", "no synthesis pass for one unrotated direction",
               "%s ms/frame (--angles 0)" % bl.fmt(a0["frame_ms_median"]),
               "%s ms/frame (--angles 0.001; synthesis pass %s ms GPU)" % (
                   bl.fmt(a1["frame_ms_median"]), bl.fmt(a1["stage_gpu_ms.synthesis"])),
               saving(a0["frame_ms_median"], a1["frame_ms_median"]),
               "swell-play bench CACHE --mode ripple --angles 0|0.001 (interleaved)")


def frames_of(cmd):
    return cmd[cmd.index("--frames") + 1]


# ---------------------------------------------------------------- render
def render(ctx, cache, size, seconds):
    return [bl.exe("swell-play"), "render", cache, "--out", ctx.path("render_skip"), "--size", size,
            "--seconds", seconds, "--json"]


def size_text(size):
    return size.replace("x", " x ")


def splash_pass(ctx, sp0, sp8):
    """The splash pass skips itself for frames without splash particles."""
    draw, cpu, gpu = ("timing_ms_per_frame.draw_synced", "timing_ms_per_frame.splash_sprites_cpu",
                      "stage_gpu_ms.splashes")
    r0, r8 = ab(ctx, render(ctx, sp0, RENDER_SIZE, "1"), render(ctx, sp8, RENDER_SIZE, "1"),
                ["shaded_fps", gpu, draw, cpu, "splash.sprites_mean"], reps(ctx))
    return row("replay/render", "no splash pass without splashes",
               "%s ms/frame drawn (no splash particles: pass skipped)" % bl.fmt(r0[draw]),
               "%s ms/frame drawn with %d splash particles per frame (%s sprites; "
               "splash pass %s ms GPU, sprites built on the CPU %s ms)" % (
                   bl.fmt(r8[draw]), SPLASHES, bl.fmt(r8["splash.sprites_mean"]), bl.fmt(r8[gpu]), bl.fmt(r8[cpu])),
               saving(r0[draw], r8[draw]),
               "swell-play render synth_splash0|%d.swell --size %s --seconds 1 (interleaved)" % (
                   SPLASHES, RENDER_SIZE))


def readback(ctx, sp0):
    """Bench and the on-screen part of render never read back; output does."""
    rb = ctx.run(render(ctx, sp0, READBACK_SIZE, "0.2"), 600)
    fb, last = median_of(ctx, bench(ctx, ctx.cache), "frame_ms_median", reps(ctx))
    res = (last.json or {}).get("res") or ["?", "?"]
    rbj = (rb.json or {}).get("timing_ms_per_frame", {})
    return row("replay", "no readback without output (the height field and the "
                         "picture stay on the GPU unless written)",
               "%s ms/frame (bench, %s x %s, no readback)" % (bl.fmt(fb), res[0], res[1]),
               "readback of a %s picture %s ms/frame, its PNG %s ms/frame" % (
                   size_text(READBACK_SIZE), bl.fmt(rbj.get("readback")), bl.fmt(rbj.get("png_write"))),
               "%s ms/frame of readback (+ %s ms PNG) when nothing is written" % (
                   bl.fmt(rbj.get("readback")), bl.fmt(rbj.get("png_write"))),
               "swell-play bench CACHE; swell-play render synth_splash0.swell --size %s --seconds 0.2" % READBACK_SIZE)


# ---------------------------------------------------------------- decoding
def decode(ctx):
    """Frames never selected are never decoded: a short replay against a long one."""
    synthetic = synth(ctx, "synthetic.swell", RENDER_SURFACE)
    (short, ls), (long_, ll) = [
        median_of(ctx, [bl.exe("swell-play"), "bench", synthetic, "--frames", n, "--warmup", 0,
                        "--error-frames", 1, "--cpu-frames", 0, "--json"], "decode_ms", reps(ctx))
        for n in DECODE_FRAMES]
    os.remove(synthetic)
    if not (ls.json and ll.json):
        return None
    js, jl = ls.json, ll.json
    return row("replay", "frames never selected are never decoded",
               "%d of %d frames decoded in %.1f ms (%s of playback)" % (
                   js["frames_decoded"], js["frames_in_cache"], short, playback(js)),
               "%d frames decoded in %.1f ms (%s of playback, loops over the cache)" % (
                   jl["frames_decoded"], long_, playback(jl)),
               "%.1f ms and %.0f%% of the frame memory at start-up" % (
                   long_ - short, 100 * (1 - js["frames_decoded"] / jl["frames_decoded"])),
               "swell-play bench out/bench/synthetic.swell --frames %d|%d --warmup 0" % DECODE_FRAMES)


def playback(j):
    """Seconds of playback the run replayed (warm-up and measured frames at its playback fps)."""
    fps = j.get("playback_fps")
    return "%.0f s" % ((j["frames"] + j.get("warmup", 0)) / fps) if fps else "?"


# ---------------------------------------------------------------- docs
def table(rows, m):
    t = [bl.header(m), "",
         "Each row: the same work with and without the skip (medians of repeated runs on the "
         "surging_small cache unless named).", "",
         bl.md_table(rows["skips"], [("stage", "stage"), ("skip", "skip"), ("with the skip", "with_skip"),
                                     ("without", "without"), ("saves", "saves"),
                                     ("command", lambda r: "`%s`" % r["command"])])]
    return {"skips": "\n".join(t)}


def plot(rows, out_dir):
    """No plot: the skips are a table."""
    return None
