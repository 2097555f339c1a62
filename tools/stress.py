#!/usr/bin/python3
"""Stability stress suite (docs/validation.md, Stability stress suite and fuzzing). Bake sweeps
over dt, particle spacing, piston stroke and period (up to and past breaking), inflow speed and
long runs (100,000 steps of the small still tank and surging scenes); replay at extreme parameters
and on degenerate caches.

Every bake must end either stable (cache verified, no NaN, conservation figures reported) or
stopped by the divergence detector with a clear message and no cache; every replay must give a
finite result that matches the CPU reference or one clear error line. A timeout is a hang.
Writes out/stress/*.csv and the outcome table in docs/validation.md; exits 1 on any failure.
--only fuzz (not part of the default run) builds the libFuzzer targets of tests/fuzz in
build-fuzz/ and runs each for --fuzz-seconds."""

import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from swellbench import common as bl  # noqa: E402
import swell_cache  # noqa: E402

OUT = os.path.join(bl.ROOT, "out", "stress")
DOC = os.path.join(bl.ROOT, "docs", "validation.md")
FUZZ_INPUT_TIMEOUT = 30  # s: libFuzzer -timeout, one input slower than this is a hang
FUZZ_RSS_MB = 2048  # libFuzzer -rss_limit_mb


def scene(name):
    return os.path.join(bl.ROOT, "scenes", name)


def bake_cases(long_steps):
    dam = "dam_break_small.json"
    c = []
    # dt: the load-time Courant check is bypassed (expected_speed) so the run-time detector is tested.
    for dt in [0.00025, 0.0005, 0.001, 0.002, 0.004]:
        c.append(("dt", "dam break, dt = %g ms" % (dt * 1e3), dam,
                  {"solver.dt": dt, "solver.expected_speed": 0.1, "output.frame_interval": 0.02,
                   "solver.end_time": 0.3}))
    for l0, dt in [(0.01, 0.001), (0.005, 0.0005), (0.0025, 0.00025)]:
        c.append(("spacing", "dam break, l0 = %g mm" % (l0 * 1e3), dam,
                  {"geometry.particle_spacing": l0, "solver.dt": dt, "output.frame_interval": 0.01,
                   "solver.end_time": 0.3}))
    surging = "surging_small.json"
    for stroke in [0.02, 0.05, 0.1, 0.15, 0.2, 0.3]:
        c.append(("piston stroke", "sinusoidal piston, T = 0.8 s, S = %g cm" % (stroke * 100), surging,
                  {"piston.kind": "sinusoidal", "piston.period": 0.8, "piston.stroke": stroke}))
    for period in [0.4, 0.6, 1.0, 1.6, 2.5]:
        c.append(("piston period", "sinusoidal piston, S = 8 cm, T = %g s" % period, surging,
                  {"piston.kind": "sinusoidal", "piston.period": period, "piston.stroke": 0.08}))
    for v in [0.05, 0.25, 0.5, 1.0, 2.0]:
        c.append(("inflow speed", "ripple channel, inflow %g m/s" % v, "ripple_small.json",
                  {"recycling.velocity": v, "solver.end_time": 2.0}))
    c.append(("long run", "still tank, %s steps" % "{:,}".format(long_steps), "still_tank_small.json",
              {"solver.end_time": long_steps * 0.001, "output.frame_interval": 0.5}))
    c.append(("long run", "surging (random piston), %s steps" % "{:,}".format(long_steps), surging,
              {"solver.end_time": long_steps * 0.002, "output.frame_interval": 0.1}))
    return c


def nan_scan(path):
    """Decodes every frame with the Python reader; returns (frames, non-finite values)."""
    c = swell_cache.Cache(path)
    bad = 0
    for i in range(len(c)):
        s, sp = c.frame(i)
        a = np.array([v for p in s for v in p] + [v for p in sp for v in p], dtype=float)
        bad += int((~np.isfinite(a)).sum())
    return len(c), bad


def run_bake(case, timeout, log):
    sweep, label, sc, sets = case
    cache = os.path.join(OUT, "case.swell")
    if os.path.exists(cache):
        os.remove(cache)
    args = [bl.exe("swell-bake"), scene(sc), "-o", cache, "--threads", "1", "--json", "-q"]
    for k, v in sets.items():
        args += ["--set", "%s=%s" % (k, v)]
    r = bl.run(args, timeout=timeout, log=log)
    row = {"sweep": sweep, "case": label, "scene": sc,
           "overrides": " ".join("%s=%s" % kv for kv in sets.items()), "wall_s": round(r.wall, 1),
           "command": "swell-bake scenes/%s -o C %s" % (sc, " ".join("--set %s=%s" % kv for kv in sets.items()))}
    warnings = [l for l in r.err.splitlines() if "warning" in l]
    row["warning"] = "breaks (Miche)" if any("breaks" in w for w in warnings) else ""
    if r.timed_out:
        row.update(outcome="FAIL: hang (no end within %d s)" % timeout, ok=False)
    elif r.rc == 0:
        j = r.json or {}
        v = bl.run([bl.exe("swell-cache"), "verify", cache, "--json"], timeout=300, nice=0)
        frames, bad = nan_scan(cache)
        cons = j.get("conservation", {})
        s0, s1 = cons.get("start", {}), cons.get("end", {})
        row.update(particles="%d + %d" % (j.get("particles_water", 0), j.get("particles_wall", 0)),
                   steps=j.get("steps"), frames=frames, nonfinite=bad, max_courant=j.get("max_courant"),
                   water_start=s0.get("water"), water_end=s1.get("water"), in_tank_end=s1.get("in_tank"),
                   volume_change=cons.get("volume_change"), energy_drift=cons.get("energy_drift"),
                   kinetic_energy_end=s1.get("kinetic_energy"), ms_per_step=j.get("ms_per_step"),
                   recycled=j.get("recycled"))
        if v.rc != 0 or bad:
            row.update(outcome="FAIL: cache %s" % (v.last_err_line() or "holds %d non-finite values" % bad),
                       ok=False)
        else:
            row.update(outcome="stable", ok=True)
    elif r.rc == 3:
        msg = r.last_err_line().replace("swell-bake: ", "")
        left = os.path.exists(cache)
        row.update(outcome="stopped: " + msg, ok=not left)
        if left:
            row["outcome"] = "FAIL: diverged but left a cache: " + msg
    else:
        row.update(outcome="FAIL: exit %s: %s" % (r.rc, r.last_err_line()), ok=False)
    if os.path.exists(cache):
        os.remove(cache)
    return row


def replay_cases(bake_cache, synth):
    c = []
    b = bake_cache
    # Every frame (--window all): the cases push the replay's parameters, not the steady
    # window (the one-frame caches have none; F = 1 spreads slices over more than the
    # small bake's steady window).
    small = ["--window", "all", "--frames", 20, "--warmup", 2, "--error-frames", 2, "--cpu-frames", 1]
    big = ["--window", "all", "--frames", 3, "--warmup", 1, "--error-frames", 1, "--cpu-frames", 0]
    c += [("F at its bound (1)", b, ["-F", 1] + small, "ok"),
          ("F above its bound (1.0001)", b, ["-F", 1.0001] + small, "error"),
          ("F = 0", b, ["-F", 0] + small, "ok"),
          ("beta 0", b, ["--beta", 0] + small, "ok"),
          ("beta 4", b, ["--beta", 4] + small, "ok"),
          ("K = 1", b, ["--slices", 1] + small, "error"),
          ("K = 2", b, ["--slices", 2] + small, "ok"),
          ("K = 4096", b, ["--slices", 4096] + small, "ok"),
          ("K = 16384 (the bound)", b, ["--slices", 16384] + big, "ok"),
          ("1 x 1 cells", b, ["--res", "1x1"] + small, "ok"),
          ("4096 x 1 cells", b, ["--res", "4096x1"] + small, "ok"),
          ("1 x 4096 cells, K = 64", b, ["--res", "1x4096", "--slices", 64] + small, "ok"),
          ("4096 x 4096 cells", b, ["--res", "4096x4096"] + big, "ok"),
          ("0 x 16 cells", b, ["--res", "0x16"] + small, "error"),
          ("sigma 0.1 cells", b, ["--sigma", 0.1] + small, "error"),
          ("sigma 0.25 cells (the bound)", b, ["--sigma", 0.25] + small, "ok"),
          ("sigma 64 cells", b, ["--sigma", 64] + small, "ok")]
    for name, path in synth.items():
        for mode in ["surging", "ripple", "whirlpool"]:
            for pol in ["loop", "clamp"]:
                c.append(("%s, %s, %s" % (name, mode, pol), path,
                          ["--mode", mode, "--policy", pol, "--res", "64x64"] + small, "ok"))
    return c


def run_replay(case, timeout, log):
    label, cache, args, expect = case
    r = bl.run([bl.exe("swell-play"), "bench", cache, "--json"] + args, timeout=timeout, log=log)
    row = {"case": label, "expect": expect, "wall_s": round(r.wall, 1),
           "command": "swell-play bench %s %s" % (os.path.basename(cache), " ".join(str(a) for a in args))}
    j = r.json or {}
    if r.timed_out:
        row.update(outcome="FAIL: hang", ok=False)
    elif r.rc == 0:
        err = j.get("max_abs_error")
        finite = err is not None and math.isfinite(err) and j.get("rms_error") is not None
        good = finite and err <= 1e-4 * j.get("water_depth", 1) and j.get("frames_exact")
        row.update(fps=j.get("fps"), max_abs_error=err, rms_error=j.get("rms_error"),
                   outcome="ok" if good else "FAIL: error %s" % err, ok=bool(good) and expect == "ok")
        if good and expect != "ok":
            row["outcome"] = "FAIL: accepted, expected a clear error"
    elif r.rc == 2 and len([l for l in r.err.splitlines() if l.strip()]) == 1 and not r.out.strip():
        row.update(outcome="clear error: " + r.last_err_line().replace("swell-play: ", ""),
                   ok=expect == "error")
    else:
        row.update(outcome="FAIL: exit %s: %s" % (r.rc, r.last_err_line()), ok=False)
    return row


# ---------------------------------------------------------------- fuzz
FUZZ_BUILD = os.path.join(bl.ROOT, "build-fuzz")
FUZZ_SRC = os.path.join(bl.ROOT, "tests", "fuzz")
FUZZ_TARGETS = ["scene", "checkpoint", "metadata", "options"]
FUZZ_STATE = os.path.join(OUT, "fuzz.json")


def fuzz_build(targets, log):
    """Configures build-fuzz/ with clang and -DSWELL_FUZZ=ON and builds the fuzz targets."""
    if not os.path.exists(os.path.join(FUZZ_BUILD, "build.ninja")):
        env = dict(os.environ, CC="clang", CXX="clang++")
        r = bl.run(["cmake", "-S", bl.ROOT, "-B", FUZZ_BUILD, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=RelWithDebInfo",
                    "-DSWELL_FUZZ=ON", "-DSWELL_BUILD_TESTS=OFF", "-DSWELL_BUILD_BENCHMARKS=OFF",
                    "-DSWELL_BUILD_PYTHON=OFF"], timeout=600, nice=0, env=env, log=log)
        if r.rc != 0:
            raise SystemExit("tools/stress: configuring build-fuzz failed: " + r.last_err_line())
    r = bl.run(["cmake", "--build", FUZZ_BUILD, "-j2", "--target"] + ["swell-%s-fuzz" % t for t in targets],
               timeout=3600, nice=0, log=log)
    if r.rc != 0:
        raise SystemExit("tools/stress: building the fuzz targets failed: " + r.last_err_line())


def fuzz_start(target, seconds, input_timeout, rss_mb):
    """Starts one libFuzzer run: new inputs go to out/stress/fuzz/<target>/corpus, the checked-in
    seeds (tests/fuzz/corpus/<target>) are read only; crash/timeout/oom files go next to them."""
    work = os.path.join(OUT, "fuzz", target)
    for sub in ["corpus", "artifacts"]:
        os.makedirs(os.path.join(work, sub), exist_ok=True)
    for f in os.listdir(os.path.join(work, "artifacts")):
        os.remove(os.path.join(work, "artifacts", f))
    args = [os.path.join(FUZZ_BUILD, "bin", "swell-%s-fuzz" % target),
            "-max_total_time=%d" % seconds, "-timeout=%d" % input_timeout, "-rss_limit_mb=%d" % rss_mb,
            "-max_len=8192", "-print_final_stats=1",
            "-artifact_prefix=%s/" % os.path.join(work, "artifacts")]
    dictionary = os.path.join(FUZZ_SRC, "%s.dict" % target)
    if os.path.exists(dictionary):
        args.append("-dict=" + dictionary)
    args += [os.path.join(work, "corpus"), os.path.join(FUZZ_SRC, "corpus", target)]
    logf = open(os.path.join(work, "libfuzzer.log"), "w")
    env = dict(os.environ, ASAN_OPTIONS="detect_leaks=0", OMP_NUM_THREADS="1")
    p = subprocess.Popen(["nice", "-n", "5"] + args, stdout=logf, stderr=subprocess.STDOUT, env=env,
                         start_new_session=True)
    cmd = "build-fuzz/bin/swell-%s-fuzz -max_total_time=%d -timeout=%d -rss_limit_mb=%d -max_len=8192%s " \
          "out/stress/fuzz/%s/corpus tests/fuzz/corpus/%s" % (
              target, seconds, input_timeout, rss_mb,
              " -dict=tests/fuzz/%s.dict" % target if os.path.exists(dictionary) else "", target, target)
    return {"target": target, "proc": p, "log": logf, "work": work, "t0": time.monotonic(), "command": cmd,
            "seconds": seconds}


def fuzz_finish(run):
    """Waits for a libFuzzer run and reads its outcome: executions, and what it left behind."""
    limit = run["seconds"] + 600
    try:
        rc = run["proc"].wait(timeout=max(1, limit - (time.monotonic() - run["t0"])))
    except subprocess.TimeoutExpired:
        os.killpg(run["proc"].pid, 9)
        rc = None
    run["log"].close()
    text = open(os.path.join(run["work"], "libfuzzer.log"), errors="replace").read()
    execs = None
    for line in text.splitlines():
        if line.startswith("stat::number_of_executed_units:"):
            execs = int(line.split(":")[-1])
    artifacts = sorted(os.listdir(os.path.join(run["work"], "artifacts")))
    kinds = {k: [a for a in artifacts if a.startswith(k + "-")] for k in ["crash", "timeout", "oom", "leak"]}
    corpus = len(os.listdir(os.path.join(run["work"], "corpus")))
    seeds = len(os.listdir(os.path.join(FUZZ_SRC, "corpus", run["target"])))
    ok = rc == 0 and execs is not None and not artifacts
    reason = ""
    if not ok:
        err = [l for l in text.splitlines() if "ERROR" in l or "swell fuzz:" in l]
        reason = (err[0] if err else "exit %s" % rc).strip()
    return {"target": run["target"], "seconds": round(time.monotonic() - run["t0"]), "executions": execs,
            "crashes": len(kinds["crash"]) + len(kinds["leak"]), "timeouts": len(kinds["timeout"]),
            "ooms": len(kinds["oom"]), "seeds": seeds, "corpus": corpus + seeds, "ok": ok,
            "outcome": "ok" if ok else "FAIL: " + reason[:160], "command": run["command"],
            "artifacts": artifacts}


def run_fuzz(targets, seconds, jobs, input_timeout, rss_mb, log):
    fuzz_build(targets, log)
    rows, queue, running = [], list(targets), []
    while queue or running:
        while queue and len(running) < jobs:
            running.append(fuzz_start(queue.pop(0), seconds, input_timeout, rss_mb))
            print("  fuzz %-12s started (%d s)" % (running[-1]["target"], seconds), flush=True)
        first = running.pop(0)
        row = fuzz_finish(first)
        rows.append(row)
        print("  fuzz %-12s %s executions, %s (%d s)" % (row["target"], row["executions"], row["outcome"],
                                                       row["seconds"]), flush=True)
    return rows


def fuzz_docs(rows, m):
    """Merges this run's rows into out/stress/fuzz.json (one row per target, the latest run) and
    writes the table of every target in it into docs/validation.md."""
    state = {}
    if os.path.exists(FUZZ_STATE):
        with open(FUZZ_STATE) as f:
            state = json.load(f)
    for r in rows:
        state[r["target"]] = dict(r, date=m["date"], commit=m["commit"], load=m["loads"][0][1])
    with open(FUZZ_STATE, "w") as f:
        json.dump(state, f, indent=1)
    ordered = [state[t] for t in FUZZ_TARGETS if t in state]
    head = ("Generated by `tools/stress --only fuzz` (%s, %d cores; libFuzzer from clang 14 with "
            "AddressSanitizer and UndefinedBehaviorSanitizer, at most two targets at once). Per target: "
            "`-timeout` %s s per input (a slower input is a hang), `-rss_limit_mb` %s (more is an OOM); "
            "an input refused with anything but one clear error line aborts, as does a broken property "
            "of an accepted one (tests/fuzz/*_fuzz.cpp). Seeds: `tests/fuzz/corpus/<target>/`, replayed "
            "by ctest (`Fuzz.*.Corpus`). State of every target's latest run: `out/stress/fuzz.json`." % (
                m["cpu"], m["cores"], FUZZ_INPUT_TIMEOUT, FUZZ_RSS_MB))
    table = bl.md_table(ordered, [
        ("surface", "target"), ("run", lambda r: "%s, commit %s" % (r["date"], r["commit"])),
        ("seconds", "seconds"), ("executions", lambda r: "{:,}".format(r["executions"] or 0)),
        ("crashes", "crashes"), ("hangs (timeouts)", "timeouts"), ("OOMs", "ooms"),
        ("corpus (seeds)", lambda r: "%s (%s)" % (r["corpus"], r["seeds"])), ("outcome", "outcome"),
        ("command", lambda r: "`%s`" % r["command"])])
    bl.replace_section(DOC, "fuzz", "\n".join([head, "", table]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--long-steps", type=int, default=100000, help="steps of the long runs")
    ap.add_argument("--timeout", type=int, default=600, help="per-run limit (s), long runs get 5x")
    ap.add_argument("--only", default="", help="bake,replay,durability,fuzz (fuzz is not in the default run)")
    ap.add_argument("--lock-trials", type=int, default=20, help="durability: lock trials")
    ap.add_argument("--fuzz-seconds", type=int, default=600, help="libFuzzer time per fuzz target (s)")
    ap.add_argument("--fuzz-targets", default=",".join(FUZZ_TARGETS), help="fuzz targets to run")
    ap.add_argument("--fuzz-jobs", type=int, default=2, help="fuzz targets run at once")
    ap.add_argument("--no-docs", action="store_true")
    args = ap.parse_args()
    only = set(filter(None, args.only.split(",")))
    os.makedirs(OUT, exist_ok=True)
    log = open(os.path.join(OUT, "commands.log"), "w")
    t0 = time.monotonic()
    loads = [("start", bl.load_average(), time.strftime("%H:%M:%S"))]
    print("tools/stress: load average %s; log out/stress/commands.log" % loads[0][1], flush=True)
    bake_rows, replay_rows = [], []
    if not only or "bake" in only:
        for case in bake_cases(args.long_steps):
            limit = args.timeout * (5 if case[0] == "long run" else 1)
            row = run_bake(case, limit, log)
            row["load"] = bl.load_average()
            bake_rows.append(row)
            print("  %-14s %-44s %s (%.0f s)" % (row["sweep"], row["case"], row["outcome"][:90], row["wall_s"]),
                  flush=True)
        bl.write_csv(os.path.join(OUT, "bake.csv"), bake_rows)
    loads.append(("after bake", bl.load_average(), time.strftime("%H:%M:%S")))
    if not only or "replay" in only:
        cache = os.path.join(OUT, "surging_small.swell")
        r = bl.run([bl.exe("swell-bake"), scene("surging_small.json"), "-o", cache, "--threads", "1", "-q"],
                   timeout=1800, log=log)
        if r.rc != 0:
            raise SystemExit("tools/stress: baking surging_small failed: " + r.last_err_line())
        synth = {}
        for name, a in [("one-frame cache", ["--frames", 1, "--surface", 200]),
                        ("zero surface particles (40 frames)", ["--frames", 40, "--surface", 0, "--splash", 0]),
                        ("one frame, zero particles", ["--frames", 1, "--surface", 0, "--splash", 0])]:
            p = os.path.join(OUT, "synth_%d.swell" % len(synth))
            bl.run([bl.exe("swell-cache"), "synth", p] + a, timeout=60, log=log)
            synth[name] = p
        for case in replay_cases(cache, synth):
            row = run_replay(case, args.timeout, log)
            replay_rows.append(row)
            print("  %-44s %s (%.0f s)" % (row["case"], row["outcome"][:90], row["wall_s"]), flush=True)
        # The other subcommands on a cache without surface particles: finite files, no crash.
        p = synth["zero surface particles (40 frames)"]
        for label, cmd in [("heights, zero surface particles",
                            ["heights", p, "--out", os.path.join(OUT, "h"), "--res", "16x16", "--seconds", "0.2",
                             "--window", "all"]),
                           ("render, zero surface particles",
                            ["render", p, "--out", os.path.join(OUT, "r"), "--size", "160x90", "--seconds",
                             "0.2", "--window", "all"])]:
            r = bl.run([bl.exe("swell-play")] + cmd + ["--json"], timeout=args.timeout, log=log)
            ok = r.rc == 0 and r.json is not None
            replay_rows.append({"case": label, "expect": "ok", "wall_s": round(r.wall, 1),
                                "outcome": "ok" if ok else "FAIL: exit %s: %s" % (r.rc, r.last_err_line()),
                                "ok": ok, "command": "swell-play " + " ".join(os.path.basename(c) if "/" in c
                                                                              else c for c in cmd)})
            print("  %-44s %s" % (label, replay_rows[-1]["outcome"]), flush=True)
        bl.write_csv(os.path.join(OUT, "replay.csv"), replay_rows)
    dur_ok = True
    if not only or "durability" in only:
        print("tools/stress: durability (locks, ENOSPC/EIO at every write site, resume)", flush=True)
        dur_ok = durability_section(args, log, not args.no_docs)
    fuzz_rows = []
    if "fuzz" in only:  # not part of the default run: 10 minutes per target
        targets = [t for t in args.fuzz_targets.split(",") if t]
        fuzz_rows = run_fuzz(targets, args.fuzz_seconds, args.fuzz_jobs, FUZZ_INPUT_TIMEOUT, FUZZ_RSS_MB, log)
    loads.append(("end", bl.load_average(), time.strftime("%H:%M:%S")))
    minutes = (time.monotonic() - t0) / 60
    m = bl.machine()
    m.update(total_minutes=round(minutes, 1), loads=loads)
    with open(os.path.join(OUT, "machine.json"), "w") as f:
        json.dump(m, f, indent=1)
    fails = [r for r in bake_rows + replay_rows + fuzz_rows if not r["ok"]]
    if not args.no_docs:
        if bake_rows or replay_rows:
            docs(bake_rows, replay_rows, m, args.long_steps)
        if fuzz_rows:
            fuzz_docs(fuzz_rows, m)
    print("tools/stress: %d cases, %d failed, %.1f min; out/stress/" % (
        len(bake_rows) + len(replay_rows) + len(fuzz_rows), len(fails), minutes), flush=True)
    for r in fails:
        print("  FAILED: %s: %s" % (r.get("case", r.get("target")), r["outcome"]))
    if not dur_ok:
        print("  FAILED: durability (see the lines above)")
    sys.exit(1 if fails or not dur_ok else 0)


def docs(bake_rows, replay_rows, m, long_steps):
    head = ("Generated by `tools/stress` on %s: %s, %d cores; commit %s; load average %s (%s). "
            "%.1f min in all. Per-run limit 600 s (long runs 3,000 s); a run past it would be "
            "reported as a hang. CSV: `out/stress/`." % (
                m["date"], m["cpu"], m["cores"], m["commit"], m["loads"][0][1],
                "; ".join("%s %s" % (w, l) for w, l, _ in m["loads"][1:]), m["total_minutes"]))
    t = [head, ""]
    if bake_rows:
        t += ["**Bake** (`swell-bake SCENE -o C --threads 1 --json --set ...`; then `swell-cache verify` "
              "and a NaN scan of every frame with `tools/swell_cache.py`). Conservation: water count at "
              "start -> end (and inside the tank at the end), volume from the mean number density of "
              "the interior water (end / start - 1), energy drift = (kinetic + potential) end / start - 1 "
              "(it includes the piston's and inflow's work and viscous losses; only the still tank "
              "should keep it).", "",
              bl.md_table(bake_rows, [
                  ("sweep", "sweep"), ("case", "case"), ("scene", lambda r: "`%s`" % r["scene"]),
                  ("particles", lambda r: r.get("particles", "-")), ("steps", lambda r: r.get("steps")),
                  ("outcome", lambda r: r["outcome"]),
                  ("water start -> end (in tank)", lambda r: "%s -> %s (%s)" % (
                      r["water_start"], r["water_end"], r["in_tank_end"]) if r.get("water_start") else "-"),
                  ("volume change", lambda r: r.get("volume_change")),
                  ("energy drift", lambda r: r.get("energy_drift")),
                  ("max Courant", lambda r: r.get("max_courant")),
                  ("NaN in cache", lambda r: r.get("nonfinite")),
                  ("Miche warning", lambda r: r.get("warning") or "-"),
                  ("wall s", "wall_s")]), ""]
    if replay_rows:
        t += ["**Replay** (`swell-play bench CACHE --json ...` on the surging_small bake and on "
              "`swell-cache synth` caches of one frame and of frames without surface particles; ok = "
              "exit 0, finite, within 1e-4 of the depth of the double-precision CPU reference and the "
              "same frame choice; clear error = exit 2 (README, \"exit status\") with one stderr line). The quick cases are also "
              "ctest tests (`PlayStress.*`, tests/runtime/play_stress_test.cpp).", "",
              bl.md_table(replay_rows, [
                  ("case", "case"), ("expected", "expect"), ("outcome", "outcome"),
                  ("max error (m)", lambda r: r.get("max_abs_error")), ("fps", lambda r: r.get("fps")),
                  ("wall s", "wall_s"), ("command", lambda r: "`%s`" % r["command"])])]
    bl.replace_section(DOC, "stress", "\n".join(t))


# ---------------------------------------------------------------- durability
# Self-contained: durability_section() runs it and writes its own table (section "durability"
# of docs/validation.md). Lock trials between two real swell-bake processes, ENOSPC and EIO at
# every write site (SWELL_FAULT_INJECT, cache/include/swell/cache/checked_write.h), and resume
# across a rebuild.

DUR = os.path.join(OUT, "durability")


def _dur_files(d):
    """Every file under d: relative name -> bytes."""
    files = {}
    for root, _, names in os.walk(d):
        for n in names:
            p = os.path.join(root, n)
            with open(p, "rb") as f:
                files[os.path.relpath(p, d)] = f.read()
    return files


def _dur_error_lines(err):
    return [l for l in err.splitlines() if l.strip() and ": warning: " not in l]


def dur_lock_trials(trials, log):
    """A long bake holds the output; a second one must be refused naming its PID; after the first
    is killed with SIGKILL a third must run (the kernel released the lock)."""
    import signal
    import subprocess
    d = os.path.join(DUR, "lock")
    os.makedirs(d, exist_ok=True)
    out = os.path.join(d, "k.swell")
    refused = released = 0
    messages = []
    env = dict(os.environ, OMP_WAIT_POLICY="PASSIVE")
    for t in range(trials):
        a = subprocess.Popen([bl.exe("swell-bake"), scene("surging_small.json"), "-o", out, "--set",
                              "solver.end_time=100", "--threads", "1", "-q"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
        tmp = "%s.tmp-%d" % (out, a.pid)
        deadline = time.monotonic() + 60
        while not os.path.exists(tmp) and time.monotonic() < deadline and a.poll() is None:
            time.sleep(0.01)  # the temporary cache exists once the lock is held
        b = bl.run([bl.exe("swell-bake"), scene("surging_small.json"), "-o", out, "--set",
                    "solver.end_time=0.1", "-q"], timeout=120, log=log)
        lines = _dur_error_lines(b.err)
        if b.rc == 6 and len(lines) == 1 and ("in use by process %d " % a.pid) in lines[0]:
            refused += 1
            messages.append(lines[0])
        a.send_signal(signal.SIGKILL)
        a.wait()
        c = bl.run([bl.exe("swell-bake"), scene("surging_small.json"), "-o", out, "--set",
                    "solver.end_time=0.1", "-q"], timeout=120, log=log)
        if c.rc == 0 and not any(".tmp-" in n for n in os.listdir(d)):
            released += 1
    return {"trials": trials, "refused": refused, "released": released,
            "message": messages[0] if messages else "-"}


def _dur_sites():
    """(group, site, make-good-command, faulted-command, file named) per write site."""
    bake = [bl.exe("swell-bake"), scene("surging_small.json"), "--threads", "1", "-q"]
    bdir = os.path.join(DUR, "bake")
    bake_good = bake + ["-o", os.path.join(bdir, "s.swell"), "--probes", os.path.join(bdir, "s.csv"),
                        "--set", "solver.end_time=0.4"]
    # The faulted bakes are shorter (a cache or probes they wrote would differ from the good ones);
    # only the checkpoint's writes checkpoints (which a bake rightly replaces as it goes).
    bake_bad = bake + ["-o", os.path.join(bdir, "s.swell"), "--probes", os.path.join(bdir, "s.csv"),
                       "--set", "solver.end_time=0.3"]
    synth = os.path.join(DUR, "synth.swell")
    small = ["--res", "48x32", "--slices", "16", "--seconds", "0.2", "--fps", "20", "--window", "all"]
    play = lambda cmd, d, extra: [bl.exe("swell-play"), cmd, synth, "--out", os.path.join(DUR, d)] + \
        small + extra
    h_png = play("heights", "heights_png", [])
    h_exr = play("heights", "heights_exr", ["--format", "exr-half", "--normals", "--blender-disp"])
    render = play("render", "render", ["--size", "160x90", "--export", "heights,mesh,splashes",
                                       "--splash-count", "2"])
    sites = [("bake", "cache", bake_good, bake_bad, ".swell.tmp", bdir),
             ("bake", "checkpoint", bake_good, bake_bad + ["--checkpoint-every", "50"], ".ckpt.tmp",
              bdir),
             ("bake", "probes CSV", bake_good, bake_bad, ".csv.tmp", bdir)]
    for name, cmd, d, files in [
            ("heights png16", h_png, "heights_png", ["height_00002.png", "heights.json"]),
            ("heights exr-half", h_exr, "heights_exr",
             ["height_00001.exr", "normal_00003.exr", "disp_0001.exr", "heights.json"]),
            ("render", render, "render",
             ["frame_00002.png", "contact_sheet.png", "render.json", "heights/height_00001.png",
              "heights/heights.json", "mesh/surface_00003.ply", "splashes/splashes_00000.ply"])]:
        for f in files:
            sites.append((name, f, cmd + ["--seed", "1"], cmd + ["--seed", "2"], f,
                          os.path.join(DUR, d)))
    return sites


def dur_faults(log):
    """ENOSPC and EIO at every write site, at the file's first byte, after 100 bytes and halfway
    through it: one clear line naming the file, non-zero exit, the previous files unchanged, no
    temporary left."""
    import shutil
    shutil.rmtree(DUR, ignore_errors=True)
    os.makedirs(os.path.join(DUR, "bake"), exist_ok=True)
    bl.run([bl.exe("swell-cache"), "synth", os.path.join(DUR, "synth.swell"), "--frames", 40],
           timeout=60, log=log)
    rows = []
    made = set()
    for group, site, good, bad, match, d in _dur_sites():
        if (group, d) not in made or group == "bake":
            g = bl.run(good, timeout=600, log=log)
            if g.rc != 0:
                raise SystemExit("tools/stress: durability: %s failed: %s" % (" ".join(good),
                                                                               g.last_err_line()))
            made.add((group, d))
        before = _dur_files(d)
        size = max([len(b) for n, b in before.items() if match in n] or [0])
        if group == "bake":  # the good bake removed its checkpoint: put one back
            ckpt = os.path.join(d, "s.swell.ckpt")
            with open(ckpt, "wb") as f:
                f.write(b"previous checkpoint")
            before = _dur_files(d)
            size = {"cache": len(before["s.swell"]), "probes CSV": len(before["s.csv"])}.get(
                site, 20000)
        row = {"group": group, "site": site, "runs": 0, "clear": 0, "damaged": 0, "left": 0,
               "example": "-"}
        for kind in ("enospc", "eio"):
            for after in sorted({0, min(100, size // 2), size // 2}):
                env = {"SWELL_FAULT_INJECT": "%s:after=%d:match=%s" % (kind, after, match)}
                r = bl.run(bad, timeout=600, env=env, log=log)
                lines = _dur_error_lines(r.err)
                reason = "Input/output error" if kind == "eio" else "No space left on device"
                named = os.path.basename(match.strip(".")) if group == "bake" else match
                clear = (r.rc not in (0, None) and len(lines) == 1 and reason in lines[0] and
                         (named.split(".")[0] in lines[0]))
                now = _dur_files(d)
                damaged = sum(1 for n, b in before.items() if now.get(n) != b)
                left = sum(1 for n in now if ".tmp-" in n) + len(set(now) - set(before))
                row["runs"] += 1
                row["clear"] += clear
                row["damaged"] += damaged
                row["left"] += left
                if clear and row["example"] == "-":
                    row["example"] = lines[0].replace(DUR + "/", "")
        rows.append(row)
        print("  %-18s %-28s %d/%d clear, %d damaged, %d left" % (
            group, site, row["clear"], row["runs"], row["damaged"], row["left"]), flush=True)
    return rows


def _dur_patch_numerics(path, version):
    """Rewrites a checkpoint as a swell-bake of another numerics version would have written it
    (the fingerprint's numerics_version; sizes and checksums redone)."""
    import struct
    import xxhash
    import zstandard
    with open(path, "rb") as f:
        data = f.read()
    raw = zstandard.ZstdDecompressor().decompress(data[48:], max_output_size=1 << 34)
    n = struct.unpack_from("<Q", raw, 0)[0]
    fp = json.loads(raw[8:8 + n])
    fp["numerics_version"] = version
    text = json.dumps(fp, separators=(",", ":")).encode()
    raw = struct.pack("<Q", len(text)) + text + raw[8 + n:]
    packed = zstandard.ZstdCompressor(level=3).compress(raw)
    head = bytearray(data[:48])
    struct.pack_into("<QQQ", head, 16, len(packed), len(raw), xxhash.xxh3_64_intdigest(packed))
    struct.pack_into("<Q", head, 40, xxhash.xxh3_64_intdigest(bytes(head[:40])))
    with open(path, "wb") as f:
        f.write(bytes(head) + packed)


def dur_resume(log):
    """A bake killed after a checkpoint, resumed by another executable (the same build with one
    byte of its help text changed, so its file digest differs), with another thread count; and
    resumes that must be refused with the reason."""
    import shutil
    import signal
    import subprocess
    d = os.path.join(DUR, "resume")
    os.makedirs(d, exist_ok=True)
    rebuilt = os.path.join(d, "swell-bake-rebuilt")
    with open(bl.exe("swell-bake"), "rb") as f:
        binary = f.read()
    old = b"continue from CACHE.ckpt"
    assert binary.count(old) == 1, "help text to change not found in swell-bake"
    with open(rebuilt, "wb") as f:
        f.write(binary.replace(old, b"Continue from CACHE.ckpt"))
    os.chmod(rebuilt, 0o755)
    base = [scene("surging_small.json"), "--set", "solver.end_time=1.5", "-q"]
    ref = os.path.join(d, "ref.swell")
    bl.run([bl.exe("swell-bake")] + base + ["-o", ref, "--threads", "2"], timeout=600, log=log)
    rows = []

    def interrupted(out):
        for p in (out, out + ".ckpt"):
            if os.path.exists(p):
                os.remove(p)
        a = subprocess.Popen([bl.exe("swell-bake")] + base + ["-o", out, "--threads", "1",
                                                               "--checkpoint-every", "100"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 120
        while not os.path.exists(out + ".ckpt") and time.monotonic() < deadline and a.poll() is None:
            time.sleep(0.005)
        a.send_signal(signal.SIGKILL)
        a.wait()
        return os.path.exists(out + ".ckpt") and not os.path.exists(out)

    out = os.path.join(d, "s.swell")
    cases = [("another executable (help text changed), 2 threads instead of 1", [rebuilt, "--threads", "2"],
              None, "accepted"),
             ("same build, another --set", [bl.exe("swell-bake"), "--threads", "1", "--set",
                                            "physics.kinematic_viscosity=1e-6"], None, "refused"),
             ("checkpoint of another numerics version", [rebuilt, "--threads", "1"], 0, "refused")]
    for label, cmd, numerics, expect in cases:
        ok_kill = interrupted(out)
        if numerics is not None:
            _dur_patch_numerics(out + ".ckpt", numerics)
        r = bl.run([cmd[0]] + base + ["-o", out, "--resume", "--json"] + cmd[1:], timeout=600, log=log)
        lines = _dur_error_lines(r.err)
        if expect == "accepted":
            same = r.rc == 0 and open(out, "rb").read() == open(ref, "rb").read()
            resumed = r.json.get("resumed_from_step") if r.json else None
            outcome = ("resumed from step %s; cache byte-identical to the uninterrupted bake" % resumed
                       if same else "FAIL: exit %s: %s" % (r.rc, r.last_err_line()))
            ok = same and ok_kill
        else:
            ok = ok_kill and r.rc == 5 and len(lines) == 1 and os.path.exists(out + ".ckpt")
            outcome = ("refused (exit 5): " + lines[0].split(".ckpt: ", 1)[-1]) if ok else \
                "FAIL: exit %s: %s" % (r.rc, r.last_err_line())
        rows.append({"case": label, "expect": expect, "outcome": outcome, "ok": ok})
        print("  %-66s %s" % (label, outcome[:100]), flush=True)
    shutil.rmtree(d, ignore_errors=True)
    return rows


def durability_section(args, log, docs_too):
    t0 = time.monotonic()
    lock = dur_lock_trials(args.lock_trials, log)
    print("  lock: %d/%d second writers refused, %d/%d bakes ran after SIGKILL of the holder" % (
        lock["refused"], lock["trials"], lock["released"], lock["trials"]), flush=True)
    faults = dur_faults(log)
    resume = dur_resume(log)
    minutes = (time.monotonic() - t0) / 60
    ok = (lock["refused"] == lock["trials"] and lock["released"] == lock["trials"] and
          all(r["clear"] == r["runs"] and r["damaged"] == 0 and r["left"] == 0 for r in faults) and
          all(r["ok"] for r in resume))
    if docs_too:
        m = bl.machine()
        runs = sum(r["runs"] for r in faults)
        t = ["Generated by `tools/stress --only durability` on %s: %s, %d cores; commit %s. %.1f min." % (
                 m["date"], m["cpu"], m["cores"], m["commit"], minutes), "",
             "**Lock** (`swell-bake` to an output a running `swell-bake` holds; then SIGKILL of the "
             "holder and a third bake): %d of %d second writers refused (exit 6, one line naming the "
             "holder's PID), %d of %d bakes ran at once after the holder was killed. Message: `%s`" % (
                 lock["refused"], lock["trials"], lock["released"], lock["trials"],
                 lock["message"].replace(DUR + "/", "")), "",
             "**ENOSPC and EIO at every write site** (`SWELL_FAULT_INJECT=enospc|eio:after=N:match=FILE`, "
             "N = 0, 100 and half the file's size; after a good run, the faulted run writes other "
             "content). Clear = non-zero exit and one stderr line naming the file and the reason; "
             "damaged = files of the previous good run changed or gone; left = temporaries or new "
             "files left: %d runs, %d clear, %d damaged, %d left." % (
                 runs, sum(r["clear"] for r in faults), sum(r["damaged"] for r in faults),
                 sum(r["left"] for r in faults)), "",
             bl.md_table(faults, [("program", "group"), ("write site", "site"), ("runs", "runs"),
                                  ("clear errors", "clear"), ("damaged", "damaged"),
                                  ("left behind", "left"),
                                  ("first message", lambda r: "`%s`" % r["example"])]), "",
             "**Resume across a rebuild** (`swell-bake scenes/surging_small.json --set solver.end_time=1.5` "
             "killed with SIGKILL after a checkpoint (`--checkpoint-every 100`), then `--resume`):", "",
             bl.md_table(resume, [("case", "case"), ("expected", "expect"), ("outcome", "outcome")])]
        bl.replace_section(DOC, "durability", "\n".join(t))
    return ok


if __name__ == "__main__":
    main()
