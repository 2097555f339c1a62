#!/usr/bin/env python3
"""The edges a user meets, swept: damaged caches, damaged scene files and JSON nested a million
levels deep, through every program, the C API and the Python module.

    tools/edges [--caches 300] [--scenes 140] [--seed 1] [--timeout 60]

Each input goes through each consumer once. A run is
  crash     killed by a signal (or a Python interpreter that died), other than SIGINT/SIGTERM;
  hang      no end within --timeout seconds;
  unclear   refused, but not with exactly one line on stderr (a traceback counts as unclear);
  silent    a damaged cache read whole without complaint while its checksums were left as
            damaged (every byte of a cache is under a checksum, so a reader of every frame
            must refuse any change: swell-cache verify, the Python module reading every frame,
            tools/swell_cache.py); the others read a part (info: the header and index, dump:
            one frame) and are counted as accepted when the damage lies elsewhere.
Damaged caches: half raw (bytes flipped, cut, inserted, repeated), half with the header and
index checksums recomputed so that the deeper checks are reached. Damaged scenes: the JSON of
scenes/surging_small.json with bytes flipped, cut or inserted, keys dropped, values replaced by
extreme numbers, wrong types or deep nesting. Writes out/edges/edges.json and prints a summary.
"""
import argparse
import json
import os
import random
import shutil
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from swellbench import common as bl  # noqa: E402

import xxhash  # noqa: E402

OUT = os.path.join(bl.ROOT, "out", "edges")
PY = "/usr/bin/python3"
PYPATH = os.path.join(bl.ROOT, "build", "python")
READER = os.path.join(bl.ROOT, "tools", "swell_cache.py")
DEEP = 1_000_000       # levels of nesting in files
DEEP_ARGUMENT = 60_000  # in a command-line argument (Linux caps one at 128 KiB)

PY_CACHE = """import sys, swell
try:
    c = swell.Cache(sys.argv[1])
    for i in range(len(c)):
        c[i]
    c.metadata
except (swell.CacheError, ValueError) as e:
    print("swell:", str(e).splitlines()[0] if str(e) else type(e).__name__, file=sys.stderr)
    sys.exit(1)
"""
PY_BAKE = """import sys, swell
try:
    swell.bake(sys.argv[1], sys.argv[2], overrides=["solver.end_time=0.02"])
except (swell.SceneError, swell.DivergenceError, swell.CacheError, ValueError, OSError) as e:
    print("swell:", str(e).splitlines()[0] if str(e) else type(e).__name__, file=sys.stderr)
    sys.exit(1)
"""
PY_DEEP_PARAMS = """import sys, swell
p = v = {}
for _ in range(%d):
    v["a"] = {}
    v = v["a"]
try:
    swell.Replay(swell.Cache(sys.argv[1]), cells=(8, 8), params=p)
except (ValueError, swell.CacheError, swell.GLError) as e:
    print("swell:", str(e).splitlines()[0], file=sys.stderr)
    sys.exit(1)
""" % DEEP


WHOLE_READERS = ("swell-cache verify", "python swell.Cache", "tools/swell_cache.py")


def verdict(r, damaged_unsealed):
    """crash / hang / unclear / silent / refused / accepted for one finished run."""
    if r.timed_out:
        return "hang"
    if r.rc is None or r.rc < 0 or (r.rc >= 128 and r.rc != 130):
        return "crash"
    if r.rc == 0:
        return "silent" if damaged_unsealed else "accepted"
    lines = [l for l in r.err.splitlines() if l.strip()]
    if len(lines) != 1 or "Traceback" in r.err:
        return "unclear"
    return "refused"


def cache_consumers(path):
    """(name, command) of every reader of a cache."""
    bench = [bl.exe("swell-play"), "bench", path, "--res", "16x16", "--frames", "2", "--warmup",
             "0", "--error-frames", "1", "--cpu-frames", "0", "--window", "all"]
    return [("swell-cache info", [bl.exe("swell-cache"), "info", path]),
            ("swell-cache info --json", [bl.exe("swell-cache"), "info", path, "--json"]),
            ("swell-cache verify", [bl.exe("swell-cache"), "verify", path]),
            ("swell-cache dump", [bl.exe("swell-cache"), "dump", path, "--frame", "0"]),
            ("swell-play bench", bench),
            ("swell-capi-bench (C API)", [bl.exe("swell-capi-bench"), path, "16", "2", "10"]),
            ("python swell.Cache", [PY, "-c", PY_CACHE, path]),
            ("tools/swell_cache.py", [PY, READER, path])]


def reseal(b):
    """Recomputes the header and index checksums of cache bytes `b` where they can be found."""
    if len(b) < 96:
        return b
    meta = struct.unpack_from("<I", b, 68)[0]
    count, index = struct.unpack_from("<QQ", b, 72)
    if 96 + meta <= len(b):
        struct.pack_into("<Q", b, 88, xxhash.xxh3_64_intdigest(bytes(b[:88]) + bytes(b[96:96 + meta])))
    end = index + 40 * count
    if count < 1 << 20 and end + 8 <= len(b):
        struct.pack_into("<Q", b, end, xxhash.xxh3_64_intdigest(bytes(b[index:end])))
    return b


def damage(data, rng):
    b = bytearray(data)
    kind = rng.choice(["flip", "flip", "cut", "insert", "repeat", "zero"])
    if kind == "flip":
        for _ in range(rng.randint(1, 8)):
            b[rng.randrange(len(b))] ^= 1 << rng.randrange(8)
    elif kind == "cut":
        del b[rng.randrange(1, len(b)):]
    elif kind == "insert":
        p = rng.randrange(len(b))
        b[p:p] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 64)))
    elif kind == "repeat":
        p = rng.randrange(len(b) - 16)
        b[p:p] = b[p:p + rng.randint(1, 200)]
    else:
        p = rng.randrange(len(b))
        b[p:p + rng.randint(1, 64)] = bytes(min(64, len(b) - p))
    return b, kind


def deep_cache(base, out):
    """`base` with its metadata replaced by an array DEEP levels deep, the checksums right."""
    b = bytearray(open(base, "rb").read())
    meta_len = struct.unpack_from("<I", b, 68)[0]
    count, index = struct.unpack_from("<QQ", b, 72)
    meta = b"[" * DEEP + b"]" * DEEP
    shift = len(meta) - meta_len
    frames = b[96 + meta_len:index]
    idx = bytearray(b[index:index + 40 * count])
    for i in range(count):
        off = struct.unpack_from("<Q", idx, 40 * i)[0]
        struct.pack_into("<Q", idx, 40 * i, off + shift)
    head = bytearray(b[:96])
    struct.pack_into("<I", head, 12, 96 + len(meta))
    struct.pack_into("<I", head, 68, len(meta))
    struct.pack_into("<Q", head, 80, index + shift)
    d = head + meta + frames + idx + struct.pack("<Q", xxhash.xxh3_64_intdigest(bytes(idx)))
    struct.pack_into("<Q", d, 88, xxhash.xxh3_64_intdigest(bytes(d[:88]) + meta))
    open(out, "wb").write(d)


def damaged_scene(text, rng):
    s = json.loads(text)
    kind = rng.choice(["bytes", "cut", "drop", "extreme", "type", "nest", "unknown"])
    keys = [(sec, k) for sec, v in s.items() if isinstance(v, dict) for k in v]
    if kind == "bytes":
        b = bytearray(text.encode())
        for _ in range(rng.randint(1, 6)):
            b[rng.randrange(len(b))] = rng.choice(b'{}[]":,0123456789-eE.xnul \x00\xff')
        return bytes(b), kind
    if kind == "cut":
        return text.encode()[:rng.randrange(len(text))], kind
    sec, k = rng.choice(keys)
    if kind == "drop":
        del s[sec][k]
    elif kind == "extreme":
        s[sec][k] = rng.choice([0, -1, 1e308, -1e308, 1e-308, 2 ** 64, 2 ** 31, 4294967297, 1e9, 1e-9])
    elif kind == "type":
        s[sec][k] = rng.choice(["text", [], {}, None, True, [1, 2, 3]])
    elif kind == "nest":
        return (json.dumps(s)[:-1] + ', "extra": ' + "[" * 70 + "]" * 70 + "}").encode(), kind
    else:
        s[sec]["no_such_key"] = 1
    return json.dumps(s).encode(), kind


def tally(rows):
    t = {}
    for r in rows:
        t[r["verdict"]] = t.get(r["verdict"], 0) + 1
    return t


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--caches", type=int, default=300)
    ap.add_argument("--scenes", type=int, default=140)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--timeout", type=int, default=60)
    args = ap.parse_args()
    for name in ("swell-cache", "swell-play", "swell-bake", "swell-validate", "swell-capi-bench"):
        if not os.path.exists(bl.exe(name)):
            sys.exit("tools/edges: no %s in build/bin (run tools/build)" % name)
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    rng = random.Random(args.seed)
    env = {"PYTHONPATH": PYPATH}
    rows = []

    def record(group, input_name, detail, consumer, cmd, unsealed=False):
        r = bl.run(cmd, timeout=args.timeout, nice=0, env=env)
        v = verdict(r, unsealed)
        rows.append({"group": group, "input": input_name, "detail": detail, "consumer": consumer,
                     "verdict": v, "rc": r.rc, "wall_s": round(r.wall, 2),
                     "err": (r.err.strip().splitlines() or [""])[-1][:300]})
        if v in ("crash", "hang", "unclear", "silent"):
            print("  %s: %s on %s (%s): rc %s: %s" % (v, consumer, input_name, detail, r.rc,
                                                      rows[-1]["err"]), flush=True)

    # Caches: a float32 and a quantized16 synthetic cache, damaged.
    bases = []
    for enc in ("float32", "quantized16"):
        p = os.path.join(OUT, "base_%s.swell" % enc)
        bl.run([bl.exe("swell-cache"), "synth", p, "--frames", "6", "--surface", "48", "--splash", "3",
                "--encoding", enc], nice=0)
        bases.append(open(p, "rb").read())
    path = os.path.join(OUT, "damaged.swell")
    for i in range(args.caches):
        sealed = i % 2 == 1
        b, kind = damage(rng.choice(bases), rng)
        if sealed:
            b = reseal(b)
        open(path, "wb").write(b)
        for consumer, cmd in cache_consumers(path):
            record("cache", "cache %d" % i, kind + (" resealed" if sealed else ""), consumer, cmd,
                   unsealed=not sealed and consumer in WHOLE_READERS)
    print("caches: %s" % tally([r for r in rows if r["group"] == "cache"]), flush=True)

    # Scenes: surging_small.json damaged, through swell-bake, swell-validate and swell.bake.
    text = open(bl.scene("surging_small.json")).read()
    scene = os.path.join(OUT, "damaged.json")
    baked = os.path.join(OUT, "scene.swell")
    for i in range(args.scenes):
        b, kind = damaged_scene(text, rng)
        open(scene, "wb").write(b)
        record("scene", "scene %d" % i, kind, "swell-bake",
               [bl.exe("swell-bake"), scene, "-o", baked, "--set", "solver.end_time=0.02", "-q"])
        record("scene", "scene %d" % i, kind, "swell-validate still-tank",
               [bl.exe("swell-validate"), "--set", "solver.end_time=0.02", "still-tank", scene,
                "--settle", "0.01"])
        record("scene", "scene %d" % i, kind, "python swell.bake", [PY, "-c", PY_BAKE, scene, baked])
    print("scenes: %s" % tally([r for r in rows if r["group"] == "scene"]), flush=True)

    # Nesting a million levels deep: a scene's name, a --set value, a cache's metadata, the
    # C API's params_json (through the Python module's params).
    deep_scene = os.path.join(OUT, "deep_scene.json")
    s = json.loads(text)
    body = json.dumps(s)
    open(deep_scene, "w").write(body[:-1] + ', "name": ' + "[" * DEEP + "]" * DEEP + "}")
    value = "name=" + "[" * DEEP_ARGUMENT + "]" * DEEP_ARGUMENT
    small = bl.scene("surging_small.json")
    for consumer, cmd in [
            ("swell-bake", [bl.exe("swell-bake"), deep_scene, "-o", baked, "-q"]),
            ("swell-bake --set", [bl.exe("swell-bake"), small, "-o", baked, "--set", value, "-q"]),
            ("swell-validate", [bl.exe("swell-validate"), "still-tank", deep_scene]),
            ("swell-validate --set", [bl.exe("swell-validate"), "--set", value, "still-tank", small]),
            ("python swell.bake", [PY, "-c", PY_BAKE, deep_scene, baked])]:
        record("nested", "scene %d deep" % DEEP, "", consumer, cmd)
    deep = os.path.join(OUT, "deep_metadata.swell")
    deep_cache(os.path.join(OUT, "base_float32.swell"), deep)
    for consumer, cmd in cache_consumers(deep):
        record("nested", "metadata %d deep" % DEEP, "", consumer, cmd)
    record("nested", "params %d deep" % DEEP, "", "python swell.Replay params (C API params_json)",
           [PY, "-c", PY_DEEP_PARAMS, os.path.join(OUT, "base_float32.swell")])
    print("nested: %s" % tally([r for r in rows if r["group"] == "nested"]), flush=True)

    bad = [r for r in rows if r["verdict"] in ("crash", "hang", "unclear", "silent")]
    summary = {"runs": len(rows), "by_group": {g: tally([r for r in rows if r["group"] == g])
                                               for g in ("cache", "scene", "nested")},
               "failures": len(bad), "seed": args.seed}
    json.dump({"summary": summary, "runs": rows}, open(os.path.join(OUT, "edges.json"), "w"), indent=1)
    print("tools/edges: %d runs, %d crashes, %d hangs, %d unclear, %d silent; out/edges/edges.json"
          % (len(rows), sum(r["verdict"] == "crash" for r in rows), sum(r["verdict"] == "hang" for r in rows),
             sum(r["verdict"] == "unclear" for r in rows), sum(r["verdict"] == "silent" for r in rows)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
