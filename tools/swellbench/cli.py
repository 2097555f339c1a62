"""Run time against error (docs/BENCHMARKS.md): bake accuracy against cost, replay accuracy against cost,
replay fidelity, compression against error, what the skips save and the render's speed. Writes
CSV files and PNG plots to out/bench/ and regenerates the marked tables in docs/BENCHMARKS.md.

Called by tools/bench (which installs and builds first). --quick: fewer and shorter runs
(under ten minutes on the 2-core project VM); the full variant takes longer (see README).
--members N: each bake check as an ensemble of N jittered members (default 1 with --quick, 3
for the full variant).
--docs-only: the tables and plots again from the CSV files of earlier runs, measuring nothing."""

import argparse
import json
import os
import shutil
import time

from . import bake, common as bl, compression, fidelity, render, replay, skips

# In the order they run; each module: CSVS, SECTIONS, PLOTS, run(ctx), table(rows, m), plot(rows, dir).
MODULES = {"bake": bake, "replay": replay, "fidelity": fidelity, "compression": compression,
           "skips": skips, "render": render}
BAKE_PARTS = bake.CSVS  # --only dam_break, ..., wet_dam_break, shoaling: one part


def parse_args(argv=None):
    ap = argparse.ArgumentParser(prog="tools/bench", description=__doc__.split("\n\n")[0].replace("\n", " "))
    ap.add_argument("--quick", action="store_true", help="fewer, shorter runs (< 10 min)")
    ap.add_argument("--only", default="",
                    help="comma list of sections: bake (or dam_break, still_tank, regular_wave, lobovsky, "
                         "standing_wave, solitary_wave, wet_dam_break, shoaling), replay, fidelity, compression, skips, render")
    ap.add_argument("--members", type=int, default=None,
                    help="bake checks as ensembles of N jittered members (swell-validate --ensemble N): "
                         "tables and the plot show mean and sd; 1: one unjittered record each "
                         "(default: 1 with --quick, 3 otherwise)")
    ap.add_argument("--no-docs", action="store_true", help="do not rewrite docs/BENCHMARKS.md")
    ap.add_argument("--docs-only", action="store_true",
                    help="measure nothing: rewrite the tables in docs/BENCHMARKS.md and the plots from "
                         "out/bench/*.csv and machine.json (the sections of the last run, or --only)")
    args = ap.parse_args(argv)
    if args.docs_only and args.no_docs:
        ap.error("--docs-only and --no-docs exclude each other")
    if args.docs_only and args.members is not None:
        ap.error("--docs-only measures nothing: it redraws the last run with its members")
    if args.members is None:
        args.members = 1 if args.quick else 3
    if not 1 <= args.members <= 64:
        ap.error("--members must be in 1..64 (swell-validate --ensemble's range), not %d" % args.members)
    args.only = set(filter(None, args.only.split(",")))
    unknown = args.only - set(MODULES) - set(BAKE_PARTS)
    if unknown:
        ap.error("unknown section(s): %s" % ", ".join(sorted(unknown)))
    return args


def selected(only):
    """{module name: bake parts or None} in running order."""
    out = {}
    for name in MODULES:
        if name == "bake":
            parts = [p for p in BAKE_PARTS if not only or "bake" in only or p in only]
            if parts:
                out[name] = parts
        elif not only or name in only:
            out[name] = None
    return out


def missing_bake_rows(chosen, no_docs, out=bl.OUT):
    """The bake tables are one block of docs/BENCHMARKS.md: a run of some bake parts rewrites it
    with the others' rows read back from out/bench/ (bake.run). Where one of those was never
    written there, or holds no rows, the rewrite would blank its table: refuse before measuring
    anything."""
    parts = chosen.get("bake")
    if no_docs or not parts:
        return
    absent = [p for p in BAKE_PARTS if p not in parts and not bl.read_csv(os.path.join(out, p + ".csv"))]
    if absent:
        raise SystemExit("tools/bench: the bake tables in docs/BENCHMARKS.md need every part's rows, and "
                         "out/bench/ has none for %s; run them too (--only bake), or add --no-docs"
                         % ", ".join(absent))


def measure(ctx, chosen):
    """Runs the chosen sections; returns (results {CSV or note name: rows or text}, sections run)."""
    results = {}
    for name, parts in chosen.items():
        module = MODULES[name]
        if name == "bake":
            results.update(module.run(ctx, parts))
            continue
        print("== %s" % {"replay": "replay sweeps", "fidelity": "replay fidelity"}.get(name, name), flush=True)
        results.update(module.run(ctx))
    return results


def describe_machine(ctx, variant, t_start, sections):
    if ctx.renderer is None:
        r = bl.run([bl.exe("swell-play"), "bench", ctx.cache, "--frames", 5, "--warmup", 0, "--error-frames", 1,
                    "--cpu-frames", 0, "--json"], 120)
        ctx.renderer = (r.json or {}).get("renderer")
    m = bl.machine(ctx.renderer)
    m.update({"variant": variant, "total_minutes": round((time.monotonic() - t_start) / 60, 1),
              "loads": ctx.loads, "sections": sections, "facts": ctx.facts})
    return m


def save(out, results):
    """Lists of rows as NAME.csv, texts (notes) as the file NAME."""
    for name, rows in results.items():
        if isinstance(rows, str):
            with open(os.path.join(out, name), "w") as f:
                f.write(rows)
        else:
            bl.write_csv(os.path.join(out, name + ".csv"), rows)


def publish(results, m, names, docs, out=bl.OUT):
    """Plots of the named sections into out/; with docs, their tables into docs/BENCHMARKS.md
    and their plots into docs/images/bench/."""
    for name in names:
        module = MODULES[name]
        module.plot(results, out)
        if not docs:
            continue
        for marker, text in module.table(results, m).items():
            bl.replace_section(bl.DOC, marker, text)
        for png in module.PLOTS:
            src = os.path.join(out, png + ".png")
            if os.path.exists(src):
                os.makedirs(bl.IMAGES, exist_ok=True)
                shutil.copy(src, os.path.join(bl.IMAGES, png + ".png"))


def main(argv=None):
    args = parse_args(argv)
    if args.docs_only:
        return docs_only(args)
    os.makedirs(bl.OUT, exist_ok=True)
    t_start = time.monotonic()
    variant = "quick" if args.quick else "full"
    with open(os.path.join(bl.OUT, "commands.log"), "w") as log:
        ctx = bl.Context(args.quick, log, members=args.members)
        ctx.note_load("start")
        print("tools/bench (%s): load average %s; log out/bench/commands.log" % (variant, bl.load_average()),
              flush=True)
        chosen = selected(args.only)
        missing_bake_rows(chosen, args.no_docs)
        ctx.bake_small_cache()
        results = measure(ctx, chosen)
        ctx.note_load("end")
        m = describe_machine(ctx, variant, t_start, list(chosen))
        m["members"] = args.members
    with open(os.path.join(bl.OUT, "machine.json"), "w") as f:
        json.dump(m, f, indent=1)
    save(bl.OUT, results)
    publish(results, m, chosen, not args.no_docs)
    print("tools/bench: done in %.1f min; CSV and PNG in out/bench/%s" % (
        m["total_minutes"], "" if args.no_docs else ", tables in docs/BENCHMARKS.md"), flush=True)
    return 0


def docs_only(args, out=bl.OUT):
    """The docs from out/bench/: the sections named by --only, else those of the last run
    (machine.json "sections"; from an older run, the CSV files written with its machine.json)."""
    path = os.path.join(out, "machine.json")
    if not os.path.exists(path):
        raise SystemExit("tools/bench --docs-only: no %s; run tools/bench first" % os.path.relpath(path, bl.ROOT))
    with open(path) as f:
        m = json.load(f)
    names = list(selected(args.only)) if args.only else m.get("sections") or written_with(out, path)
    results = {}
    for name in names:
        for csv_name in MODULES[name].CSVS:
            results[csv_name] = bl.read_csv(os.path.join(out, csv_name + ".csv"))
    results[bake.NOTE] = bake.load_note(out)
    names = [n for n in names if results.get(MODULES[n].CSVS[0])]
    absent = [p for p in BAKE_PARTS if not results.get(p)] if "bake" in names else []
    if absent:  # one block holds every bake table: it would lose theirs
        raise SystemExit("tools/bench --docs-only: out/bench/ has no rows for %s, and the bake tables in "
                         "docs/BENCHMARKS.md are rewritten together; run them first" % ", ".join(absent))
    if not names:
        raise SystemExit("tools/bench --docs-only: no CSV files in out/bench/ for these sections")
    publish(results, m, names, True, out)
    print("tools/bench --docs-only: %s regenerated in docs/BENCHMARKS.md from out/bench/ (run of %s)" % (
        ", ".join(names), m.get("date")), flush=True)
    return 0


def written_with(out, machine_json, slack=120):
    """Sections whose first CSV was written within slack seconds after machine.json."""
    t = os.path.getmtime(machine_json)
    names = []
    for name, module in MODULES.items():
        p = os.path.join(out, module.CSVS[0] + ".csv")
        if os.path.exists(p) and 0 <= os.path.getmtime(p) - t <= slack:
            names.append(name)
    return names
