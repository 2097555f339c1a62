#!/usr/bin/python3
"""Peak memory of swell on long caches and large bakes (docs/BENCHMARKS.md).

Replays synthetic caches of 1,000, 10,000 and 100,000 frames (400 surface and 4 splash particles
per frame) with `swell-play bench`, `render`, `heights` and the C API (`swell-capi-bench`, whose
Playback holds every frame of its timeline), and bakes still tanks of 10k, 100k and 1M water
particles for a few steps. For each run: peak RSS of the process (wait4's ru_maxrss; on Mesa
llvmpipe the GL buffers are process memory too), the replay's own memory estimate (replay_memory.h)
and the bytes it uploaded to the GPU. Prints a Markdown table.

    /usr/bin/python3 tools/memory_bench.py [--bin build/bin] [--out out/memory] [--quick]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time


def run_rss(cmd):
    """(exit code, stdout, stderr, peak RSS bytes, wall seconds) of one process (wait4). Its
    output goes through files in a temporary folder of this call's own, removed after."""
    with tempfile.TemporaryDirectory(prefix="swell-memory-") as folder:
        out_path = os.path.join(folder, "out.json")
        err_path = os.path.join(folder, "err.txt")
        t0 = time.monotonic()
        pid = os.fork()
        if pid == 0:
            out = os.open(os.devnull if "--json" not in cmd else out_path,
                          os.O_WRONLY | os.O_CREAT | os.O_TRUNC)
            err = os.open(err_path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC)
            os.dup2(out, 1)
            os.dup2(err, 2)
            try:
                os.execv(cmd[0], cmd)
            finally:
                os._exit(127)
        _, status, usage = os.wait4(pid, 0)
        wall = time.monotonic() - t0
        code = os.waitstatus_to_exitcode(status)
        text = open(out_path).read() if "--json" in cmd else ""
        err = open(err_path).read()
    return code, text, err, usage.ru_maxrss * 1024, wall


def mib(b):
    return "-" if b is None else f"{b / 2**20:,.1f}"


def still_tank(path, particles, l0=0.01, depth=0.25):
    width = particles * l0 * l0 / depth
    scene = {
        "name": f"memory_tank_{particles}",
        "description": "tools/memory_bench.py: a still tank sized to hold the given water particles",
        "physics": {"density": 1000.0, "kinematic_viscosity": 1e-6, "gravity": 9.81},
        "geometry": {
            "particle_spacing": l0,
            "tank": {"x0": 0.0, "y0": 0.0, "x1": width, "y1": 2 * depth},
            "water": [{"x0": 0.0, "y0": 0.0, "x1": width, "y1": depth}],
        },
        "solver": {"dt": 0.001, "end_time": 0.02, "expected_speed": 0.1},
        "output": {"frame_interval": 0.01},
    }
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default="build/bin")
    ap.add_argument("--out", default="out/memory")
    ap.add_argument("--quick", action="store_true", help="1k and 10k frames, 10k and 100k particles")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    play = os.path.join(a.bin, "swell-play")
    rows = []
    frame_counts = [1000, 10000] if a.quick else [1000, 10000, 100000]
    for n in frame_counts:
        cache = os.path.join(a.out, f"synth_{n}.swell")
        if not os.path.exists(cache):
            subprocess.run([os.path.join(a.bin, "swell-cache"), "synth", cache, "--frames", str(n),
                            "--surface", "400", "--splash", "4"], check=True,
                           stdout=subprocess.DEVNULL)
        cases = [
            ("bench 128², 200 frames", [play, "bench", cache, "--res", "128x128", "--frames", "200",
                                       "--warmup", "10", "--error-frames", "1", "--cpu-frames", "1",
                                       "--json"]),
            ("render 640x360, 2 s", [play, "render", cache, "--size", "640x360", "--seconds", "2",
                                    "--out", os.path.join(a.out, f"render_{n}"), "--json"]),
            ("heights 128², 60 s", [play, "heights", cache, "--res", "128x128", "--seconds", "60",
                                   "--out", os.path.join(a.out, f"heights_{n}"), "--json"]),
            ("C API Playback 128² (whole timeline)",
             [os.path.join(a.bin, "swell-capi-bench"), cache, "128", "100", "100"]),
        ]
        for name, cmd in cases:
            code, out, err, rss, wall = run_rss(cmd)
            row = {"what": name, "size": f"{n:,} frames", "code": code, "rss": rss, "wall": wall}
            if code == 0 and out.strip().startswith("{") and "--json" in cmd:
                j = json.loads(out)
                mem = j.get("memory") or (j.get("params") or {}).get("memory")
                row["decoded"] = j.get("frames_decoded")
                row["uploaded"] = j.get("uploaded_bytes")
                if mem:
                    row["estimate"] = mem.get("estimate_bytes")
                    row["gpu"] = mem.get("gpu_bytes")
            elif code != 0:
                row["error"] = err.strip().splitlines()[-1] if err.strip() else f"exit {code}"
            rows.append(row)
            print(f"{name} {n}: exit {code}, peak RSS {mib(rss)} MiB, {wall:.1f} s", file=sys.stderr)
    particle_counts = [10000, 100000] if a.quick else [10000, 100000, 1000000]
    for n in particle_counts:
        scene = os.path.join(a.out, f"tank_{n}.json")
        still_tank(scene, n)
        out = os.path.join(a.out, f"tank_{n}.swell")
        cmd = [os.path.join(a.bin, "swell-bake"), scene, "-o", out, "--json"]
        code, text, err, rss, wall = run_rss(cmd)
        row = {"what": "swell-bake, 20 steps", "size": f"{n:,} water particles", "code": code,
               "rss": rss, "wall": wall}
        if code == 0:
            j = json.loads(text)
            row["particles"] = j.get("particles") or j.get("particle_count")
        else:
            row["error"] = err.strip().splitlines()[-1] if err.strip() else f"exit {code}"
        rows.append(row)
        print(f"bake {n}: exit {code}, peak RSS {mib(rss)} MiB, {wall:.1f} s", file=sys.stderr)

    print("| run | input | exit | peak RSS (MiB) | estimate (MiB) | of it GPU buffers (MiB) "
          "| uploaded (MiB) | frames decoded | wall (s) |")
    print("|---|---|---|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print(f"| {r['what']} | {r['size']} | {r['code']} | {mib(r['rss'])} | "
              f"{mib(r.get('estimate'))} | {mib(r.get('gpu'))} | {mib(r.get('uploaded'))} | "
              f"{r.get('decoded', '-')} | {r['wall']:.1f} |")
        if "error" in r:
            print(f"|  | error: {r['error']} |||||||")
    return 0 if all(r["code"] == 0 for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
