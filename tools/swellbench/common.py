"""Shared helpers of tools/bench (this package) and tools/stress.py: running our programs
with a timeout, machine description, CSV / Markdown output, marked sections in docs, and the
Context every section of tools/bench measures with.

Run with Debian's /usr/bin/python3 (numpy, zstandard, matplotlib from tools/setup)."""

import csv
import datetime
import hashlib
import json
import os
import platform
import re
import statistics
import subprocess
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.path.join(ROOT, "build", "bin")
OUT = os.path.join(ROOT, "out", "bench")
SCENES = os.path.join(ROOT, "scenes")
DOC = os.path.join(ROOT, "docs", "BENCHMARKS.md")
IMAGES = os.path.join(ROOT, "docs", "images", "bench")


def exe(name):
    return os.path.join(BIN, name)


def scene(name):
    return os.path.join(SCENES, name)


def load_scene(name):
    with open(scene(name)) as f:
        return json.load(f)


def sets(d):
    """--set KEY=VALUE arguments of a dict."""
    out = []
    for k, v in d.items():
        out += ["--set", "%s=%s" % (k, v)]
    return out


class Run:
    """One finished command: rc (None on timeout), stdout, stderr, wall seconds, json."""

    def __init__(self, cmd, rc, out, err, wall, timed_out):
        self.cmd, self.rc, self.out, self.err, self.wall = cmd, rc, out, err, wall
        self.timed_out = timed_out
        self.json = None
        for line in reversed(out.strip().splitlines()):
            line = line.strip()
            if line.startswith("{"):
                try:
                    self.json = json.loads(line)
                except ValueError:
                    pass
                break

    def last_err_line(self):
        lines = [l for l in self.err.strip().splitlines() if l.strip()]
        return lines[-1] if lines else ""


def run(cmd, timeout=600, nice=5, env=None, log=None):
    """Runs cmd (a list) under `nice -n`, kills its process group after `timeout` s."""
    full = (["nice", "-n", str(nice)] if nice else []) + [str(c) for c in cmd]
    e = dict(os.environ)
    e.setdefault("OMP_WAIT_POLICY", "PASSIVE")
    if env:
        e.update(env)
    t0 = time.monotonic()
    p = subprocess.Popen(full, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=e,
                         encoding="utf-8", errors="replace", start_new_session=True)
    timed_out = False
    try:
        out, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        timed_out = True
        os.killpg(p.pid, 9)
        out, err = p.communicate()
    wall = time.monotonic() - t0
    r = Run(" ".join(str(c) for c in cmd), None if timed_out else p.returncode, out, err, wall,
            timed_out)
    if log:
        log.write("$ %s\n  rc %s, %.1f s%s\n" % (r.cmd, r.rc, wall,
                                                 ", TIMED OUT" if timed_out else ""))
        if r.rc not in (0, None) or timed_out:
            log.write("  stderr: %s\n" % r.last_err_line())
        log.flush()
    return r


def load_average():
    try:
        with open("/proc/loadavg") as f:
            return " ".join(f.read().split()[:3])
    except OSError:
        return "?"


def machine(renderer=None):
    cpu = "?"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                                capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "-uno"],
                               capture_output=True, text=True).stdout.strip()
        if dirty:
            commit += " (with uncommitted changes)"
    except OSError:
        commit = "?"
    try:
        mem = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
    except (ValueError, OSError):
        mem = 0
    return {
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "cpu": cpu,
        "cores": os.cpu_count(),
        "memory_gib": round(mem, 1),
        "os": platform.platform(),
        "renderer": renderer or "?",
        "commit": commit,
        "load_average": load_average(),
    }


def outcome(r):
    """'ok', or a run's exit status and last error line."""
    return "ok" if r.rc == 0 else "exit %s: %s" % (r.rc, r.last_err_line())


def median(values):
    """Median of the values that are not None, None when there are none."""
    values = [v for v in values if v is not None]
    return float(statistics.median(values)) if values else None


def dig(j, key):
    """j["a"]["b"] for key "a.b"; None where a part is missing."""
    for part in key.split("."):
        j = j.get(part) if isinstance(j, dict) else None
    return j


class Context:
    """What every section shares: the variant (quick), the members of each bake check (1: one
    unjittered record; N > 1: swell-validate --ensemble N), the command log, the load averages
    noted at each section's start, the output folder and the surging_small bake."""

    def __init__(self, quick, log, out=OUT, members=1):
        self.quick = quick
        self.members = members
        self.log = log
        self.out = out
        self.loads = []
        self.cache = None  # out/bench/surging_small.swell, baked by bake_small_cache()
        self.bake_summary = None  # swell-bake --json of that cache
        self.renderer = None  # the GL renderer, from the first swell-play run that names it
        self.facts = {}  # {section: what its docs text quotes from the runs}, into machine.json

    def note_load(self, what):
        self.loads.append((what, load_average(), time.strftime("%H:%M:%S")))

    def run(self, cmd, timeout=900):
        return run(cmd, timeout=timeout, log=self.log)

    def path(self, name):
        return os.path.join(self.out, name)

    def bake_small_cache(self):
        """Bakes scenes/surging_small.json into out/bench/surging_small.swell (every run)."""
        self.cache = self.path("surging_small.swell")
        r = self.run([exe("swell-bake"), scene("surging_small.json"), "-o", self.cache, "--threads",
                      "1", "--json", "-q"], 1800)
        if r.rc != 0:
            raise SystemExit("tools/bench: baking surging_small failed: " + r.last_err_line())
        self.bake_summary = r.json
        self.facts["surging_small"] = cache_facts(r.json)
        return self.cache

    def paper_cache(self):
        """The paper-scale surging bake (scenes/surging.json) in out/bench/, baked again only
        when the scene file or the solver's numerics version changed since the last one (a
        stamp beside the cache records both), so its figures are always the shipped scene's."""
        cache = self.path("surging.swell")
        stamp_path = cache + ".stamp.json"
        stamp = {"scene_sha256": file_sha256(scene("surging.json")),
                 "numerics_version": numerics_version()}
        try:
            with open(stamp_path) as f:
                fresh = json.load(f) == stamp and os.path.exists(cache)
        except (OSError, ValueError):
            fresh = False
        if not fresh:
            r = self.run([exe("swell-bake"), scene("surging.json"), "-o", cache, "--json", "-q"], 3600)
            if r.rc != 0:
                raise SystemExit("tools/bench: baking surging failed: " + r.last_err_line())
            with open(stamp_path, "w") as f:
                json.dump(stamp, f)
        return cache


def file_sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def numerics_version():
    """kNumericsVersion of the source tree (bake/include/swell/bake/numerics_version.h)."""
    path = os.path.join(ROOT, "bake", "include", "swell", "bake", "numerics_version.h")
    with open(path) as f:
        m = re.search(r"kNumericsVersion\s*=\s*(\d+)", f.read())
    if not m:
        raise SystemExit("tools/bench: no kNumericsVersion in " + path)
    return int(m.group(1))


def cache_facts(summary=None, cache=None):
    """Frames and mean surface particles of the surging_small bake: from swell-bake's summary,
    or (docs from earlier CSVs) read from the cache file itself."""
    if summary:
        return {"frames": summary.get("frames"), "steps": summary.get("steps"),
                "surface_mean": summary.get("surface_mean")}
    try:
        import swell_cache
        c = swell_cache.Cache(cache or os.path.join(OUT, "surging_small.swell"))
    except (ImportError, OSError, ValueError):
        return {}
    counts = [c.index[i][3] for i in range(len(c))]
    return {"frames": len(c), "steps": None,
            "surface_mean": sum(counts) / len(counts) if counts else None}


def header(m):
    """The first paragraph of most generated sections: command, machine, load, duration."""
    return ("Generated by `tools/bench%s` on %s: %s, %d cores, %s GiB; %s; renderer %s; commit %s. "
            "Load average %s at the start (other engineers' builds share the machine: wall times "
            "are upper bounds). The whole run took %.1f min. CSV and plots: `out/bench/`." % (
                quick_flag(m), m["date"], m["cpu"], m["cores"], m["memory_gib"], m["os"],
                m["renderer"], m["commit"], m["loads"][0][1], m["total_minutes"]))


def quick_flag(m):
    return " --quick" if m.get("variant") == "quick" else ""


def loads_text(m):
    return "; ".join("%s %s (%s)" % (w, l, t) for w, l, t in m["loads"])


def plural(n, one, many=None):
    return "%s %s" % (fmt(n), one if n == 1 else (many or one + "s"))


def combine(rows, spread):
    """One row from the rows of an ensemble's members (swell-validate --ensemble): each number the
    mean over the members that have it, and for each field in spread (a collection of names, or a
    test on the name) its sample sd too, as FIELD_sd (None with one member); any other value
    (text) the first member's. 'members' is the number of rows; 'outcome' the first member's
    that is not 'stable' (naming it), else 'stable'."""
    wanted = spread if callable(spread) else spread.__contains__
    out = {"members": len(rows)}
    for r in rows:
        for k, v in r.items():
            if k in out:
                continue
            values = [x.get(k) for x in rows]
            nums = [x for x in values if isinstance(x, (int, float)) and not isinstance(x, bool)]
            if nums and len(nums) == len([x for x in values if x is not None]):
                mean = sum(nums) / len(nums)
                out[k] = round(mean) if all(isinstance(x, int) for x in nums) else mean
                if wanted(k):
                    out[k + "_sd"] = statistics.stdev(nums) if len(nums) > 1 else None
            else:
                out[k] = v
    bad = [(m, r.get("outcome")) for m, r in enumerate(rows, 1) if r.get("outcome") != "stable"]
    if rows and "outcome" in rows[0]:
        out["outcome"] = "member %d: %s" % bad[0] if bad else "stable"
    return out


def read_csv(path):
    """Rows of an earlier run's CSV with numbers parsed back (empty: None)."""
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [{k: parse_cell(v) for k, v in r.items()} for r in csv.DictReader(f)]


def parse_cell(v):
    if v == "":
        return None
    for kind in (int, float):
        try:
            return kind(v)
        except ValueError:
            pass
    return {"True": True, "False": False}.get(v, v)


def write_csv(path, rows, fields=None):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    if fields is None:
        fields = []
        for r in rows:
            for k in r:
                if k not in fields:
                    fields.append(k)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)


def fmt(v, digits=3):
    """Number for a table: 3 significant digits, thousands separated; '-' for None."""
    if v is None or v == "":
        return "-"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, int):
        return "{:,}".format(v)
    if isinstance(v, float):
        if v != v:
            return "NaN"
        if v == 0:
            return "0"
        a = abs(v)
        if a >= 1e5 or a < 1e-3:
            return "{:.{}g}".format(v, digits - 1 if digits > 1 else 1).replace("e-0", "e-").replace("e+0", "e")
        if a >= 100:
            return "{:,.0f}".format(v)
        return "{:.{}g}".format(v, digits)
    return str(v)


def md_table(rows, columns):
    """columns: [(header, key or function of the row)]; a key whose row also has KEY_sd (an
    ensemble's spread, combine()) reads 'mean ± sd'."""
    head = "| " + " | ".join(h for h, _ in columns) + " |"
    sep = "|" + "|".join("---" for _ in columns) + "|"
    lines = [head, sep]
    for r in rows:
        cells = []
        for _, k in columns:
            v = k(r) if callable(k) else r.get(k)
            text = v if isinstance(v, str) else fmt(v)
            sd = None if callable(k) else r.get(k + "_sd")
            cells.append(text + " ± " + fmt(sd, 2) if isinstance(sd, float) and v is not None else text)
        lines.append("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
    return "\n".join(lines)


def replace_section(path, name, text):
    """Replaces (or appends) the text between <!-- bench:begin NAME --> and
    <!-- bench:end NAME --> in the Markdown file at path; the rest stays as it is."""
    begin, end = "<!-- bench:begin %s -->" % name, "<!-- bench:end %s -->" % name
    with open(path) as f:
        doc = f.read()
    block = "%s\n%s\n%s" % (begin, text.strip("\n"), end)
    pattern = re.compile(re.escape(begin) + ".*?" + re.escape(end), re.S)
    if pattern.search(doc):
        doc = pattern.sub(lambda _: block, doc)
    else:
        doc = doc.rstrip("\n") + "\n\n" + block + "\n"
    with open(path, "w") as f:
        f.write(doc)


def lower_bar(y, sd, logy):
    """The length of an error bar below y: sd, but on a log axis one that reaches zero or below
    is drawn down to (almost) zero, off the axis' bottom."""
    return min(sd, 0.999999 * y) if logy else sd


def plot(path, title, xlabel, ylabel, series, logx=False, logy=False, annotate=None, legend_extra=(),
         figsize=(6.4, 4.2), plain_x=False, legend_outside=False):
    """series: [(label, xs, ys)] or [(label, xs, ys, style)], style: keyword arguments of
    matplotlib's plot (color, linestyle, marker, ...) over the default "o-", and "yerr": one
    error bar per point (None: none); a label starting
    with "_" stays out of the legend. legend_extra: [(label, style)], legend entries without
    data (what a colour or a line style stands for). annotate: {label: [text per point]}.
    plain_x: x tick labels as plain numbers, minor ticks too (a log axis within a decade or two).
    legend_outside: the legend to the right of the axes, where it hides no point (many series).
    Writes a PNG; returns False when matplotlib is missing."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return False
    fig, ax = plt.subplots(figsize=figsize, dpi=100)
    floor = []  # the lowest point or bar end above zero: a log axis ends half below it
    for label, xs, ys, *style in series:
        kw = {"marker": "o", "linestyle": "-"}
        kw.update(style[0] if style else {})
        yerr = kw.pop("yerr", None) or [None] * len(ys)
        pts = [(x, y, e) for x, y, e in zip(xs, ys, yerr) if x is not None and y is not None and y == y]
        if not pts:
            continue
        line, = ax.plot([p[0] for p in pts], [p[1] for p in pts], label=label, **kw)
        bars = [p for p in pts if p[2]]
        if bars:
            ax.errorbar([p[0] for p in bars], [p[1] for p in bars],
                        yerr=[[lower_bar(p[1], p[2], logy) for p in bars], [p[2] for p in bars]],
                        fmt="none", ecolor=line.get_color(), capsize=3, linewidth=1)
            floor.extend(p[1] - p[2] for p in bars if p[1] - p[2] > 0)
        floor.extend(p[1] for p in pts)
        if annotate:
            for (x, y, _), a in zip(pts, annotate.get(label, [])):
                ax.annotate(a, (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7,
                            color=line.get_color() if style else None)
    for label, style in legend_extra:
        ax.plot([], [], label=label, **style)
    if logx:
        ax.set_xscale("log")
    if plain_x:
        from matplotlib.ticker import FuncFormatter
        for set_formatter in (ax.xaxis.set_major_formatter, ax.xaxis.set_minor_formatter):
            set_formatter(FuncFormatter(lambda v, _: "%g" % v))
    if logy:
        ax.set_yscale("log")
        if floor and min(floor) > 0:
            ax.set_ylim(bottom=0.5 * min(floor))  # a bar reaching zero runs off the bottom
    ax.set_title(title, fontsize=10)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
    if legend_outside:
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    else:
        ax.legend(fontsize=8)
    fig.tight_layout()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    fig.savefig(path)
    plt.close(fig)
    return True
