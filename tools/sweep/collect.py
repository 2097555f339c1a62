#!/usr/bin/python3
"""Collects a sweep's swell-bake and swell-play bench JSONs into one table (docs/sweeps.md).

One row per (case, seed), written as CSV (every column, for scripts and spreadsheets) and as a
Markdown table (the columns a reader compares, rendered by GitHub and readable in a terminal).
Both files are written to a temporary name and renamed, so neither is ever half written.

The Snakefile calls write_tables() from its `collect` rule. Standalone, from a manifest:
    /usr/bin/python3 tools/sweep/collect.py MANIFEST.json TABLE.csv TABLE.md
where MANIFEST.json is a list of {case, scene, overrides, bench_args, seed, bake_json, bench_json}.
Standard library only."""

import csv
import io
import json
import math
import os
import sys

# (column, source, key path, format for the Markdown table or None to leave it out there)
COLUMNS = [
    ("case", "row", "case", "{}"),
    ("scene", "row", "scene", "{}"),
    ("overrides", "row", "overrides", "{}"),
    ("seed", "row", "seed", "{}"),
    ("particles_water", "bake", "particles_water", "{}"),
    ("particles_wall", "bake", "particles_wall", None),
    ("bake_steps", "bake", "steps", None),
    ("bake_frames", "bake", "frames", None),
    ("bake_s", "bake", "wall_seconds", "{:.2f}"),
    ("bake_ms_per_step", "bake", "ms_per_step", None),
    ("ppe_iterations_mean", "bake", "ppe_iterations_mean", None),
    ("energy_drift", "bake", "conservation.energy_drift", None),
    ("water_lost", "bake", "conservation.water_lost", None),
    ("cache_bytes", "bake", "cache_bytes", None),
    ("steady_start_s", "bake", "replay.steady_start_s", None),
    ("bench_args", "row", "bench_args", None),
    ("mode", "bench", "mode", None),
    ("res", "bench", "res", "{}"),
    ("slices", "bench", "slices", None),
    ("timed_frames", "bench", "timed_frames", None),
    ("fps", "bench", "fps", "{:.1f}"),
    ("frame_ms_mean", "bench", "frame_ms_mean", None),
    ("frame_ms_median", "bench", "frame_ms_median", "{:.3f}"),
    ("frame_ms_p95", "bench", "frame_ms_p95", "{:.3f}"),
    ("error_frames", "bench", "error_frames", None),
    ("max_abs_error", "bench", "max_abs_error", "{:.2e}"),
    ("max_rel_error", "bench", "max_rel_error", None),
    ("rms_error", "bench", "rms_error", "{:.2e}"),
    ("cpu_reference_fps", "bench", "cpu_reference_fps", None),
    ("renderer", "bench", "renderer", "{}"),
    ("llvmpipe_threads", "bench", "llvmpipe_threads", None),
]


def lookup(data, path):
    for key in path.split("."):
        if not isinstance(data, dict) or key not in data:
            return None
        data = data[key]
    return data


def cell(value):
    if value is None:
        return ""
    if isinstance(value, list):
        return "x".join(str(v) for v in value)
    return str(value)


def load(path):
    with open(path, encoding="utf-8") as f:
        try:
            return json.load(f)
        except json.JSONDecodeError as e:
            raise SystemExit(f"collect: {path}: not a JSON object ({e})")


def table_rows(rows):
    bakes = {}
    out = []
    for r in rows:
        if r["bake_json"] not in bakes:
            bakes[r["bake_json"]] = load(r["bake_json"])
        sources = {"row": r, "bake": bakes[r["bake_json"]], "bench": load(r["bench_json"])}
        out.append({col: lookup(sources[src], key) for col, src, key, _ in COLUMNS})
    return out


def markdown(rows):
    cols = [(c, fmt) for c, _, _, fmt in COLUMNS if fmt is not None]
    lines = ["| " + " | ".join(c for c, _ in cols) + " |", "|" + "|".join("---" for _ in cols) + "|"]
    for row in rows:
        cells = []
        for c, fmt in cols:
            v = row[c]
            if v is None or isinstance(v, list) or (isinstance(v, float) and not math.isfinite(v)):
                text = cell(v)
            else:
                text = fmt.format(v)
            cells.append(text.replace("|", "\\|") or " ")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def write_atomic(path, text):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8", newline="") as f:
        f.write(text)
    os.replace(tmp, path)


def write_tables(rows, csv_path, md_path):
    data = table_rows(rows)
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow([c for c, _, _, _ in COLUMNS])
    for row in data:
        writer.writerow([cell(row[c]) for c, _, _, _ in COLUMNS])
    write_atomic(csv_path, buf.getvalue())
    write_atomic(md_path, markdown(data))


def main(argv):
    if len(argv) != 4:
        print(__doc__.split("\n\n")[2], file=sys.stderr)
        return 2
    write_tables(load(argv[1]), argv[2], argv[3])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
