#!/usr/bin/python3
"""Concurrent use: eight `swell-play bench` processes at once and a bake beside them.

Every bench must get a GL context, finish, and match the double-precision CPU reference within
1e-4 of the water depth (bench's max_rel_error); the bake must finish with a valid cache. On the
2-core CI machine the eleven processes share two cores, so this also exercises llvmpipe's
threads under oversubscription. Usage: concurrent_use_test.py BIN_DIR SCENES_DIR
"""
import json
import os
import subprocess
import sys
import tempfile

BENCHES = 8


def main():
    bin_dir, scenes = sys.argv[1], sys.argv[2]
    play = os.path.join(bin_dir, "swell-play")
    with tempfile.TemporaryDirectory(prefix="swell_concurrent_") as tmp:
        cache = os.path.join(tmp, "wave.swell")
        subprocess.run([os.path.join(bin_dir, "swell-cache"), "synth", cache, "--frames", "600",
                        "--surface", "300", "--splash", "2"], check=True,
                       stdout=subprocess.DEVNULL)
        env = dict(os.environ, OMP_WAIT_POLICY="PASSIVE")
        bake = subprocess.Popen(
            [os.path.join(bin_dir, "swell-bake"), os.path.join(scenes, "still_tank_small.json"),
             "-o", os.path.join(tmp, "tank.swell"), "--set", "solver.end_time=1.0", "--json",
             "--threads", "2"],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
        benches = []
        for seed in range(1, BENCHES + 1):
            benches.append(subprocess.Popen(
                [play, "bench", cache, "--res", "96x64", "--frames", "60", "--warmup", "5",
                 "--error-frames", "4", "--cpu-frames", "1", "--seed", str(seed), "--json"],
                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env))
        failures = []
        for seed, p in enumerate(benches, start=1):
            out, err = p.communicate(timeout=600)
            if p.returncode != 0:
                failures.append(f"bench seed {seed}: exit {p.returncode}: {err.strip()}")
                continue
            j = json.loads(out)
            if j["seed"] != seed:
                failures.append(f"bench seed {seed}: reports seed {j['seed']}")
            if not j["max_rel_error"] <= 1e-4:
                failures.append(f"bench seed {seed}: max error {j['max_rel_error']} of depth")
            if not j["frames_exact"]:
                failures.append(f"bench seed {seed}: slice frames differ from the CPU's")
            print(f"bench seed {seed}: {j['fps']:.0f} fps, max error {j['max_rel_error']:.2e} "
                  f"of depth, {j['renderer']}")
        out, err = bake.communicate(timeout=600)
        if bake.returncode != 0:
            failures.append(f"bake: exit {bake.returncode}: {err.strip()}")
        else:
            verify = subprocess.run([os.path.join(bin_dir, "swell-cache"), "verify",
                                     os.path.join(tmp, "tank.swell")],
                                    capture_output=True, text=True)
            if verify.returncode != 0:
                failures.append(f"bake: cache does not verify: {verify.stderr.strip()}")
            print(f"bake: {json.loads(out).get('frames', '?')} frames, verified")
        for f in failures:
            print("FAIL " + f)
        return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
