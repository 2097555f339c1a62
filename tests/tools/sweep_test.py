#!/usr/bin/python3
"""The sweep workflow end to end (tools/sweep, docs/sweeps.md), on the CI config
tools/sweep/ci.yaml (2 cases x 2 seeds) with -j 2:

1. the sweep runs and its table has one row per (case, seed) with finite fps and errors;
2. after one bench JSON is deleted, a dry run plans exactly that bench (plus the table), the
   rerun runs only it, and every other output keeps its modification time;
3. then nothing is left to do;
4. a config naming a missing scene, or repeating a case name, or with a non-integer seed,
   fails before anything runs with one line naming the problem.

Usage: sweep_test.py BIN_DIR [SNAKEMAKE]   (BIN_DIR holds swell-bake and swell-play)
Standard library only. Exits non-zero on any failure."""

import csv
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SNAKEFILE = os.path.join(ROOT, "tools", "sweep", "Snakefile")
CI_CONFIG = os.path.join(ROOT, "tools", "sweep", "ci.yaml")
CASES = ["surging", "ripple"]
SEEDS = [1, 2]


class Failure(Exception):
    pass


def check(condition, message):
    if not condition:
        raise Failure(message)


def snakemake(tool, bin_dir, out, workdir, *extra, config=CI_CONFIG, expect_ok=True):
    cmd = [tool, "-s", SNAKEFILE, "-j", "2", "-d", workdir, "--configfile", config,
           "--config", f"bin={bin_dir}", f"out={out}", *extra]
    run = subprocess.run(cmd, capture_output=True, text=True)
    text = run.stdout + run.stderr
    if expect_ok and run.returncode != 0:
        raise Failure(f"{' '.join(cmd)} exited {run.returncode}:\n{text}")
    return run.returncode, text


def job_counts(text):
    """Snakemake's 'Job stats' table: {rule: count}, without the total."""
    m = re.search(r"Job stats:\n(.*?)\n\n", text + "\n\n", re.S)
    check(m is not None, f"no 'Job stats' table in:\n{text}")
    counts = {}
    for line in m.group(1).splitlines():
        row = re.match(r"^(\w+)\s+(\d+)\b", line)
        if row and row.group(1) != "total":
            counts[row.group(1)] = int(row.group(2))
    return counts


def read_table(out):
    with open(os.path.join(out, "table.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    keys = sorted((r["case"], int(r["seed"])) for r in rows)
    check(keys == sorted((c, s) for c in CASES for s in SEEDS), f"table rows {keys}")
    for r in rows:
        where = f"table row {r['case']} seed {r['seed']}"
        fps = float(r["fps"])
        check(math.isfinite(fps) and fps > 0, f"{where}: fps {r['fps']}")
        for col in ("max_abs_error", "rms_error", "bake_s"):
            check(math.isfinite(float(r[col])), f"{where}: {col} {r[col]}")
        check(int(r["particles_water"]) > 0, f"{where}: particles_water {r['particles_water']}")
        check(r["renderer"] != "", f"{where}: no renderer")
    with open(os.path.join(out, "table.md")) as f:
        md = f.read().splitlines()
    check(len(md) == 2 + len(rows), f"table.md has {len(md)} lines for {len(rows)} rows")
    return rows


def outputs(out):
    files = [os.path.join(out, "caches", f"{c}.swell") for c in CASES]
    files += [os.path.join(out, "bake", f"{c}.json") for c in CASES]
    files += [os.path.join(out, "bench", c, f"seed{s}.json") for c in CASES for s in SEEDS]
    return files


def bad_configs(tool, bin_dir, tmp):
    with open(CI_CONFIG) as f:
        good = f.read()
    cases = [
        ("missing scene", good.replace("scenes/ripple_small.json", "scenes/no_such_scene.json"),
         "scene file .*no_such_scene.json does not exist"),
        ("duplicate case", good.replace("name: ripple", "name: surging"), "duplicate case name"),
        ("non-integer seed", good.replace("seeds: [1, 2]", "seeds: [1, 2.5]"), "seed 2.5 is not an integer"),
    ]
    for label, text, expected in cases:
        check(text != good, f"{label}: the CI config changed, update this test")
        path = os.path.join(tmp, "bad.yaml")
        with open(path, "w") as f:
            f.write(text)
        out = os.path.join(tmp, "bad-out")
        rc, log = snakemake(tool, bin_dir, out, os.path.join(tmp, "bad-wd"), "-n", config=path, expect_ok=False)
        check(rc != 0, f"{label}: snakemake accepted the config")
        check(re.search("sweep config: .*" + expected, log), f"{label}: no message /{expected}/ in:\n{log}")
        check(not os.path.exists(out), f"{label}: something was written to {out}")
        print(f"bad config ({label}): refused")


def main(argv):
    if len(argv) not in (2, 3):
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    bin_dir = os.path.abspath(argv[1])
    tool = argv[2] if len(argv) == 3 else "snakemake"
    check(shutil.which(tool) is not None, f"{tool} not found (tools/setup installs Debian's snakemake)")
    tmp = tempfile.mkdtemp(prefix="swell-sweep-test-")
    try:
        out, wd = os.path.join(tmp, "out"), os.path.join(tmp, "wd")

        snakemake(tool, bin_dir, out, wd)
        read_table(out)
        print("sweep: table has every (case, seed) row with finite fps and errors")

        victim = os.path.join(out, "bench", "ripple", "seed2.json")
        before = {p: os.stat(p).st_mtime_ns for p in outputs(out) if p != victim}
        os.remove(victim)
        _, plan = snakemake(tool, bin_dir, out, wd, "-n")
        check(job_counts(plan) == {"all": 1, "bench": 1, "collect": 1}, f"dry run plans {job_counts(plan)}")
        check("wildcards: case=ripple, seed=2" in plan, f"dry run does not plan ripple seed 2:\n{plan}")
        _, log = snakemake(tool, bin_dir, out, wd)
        check(job_counts(log) == {"all": 1, "bench": 1, "collect": 1}, f"rerun ran {job_counts(log)}")
        check(os.path.isfile(victim), "the deleted bench JSON was not made again")
        after = {p: os.stat(p).st_mtime_ns for p in before}
        changed = [p for p in before if before[p] != after[p]]
        check(not changed, f"the rerun touched finished outputs: {changed}")
        read_table(out)
        print("resume: only the missing bench ran; every other output untouched")

        _, plan = snakemake(tool, bin_dir, out, wd, "-n")
        check("Nothing to be done" in plan, f"a finished sweep still plans jobs:\n{plan}")

        bad_configs(tool, bin_dir, tmp)
    except Failure as e:
        print(f"sweep_test: FAILED: {e}", file=sys.stderr)
        print(f"sweep_test: outputs kept in {tmp}", file=sys.stderr)
        return 1
    shutil.rmtree(tmp)
    print("sweep_test: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
