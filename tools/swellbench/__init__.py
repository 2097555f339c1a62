"""tools/bench as a package: run time against error, one module per section.

    common       helpers (running programs, machine, CSV, Markdown, marked doc sections, plots)
                 and the Context the sections share (quick flag, command log, loads, out/bench/)
    cli          the command line of tools/bench: section choice, machine.json, CSV, docs
    bake         both schemes: dam break, still tank, waves, Lobovsky -> dam_break/still_tank/regular_wave/lobovsky.csv
    replay       swell-play bench sweeps                     -> replay.csv
    fidelity     replay fidelity sweep and continuity        -> fidelity.csv, continuity.csv
    compression  encodings and filters against error         -> compression.csv
    skips        what each skipped stage saves               -> skips.csv
    render       shaded fps and stage costs                  -> render.csv

Every section module has the same three functions: run(ctx) -> {CSV name: rows} (the
measurements), table(rows, machine) -> {docs marker: Markdown} (its generated sections of
docs/BENCHMARKS.md, every count in the text taken from the rows, the run's JSON or the
parameters of its commands) and plot(rows, out_dir) (its PNG, if it has one); CSVS, SECTIONS
and PLOTS name its CSV files, docs markers and plots. Run it as tools/bench (python3 -m
swellbench with tools/ on the path)."""

import os
import sys

_TOOLS = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if _TOOLS not in sys.path:
    sys.path.insert(0, _TOOLS)  # swell_cache.py
