"""Bake accuracy against cost for the two MPS schemes (solver.scheme): "swell", the default
(Khayyer & Gotoh corrected gradient, neighbour-distribution free-surface test, mixed source with
particle shifting and inelastic collisions: docs/validation.md section 7.1), and
"textbook" (Koshizuka & Oka 1996). Every case runs both schemes at several particle spacings:
dam break against Martin & Moyce (raw and aligned front error), still-tank bed pressure,
regular waves against Biesel (full: also progressive waves over three wavelengths) and the
Lobovsky et al. 2014 dam break (water levels at four gauges), a standing wave against linear
theory (held out: period and decay per period), a solitary wave against Rayleigh's celerity
and Boussinesq's shape (held out) and a dam breaking onto a wet bed against Stoker's
shallow-water solution (held out: the bore's speed, the depth behind it, the depth at ten
gauges); full mode adds PPE tolerances for the default scheme. Every row has its wall time and
solver time per particle-step.

CSV: dam_break, still_tank, regular_wave (+ regular_wave.note), lobovsky, standing_wave,
solitary_wave, wet_dam_break, shoaling; docs section: bake."""

import math
import os

from . import common as bl

CSVS = ("dam_break", "still_tank", "regular_wave", "lobovsky", "standing_wave", "solitary_wave",
        "wet_dam_break", "shoaling")
NOTE = "regular_wave.note"
SECTIONS = ("bake",)
PLOTS = ("bake_error_vs_cost",)

DAM_SCENE, TANK_SCENE, WAVE_SCENE = "dam_break_small.json", "still_tank_small.json", "regular_wave_small.json"
PROGRESSIVE_SCENES = ("progressive_wave.json", "progressive_wave_deep.json")  # full mode, own l0 and dt
LOB_SCENES = {0.02: "lobovsky_small.json", 0.01: "lobovsky.json"}  # l0 -> the scene made for it
LOB_EXTRA = (0.0075, "lobovsky_small.json")  # full mode: H/40, tank height rounded to whole spacings
SLOSH_SCENES = ((25, "standing_wave_small.json"), (50, "standing_wave.json"))  # h/N -> scene; quick: h/25
SOLITARY_SCENES = ((10, "solitary_wave_small.json"), (20, "solitary_wave.json"))  # h/N -> scene; quick: h/10
WET_SCENES = ((20, "wet_dam_break_small.json"), (40, "wet_dam_break.json"))  # h0/N -> scene; quick: h0/20
SHOAL_SCENES = ((20, "shoaling_small.json"), (40, "shoaling.json"))  # h0/N -> scene; quick: h0/20
LOB_LIMIT_S = 60.0  # LOB_EXTRA runs when the l0 = 0.01 run predicts it under this (s)
DAM_DT = (0.0005, 0.005)  # dt = 0.5 ms at l0 = 5 mm, proportional to l0
WAVE_DT = ((0.04, 0.004), (0.02, 0.002), (0.0, 0.001))  # (l0 at least, dt): frames every 20 ms
SCHEMES = [("swell (default)", {}), ("textbook", {"solver.scheme": "textbook"})]
DEFAULT_SCHEME = SCHEMES[0][0]
# The figures of each case whose spread over an ensemble's members the tables and the plot show.
DAM_SPREAD = ("front_error_mean_a", "front_error_max_a", "aligned_front_error_mean_a",
              "aligned_front_error_max_a", "aligned_shift_T")
TANK_SPREAD = ("bed_pressure_ratio", "pressure_error", "max_speed_over_sqrt_gH")
SLOSH_SPREAD = ("period_error", "decay_per_period", "first_amplitude_over_theory")
SOLITARY_SPREAD = ("celerity_error", "first_amplitude_over_height", "decay_total", "mean_width_error")
WET_SPREAD = ("bore_speed_error", "plateau_depth_error", "mean_abs_error_over_h0_worst")
SHOAL_SPREAD = ("incident_crest_error", "crest_error_worst", "mean_abs_error_over_h0_worst", "travel_time_error")
WAVE_SPREAD = ("H_m", "height_error", "wavelength_error", "wavelength_fit_error", "decay_per_wavelength",
               "decay_total", "decay_total_fit")


def lobovsky_spread(field):
    """The Lobovsky figures with a spread: the worst gauge's and each gauge's mean error, and the
    far wall's pressure figures (sensor P1)."""
    return field.endswith("mean_abs_error_over_H") or field.startswith("p1_")


def scheme_of(r):
    """The scheme of a row (rows of runs before the schemes: their 'variant')."""
    return r.get("scheme") or r.get("variant")


def validate(ctx, kind, scene_name, settings, extra=(), timeout=900):
    """One swell-validate run: (Run, [each member's JSON]). With ctx.members > 1 it runs them as
    an ensemble (--ensemble N: seeds 1..N, the water jittered by 1e-6 l0) and each member's JSON
    gets the run's wall time over N as its wall_seconds; otherwise one unjittered record. A run
    that wrote no JSON gives one empty member."""
    ensemble = ["--ensemble", ctx.members] if ctx.members > 1 else []
    r = ctx.run([bl.exe("swell-validate"), "--json", "--threads", "1"] + bl.sets(settings) +
                [kind, bl.scene(scene_name)] + [str(e) for e in list(extra) + ensemble],
                timeout * ctx.members)
    j = r.json or {}
    if not ensemble or "members" not in j:
        return r, [j]
    members = [dict(m) for m in j["members"]]
    for m in members:
        m.setdefault("wall_seconds", r.wall / len(members))
    return r, members


def validate_outcome(r, j):
    """The outcome a swell-validate run reports, or its exit status and last error line."""
    if r.timed_out:
        return "timed out after %.0f s" % r.wall
    return j.get("outcome", "exit %s: %s" % (r.rc, r.last_err_line()))


def each_member(r, members, row_of, spread):
    """The row of a case: row_of(member JSON) for each member, combined (common.combine: means,
    and the sample sd of the fields in spread); with one member its row as it is."""
    rows = [row_of(j) for j in members]
    if len(rows) == 1:
        return rows[0]
    return bl.combine(rows, spread)


def us_per_particle_step(j, steps, particles):
    """Solver time per step and particle (us) of a swell-validate run, None if it did not run."""
    return 1e6 * j["solver_seconds"] / steps / particles if steps and particles else None


# ---------------------------------------------------------------- dam break
def dam_break_cases(quick):
    """(spacing a/per, scheme, settings, PPE tolerance): both schemes at 1e-6 at every spacing;
    full mode also 1e-3 and 1e-4 for the default scheme at a/20 and a/40."""
    spacings = [10, 20, 40] if quick else [10, 20, 40, 50, 80]
    tolerances = [1e-6] if quick else [1e-3, 1e-4, 1e-6]
    for per in spacings:
        for sname, sset in SCHEMES:
            for tol in tolerances:
                if tol != 1e-6 and (sname != DEFAULT_SCHEME or per not in (20, 40)):
                    continue
                yield per, sname, sset, tol


def dam_break(ctx):
    ctx.note_load("dam break")
    a = bl.load_scene(DAM_SCENE)["geometry"]["water"][0]
    a = a["x1"] - a["x0"]
    rows = []
    for per, sname, sset, tol in dam_break_cases(ctx.quick):
        l0 = a / per
        dt = DAM_DT[0] * (l0 / DAM_DT[1])
        s = {"geometry.particle_spacing": "%.6g" % l0, "solver.dt": "%.6g" % dt,
             "solver.ppe_tolerance": "%g" % tol}
        s.update(sset)
        r, members = validate(ctx, "dam-break", DAM_SCENE, s)

        def row_of(j):
            steps, parts = j.get("steps") or 0, j.get("particles") or 0
            return {
                "resolution": "a/%d" % per, "l0_m": l0, "dt_s": dt, "scheme": sname,
                "ppe_tolerance": tol, "particles": parts, "water": j.get("water"),
                "steps": steps, "outcome": validate_outcome(r, j),
                "front_error_mean_a": j.get("front_error_mean"), "front_error_max_a": j.get("front_error_max"),
                "aligned_front_error_mean_a": j.get("aligned_front_error_mean"),
                "aligned_front_error_max_a": j.get("aligned_front_error_max"),
                "aligned_shift_T": j.get("aligned_shift_T"),
                "ppe_iterations_mean": j.get("ppe_iterations_mean"), "wall_s": j.get("wall_seconds", r.wall),
                "us_per_particle_step": us_per_particle_step(j, steps, parts)}
        rows.append(each_member(r, members, row_of, DAM_SPREAD))
    return rows


# ---------------------------------------------------------------- still tank
def still_tank(ctx):
    ctx.note_load("still tank")
    water = bl.load_scene(TANK_SCENE)["geometry"]["water"][0]
    H = water["y1"] - water["y0"]
    steps, settle = (2000, 1.0) if ctx.quick else (20000, 2.0)
    rows = []
    for per in [10, 20, 40]:
        l0 = H / per
        for sname, sset in SCHEMES:
            s = {"geometry.particle_spacing": "%.6g" % l0}
            s.update(sset)
            r, members = validate(ctx, "still-tank", TANK_SCENE, s, ["--steps", steps, "--settle", settle])

            def row_of(j):
                n, parts = j.get("steps") or 0, j.get("particles") or 0
                ratio = j.get("bottom_pressure_ratio")
                return {
                    "resolution": "H/%d" % per, "l0_m": l0, "scheme": sname, "particles": parts,
                    "water": j.get("water"), "steps": n, "settle_s": settle, "outcome": validate_outcome(r, j),
                    "bed_pressure_ratio": ratio, "pressure_error": abs(ratio - 1.0) if ratio is not None else None,
                    "max_speed_over_sqrt_gH": j.get("max_speed_over_sqrt_gH"), "escaped": j.get("escaped"),
                    "wall_s": j.get("wall_seconds", r.wall),
                    "us_per_particle_step": us_per_particle_step(j, n, parts)}
            rows.append(each_member(r, members, row_of, TANK_SPREAD))
    return rows


# ---------------------------------------------------------------- regular waves
def wave_setup(scene_name=WAVE_SCENE):
    """Depth h, period T, stroke S, spacing, dt and the gauges of a regular-wave scene."""
    sc = bl.load_scene(scene_name)
    w = sc["geometry"]["water"][0]
    return {"h": w["y1"] - w["y0"], "T": sc["piston"]["period"], "S": sc["piston"]["stroke"],
            "l0": sc["geometry"]["particle_spacing"], "dt": sc["solver"]["dt"],
            "gauges": sc["output"].get("gauges", [])}


def wave_dt(l0):
    return next(dt for at_least, dt in WAVE_DT if l0 >= at_least)


def wave_cases(quick):
    """(scene, l0 or None for the scene's own, dt or None): the spacing sweep on
    regular_wave_small.json (quick: l0 = 0.02 and 0.2/15 only), full mode also the progressive
    waves over three wavelengths at their own spacing."""
    spacings = [0.02, 0.2 / 15] if quick else [0.04, 0.02, 0.2 / 15, 0.01]
    cases = [(WAVE_SCENE, l0, wave_dt(l0)) for l0 in spacings]
    return cases + ([] if quick else [(name, None, None) for name in PROGRESSIVE_SCENES])


def regular_wave(ctx):
    ctx.note_load("regular wave")
    rows = []
    for scene_name, l0, dt in wave_cases(ctx.quick):
        w = wave_setup(scene_name)
        base = {} if l0 is None else {"geometry.particle_spacing": repr(l0), "solver.dt": repr(dt)}
        l0, dt = l0 or w["l0"], dt or w["dt"]
        for sname, sset in SCHEMES:
            s = dict(base)
            s.update(sset)
            r, members = validate(ctx, "regular-wave", scene_name, s, timeout=3600)

            def row_of(j):
                hs, he = j.get("heights") or [None], j.get("height_errors") or [None]
                win = j.get("window")
                return {"scene": scene_name[:-len(".json")], "resolution": "h/%d" % round(w["h"] / l0),
                        "l0_m": l0, "dt_s": dt, "scheme": sname, "kh": j.get("kh"),
                        "gauges": len(j.get("gauges") or w["gauges"]),
                        "particles": (j.get("water") or 0) + (j.get("fixed") or 0) or None,
                        "water": j.get("water"), "steps": j.get("steps"), "outcome": validate_outcome(r, j),
                        "window_s": "%.1f-%.1f" % tuple(win) if win else None,
                        # Since 2026-12-04 the first gauge's height is read over its own window.
                        "H_window": "own" if j.get("gauge_windows") else "common",
                        "H_m": hs[0], "height_error": he[0], "theory_H_m": j.get("height_theory"),
                        "L_m": j.get("wavelength"), "wavelength_error": j.get("wavelength_error"),
                        "L_fit_m": j.get("wavelength_fit"), "wavelength_fit_error": j.get("wavelength_fit_error"),
                        "theory_L_m": j.get("wavelength_theory"),
                        "decay_per_wavelength": j.get("decay_per_wavelength"), "decay_total": j.get("decay_total"),
                        "decay_total_fit": j.get("decay_total_fit"),
                        "wall_s": j.get("wall_seconds", r.wall),
                        "us_per_particle_step": j.get("us_per_particle_step"),
                        "source": "swell-validate regular-wave"}
            rows.append(each_member(r, members, row_of, WAVE_SPREAD))
    return rows


def wave_note(quick):
    """The scenes' parameters, written with the CSV (the docs text of --docs-only reads it)."""
    parts = []
    for name in [WAVE_SCENE] + ([] if quick else list(PROGRESSIVE_SCENES)):
        w = wave_setup(name)
        parts.append("`scenes/%s`: h = %g m, T = %g s, S = %g cm, %d gauges at x = %s m" % (
            name, w["h"], w["T"], 100 * w["S"], len(w["gauges"]), ", ".join("%g" % g for g in w["gauges"])))
    return "; ".join(parts)


# ---------------------------------------------------------------- Lobovsky dam break
def lobovsky_cases(quick):
    """(l0, scene, settings beyond the scheme's) of the Lobovsky runs: the scenes' own spacings
    (H/15, H/30); full mode also LOB_EXTRA with dt scaled from its scene and the tank's height
    rounded up to whole spacings (the loader's rule)."""
    cases = [(l0, name, {}) for l0, name in sorted(LOB_SCENES.items(), reverse=True)]
    if not quick:
        l0, name = LOB_EXTRA
        sc = bl.load_scene(name)
        g = sc["geometry"]
        tank = g["tank"]
        y1 = tank["y0"] + math.ceil((tank["y1"] - tank["y0"]) / l0 - 1e-6) * l0
        dt = sc["solver"]["dt"] * l0 / g["particle_spacing"]
        cases.append((l0, name, {"geometry.particle_spacing": "%.6g" % l0, "solver.dt": "%.6g" % dt,
                                 "geometry.tank.y1": "%.6g" % y1}))
    return cases


def lobovsky(ctx):
    ctx.note_load("lobovsky")
    rows = []
    for l0, scene_name, base in lobovsky_cases(ctx.quick):
        sc = bl.load_scene(scene_name)
        H = lobovsky_height(scene_name)
        dt = float(base.get("solver.dt", sc["solver"]["dt"]))
        for sname, sset in SCHEMES:
            row = {"resolution": "H/%d" % round(H / l0), "l0_m": l0, "dt_s": dt, "scheme": sname,
                   "scene": scene_name[:-len(".json")], "H_m": H,
                   "tank_m": "%g x %g" % (sc["geometry"]["tank"]["x1"] - sc["geometry"]["tank"]["x0"],
                                          float(base.get("geometry.tank.y1", sc["geometry"]["tank"]["y1"]))
                                          - sc["geometry"]["tank"]["y0"])}
            estimate = lobovsky_estimate(rows, sname, l0)
            if estimate is not None and estimate >= LOB_LIMIT_S:
                row["outcome"] = ("skipped: predicted %.0f s >= %.0f s" % (estimate, LOB_LIMIT_S)
                                  if estimate < math.inf else
                                  "skipped: no stable l0 = %g m run to predict from" % min(LOB_SCENES))
                rows.append(row)
                continue
            s = dict(base)
            s.update(sset)
            r, members = validate(ctx, "lobovsky", scene_name, s)

            def row_of(j, row=row):
                steps, parts = j.get("steps") or 0, j.get("particles") or 0
                out = dict(row)
                out.update({"particles": parts or None, "water": j.get("water"), "steps": steps or None,
                            "outcome": validate_outcome(r, j),
                            "worst_mean_abs_error_over_H": j.get("mean_abs_error_over_H_worst"),
                            "window_s": "%g-%g" % tuple(j["window"]) if j.get("window") else None,
                            # Issue 14's "first impact and run-up": until the record's water lands
                            # on the far gauge (docs/validation.md 7.49), and when the run's does.
                            "run_up_worst_mean_abs_error_over_H": j.get("mean_abs_error_over_H_worst_run_up"),
                            "far_gauge_landing_s": j.get("far_gauge_landing_time")})
                # The far wall's pressure at Buchner's sensor P1 (docs/validation.md 7.51): when
                # the run-up collapses, and the mean error against delta-SPH at H/dx = 320.
                p1 = j.get("far_wall_pressure") or {}
                out.update({"p1_collapse_t": p1.get("second_peak_time"),
                            "p1_mean_abs_error_delta_sph": (p1.get("delta_sph_320") or {}).get("mean_abs_error")})
                for g in j.get("gauges") or []:
                    out["%s_x_m" % g["name"]] = g.get("x")
                    out["%s_mean_abs_error_over_H" % g["name"]] = g.get("mean_abs_error_over_H")
                    out["%s_mean_signed_error_over_H" % g["name"]] = g.get("mean_signed_error_over_H")
                    # The experiment's two series against each other (none for H1): the error
                    # the records themselves cannot resolve.
                    out["%s_experiment_scatter_over_H" % g["name"]] = g.get("experiment_scatter_over_H")
                out.update({"ppe_iterations_mean": j.get("ppe_iterations_mean"),
                            "wall_s": j.get("wall_seconds", r.wall),
                            "us_per_particle_step": j.get("us_per_particle_step") or
                            us_per_particle_step(j, steps, parts)})
                return out
            row = each_member(r, members, row_of, lobovsky_spread)
            # The worst gauge: the one with the largest mean error (over the members).
            means = {n: row.get("%s_mean_abs_error_over_H" % n) for n in gauge_names([row])}
            means = {n: v for n, v in means.items() if v is not None}
            row["worst_gauge"] = max(means, key=means.get) if means else None
            rows.append(row)
    return rows


def lobovsky_estimate(rows, scheme, l0):
    """Predicted wall time (s) of a run below the scenes' spacings, from the same scheme's run at
    the finest of them (particles ~ l0^-2, steps ~ l0^-1); None for the scenes' own spacings."""
    finest = min(LOB_SCENES)
    if l0 >= finest:
        return None
    done = [r for r in rows if r["scheme"] == scheme and r["l0_m"] == finest and r.get("wall_s")]
    if not done or not str(done[0].get("outcome", "")).startswith("stable"):
        return math.inf
    return done[0]["wall_s"] * (finest / l0) ** 3


# ---------------------------------------------------------------- held-out waves
def per_resolution(ctx, note, kind, scenes, spread, figures, depth="h"):
    """Rows of a held-out check: both schemes on each (h/N, scene) of `scenes` (quick: the first;
    the resolution named depth/N), each row the run's common columns with `figures(json)` between
    its outcome and times."""
    ctx.note_load(note)
    rows = []
    for per, scene_name in scenes[:1] if ctx.quick else scenes:
        for sname, sset in SCHEMES:
            r, members = validate(ctx, kind, scene_name, dict(sset))

            def row_of(j, per=per, scene_name=scene_name, sname=sname, r=r):
                n, parts = j.get("steps") or 0, j.get("particles") or 0
                row = {"resolution": "%s/%d" % (depth, per), "scene": scene_name[:-len(".json")], "l0_m": j.get("l0"),
                       "scheme": sname, "particles": parts, "water": j.get("water"), "steps": n,
                       "outcome": validate_outcome(r, j)}
                row.update(figures(j))
                row.update({"wall_s": j.get("wall_seconds", r.wall),
                            "us_per_particle_step": us_per_particle_step(j, n, parts)})
                return row
            rows.append(each_member(r, members, row_of, spread))
    return rows


def standing_wave(ctx):
    return per_resolution(ctx, "standing wave", "standing-wave", SLOSH_SCENES, SLOSH_SPREAD, lambda j: {
        "period_theory_s": j.get("period_theory"), "period_s": j.get("period"),
        "period_error": j.get("period_error"), "decay_per_period": j.get("decay_per_period"),
        "first_amplitude_over_theory": j.get("first_amplitude_over_theory")})


def solitary_wave(ctx):
    return per_resolution(ctx, "solitary wave", "solitary-wave", SOLITARY_SCENES, SOLITARY_SPREAD, lambda j: {
        "celerity_theory_m_s": j.get("celerity_theory"), "celerity_m_s": j.get("celerity"),
        "celerity_error": j.get("celerity_error"),
        "first_amplitude_over_height": j.get("first_amplitude_over_height"),
        "decay_total": j.get("decay_total"), "mean_width_error": j.get("mean_width_error")})


def wet_dam_break(ctx):
    return per_resolution(ctx, "wet dam break", "wet-dam-break", WET_SCENES, WET_SPREAD, lambda j: {
        "bore_speed_theory_m_s": (j.get("theory") or {}).get("bore_speed"),
        "bore_speed_m_s": j.get("bore_speed"), "bore_speed_error": j.get("bore_speed_error"),
        "plateau_depth_error": j.get("plateau_depth_error"),
        "mean_abs_error_over_h0_worst": j.get("mean_abs_error_over_h0_worst")}, depth="h0")


def shoaling(ctx):
    return per_resolution(ctx, "shoaling", "shoaling", SHOAL_SCENES, SHOAL_SPREAD, lambda j: {
        "incident_crest_error": j.get("incident_crest_error"), "crest_error_worst": j.get("crest_error_worst"),
        "mean_abs_error_over_h0_worst": j.get("mean_abs_error_over_h0_worst"),
        "travel_time_error": j.get("travel_time_error")}, depth="h0")


# ---------------------------------------------------------------- the section
PARTS = {"dam_break": dam_break, "still_tank": still_tank, "regular_wave": regular_wave, "lobovsky": lobovsky,
         "standing_wave": standing_wave, "solitary_wave": solitary_wave, "wet_dam_break": wet_dam_break,
         "shoaling": shoaling}


def run(ctx, parts=CSVS):
    """The bake runs named in parts; the others are read back from the last run's CSVs (a
    partial rerun, --only regular_wave, keeps the other bake tables)."""
    rows = {}
    for name in CSVS:
        if name in parts:
            print("== bake: %s" % name.replace("_", " ").replace("regular wave", "regular waves"), flush=True)
            rows[name] = PARTS[name](ctx)
        else:
            rows[name] = bl.read_csv(ctx.path(name + ".csv"))
    rows[NOTE] = wave_note(ctx.quick) if "regular_wave" in parts else load_note(ctx.out)
    return rows


def load_note(out):
    try:
        with open(os.path.join(out, NOTE)) as f:
            return f.read().strip()
    except OSError:
        return ""


def table(rows, m):
    t = [bl.header(m), "", "Load average by section: " + bl.loads_text(m) + ".", "",
         schemes_text(), "", members_text(m.get("members", 1)), "",
         dam_break_text(rows["dam_break"]), "", dam_break_table(rows["dam_break"]), "",
         still_tank_text(rows["still_tank"]), "", still_tank_table(rows["still_tank"]), "",
         regular_wave_text(rows.get(NOTE, "")), "", regular_wave_table(rows["regular_wave"]), "",
         lobovsky_text(rows.get("lobovsky", [])), "", lobovsky_table(rows.get("lobovsky", [])), "",
         standing_wave_text(), "", standing_wave_table(rows.get("standing_wave", [])), "",
         solitary_wave_text(), "", solitary_wave_table(rows.get("solitary_wave", [])), "",
         wet_dam_break_text(), "", wet_dam_break_table(rows.get("wet_dam_break", [])), "",
         shoaling_text(), "", shoaling_table(rows.get("shoaling", [])), "",
         plot_text(), "",
         "![bake error against cost](images/bench/bake_error_vs_cost.png)"]
    return {"bake": "\n".join(t)}


def schemes_text():
    textbook = SCHEMES[1][0]
    return ("**Schemes.** Every case runs both MPS schemes of `solver.scheme` with the same scene, "
            "spacing and dt. Rows **%s**: the default scheme `swell` (the scenes set no scheme key): "
            "the Khayyer & Gotoh corrected pressure gradient, the neighbour-distribution "
            "free-surface test, the Tanaka & Masunaga mixed source (gamma 0.02) with particle "
            "shifting (C 0.02) and inelastic collisions from 0.8 l0 (docs/validation.md, Schemes). "
            "Rows **%s**: Koshizuka & Oka 1996 as the textbook code has it "
            "(minimum-pressure gradient, density-only surface test), "
            "run with `%s`. One thread (`--threads 1`); cost = solver time / steps / all particles "
            "(water + wall + dummy), in µs per particle-step." % (
                DEFAULT_SCHEME, textbook, " ".join(bl.sets(dict(SCHEMES)[textbook]))))


def members_text(n):
    if n <= 1:
        return ("**Members.** One record per row, unjittered (`tools/bench --members N` runs each check "
                "as an ensemble instead): where the flow amplifies small differences (the dam breaks "
                "after the impact, the waves over several wavelengths, the still tank's settled state) "
                "one record is one draw, good to the spread that an ensemble measures.")
    return ("**Members.** Each row is an ensemble of %d members (`tools/bench --members %d`: "
            "`swell-validate ... --ensemble %d`, seeds 1..%d, the water jittered by 1e-6 l0, the same "
            "flow up to a perturbation far below the resolution): each figure reads the members' mean "
            "± their sample sd (the error figures; counts, times and costs are means), and the plot "
            "draws that sd as a bar. A row's outcome is the first member's that was not stable, "
            "if any." % (n, n, n, n))


def dam_break_text(rows):
    return ("**Dam break against Martin & Moyce** (`swell-validate --json --threads 1 --set "
            "geometry.particle_spacing=L0 --set solver.dt=DT [--set solver.scheme=textbook] dam-break "
            "scenes/%s`; dt = %g ms x l0 / %g mm). Front Z = z / a against T = t sqrt(2g/a), over the "
            "experimental points with T in [0.8, 3.0], in units of a. **Raw**: mean and max |Z_sim - Z_exp| "
            "with T counted from the start of the run. **Aligned**: the same after shifting the simulated "
            "T by a fixed rule, never fitted, so that the front reaches the experiment's first recorded "
            "position at that point's T (the alignment point left out); 'shift T' is that shift "
            "(positive: the simulation was ahead). Martin & Moyce's time origin (the gate's release) "
            "is not known, so part of the raw error is an offset in time that every code shares; the "
            "aligned error leaves it out and compares how the front advances:" % (DAM_SCENE, 1e3 * DAM_DT[0], 1e3 * DAM_DT[1]))


def dam_break_table(rows):
    return bl.md_table(rows, [
        ("resolution", "resolution"), ("scheme", scheme_of), ("PPE tol.", "ppe_tolerance"),
        ("particles", "particles"), ("steps", "steps"), ("outcome", lambda r: r["outcome"][:60]),
        ("raw mean abs dZ (a)", "front_error_mean_a"), ("raw max abs dZ (a)", "front_error_max_a"),
        ("aligned mean abs dZ (a)", "aligned_front_error_mean_a"),
        ("aligned max abs dZ (a)", "aligned_front_error_max_a"), ("shift T", "aligned_shift_T"),
        ("PPE iter.", "ppe_iterations_mean"), ("wall s", "wall_s"),
        ("µs / particle-step", "us_per_particle_step")])


def still_tank_text(rows):
    """H from the rows (l0 x the divisor of 'H/N'), dt from the scene the rows were run with."""
    H = next((r["l0_m"] * int(r["resolution"].split("/")[1]) for r in rows if r.get("l0_m")), None)
    dt = bl.load_scene(TANK_SCENE)["solver"]["dt"]
    settle = next((r.get("settle_s") for r in rows if r.get("settle_s") is not None), None)
    return ("**Still tank** (`swell-validate --json --threads 1 --set geometry.particle_spacing=L0 "
            "[--set solver.scheme=textbook] still-tank scenes/%s --steps N --settle S`; H = %s m, "
            "dt = %g ms%s). Error = |bed pressure / rho g H - 1|, the bed pressure averaged over the "
            "middle half of the bed after the settling time; max speed = the largest |u| a water "
            "particle carries at the end of a step after it, after the shift's damping:" % (
                TANK_SCENE, bl.fmt(H), 1e3 * dt, ", S = %s s" % bl.fmt(settle) if settle is not None else ""))


def still_tank_table(rows):
    return bl.md_table(rows, [
        ("resolution", "resolution"), ("scheme", scheme_of), ("particles", "particles"),
        ("steps", "steps"), ("outcome", lambda r: r["outcome"][:60]),
        ("bed p / rho g H", "bed_pressure_ratio"), ("pressure error", "pressure_error"),
        ("max speed / sqrt(gH)", "max_speed_over_sqrt_gH"), ("wall s", "wall_s"),
        ("µs / particle-step", "us_per_particle_step")])


def regular_wave_text(note):
    dts = [t for _, t in WAVE_DT]
    bounds = [a for a, _ in WAVE_DT[:-1]]
    rule = "dt %s ms at l0 >= %s, below %g mm" % (
        ", ".join("%g" % (1e3 * t) for t in dts), ", >= ".join("%g" % (1e3 * b) for b in bounds),
        1e3 * bounds[-1])
    return ("**Regular waves against Biesel** (`swell-validate --json --threads 1 [--set "
            "geometry.particle_spacing=L0 --set solver.dt=DT] [--set solver.scheme=textbook] "
            "regular-wave scenes/SCENE`, its default fit windows: the phases over the common window "
            "(**window s**: after the ramp and the wave's arrival at the farthest gauge, before "
            "reflections return); the heights over the window in **H window**: `own`, each gauge's "
            "own window from the grown wave's arrival at that gauge until the far wall's reflection "
            "reaches it or the run ends, or `common`, the common window. The spacing sweep runs "
            "`scenes/%s` (%s); the progressive-wave scenes (full run only) keep their own l0 and dt. "
            "**H error** = H / H_Biesel - 1 at the first gauge; **L error** = L / L_theory - 1 with L "
            "from the phase lag between the first two gauges, **L fit error** the same with L from the "
            "phase slope over all gauges; **decay / L** = the fractional height loss per wavelength "
            "from a fit ln H = a + b x over all gauges (positive: the wave decays), **lost over the gauges** "
            "= 1 - exp(b (x_last - x_first)) along the same line (3 L in the progressive-wave scenes). Scenes: %s:" % (
                WAVE_SCENE, rule, note or "-"))


def regular_wave_table(rows):
    return bl.md_table(rows, [
        ("scene", "scene"), ("resolution", "resolution"), ("scheme", scheme_of),
        ("particles", "particles"), ("steps", "steps"),
        ("outcome", lambda r: r["outcome"][:60]), ("window s", "window_s"),
        ("H window", lambda r: r.get("H_window") or "common"),
        ("H (m)", "H_m"), ("H Biesel (m)", "theory_H_m"), ("H error", "height_error"),
        ("L (m)", "L_m"), ("L theory (m)", "theory_L_m"), ("L error", "wavelength_error"),
        ("L fit error", "wavelength_fit_error"), ("decay / L", "decay_per_wavelength"),
        ("lost over the gauges", "decay_total_fit"),
        ("wall s", "wall_s"), ("µs / particle-step", "us_per_particle_step")])


def gauge_names(rows):
    """H1.. in the order the rows have them (from the CSV columns NAME_x_m, one per gauge: the
    other figures ending in _mean_abs_error_over_H, the worst gauge's and the run-up's, are not
    gauges)."""
    names = []
    for r in rows:
        for k in r:
            if k.endswith("_x_m"):
                n = k[:-len("_x_m")]
                if n not in names:
                    names.append(n)
    return names


def lobovsky_text(rows):
    names = gauge_names(rows)
    first = next((r for r in rows if r.get("H_m")), {})
    xs = ", ".join("%s %s" % (n, bl.fmt(first.get("%s_x_m" % n))) for n in names) or "-"
    window = next((r["window_s"] for r in rows if r.get("window_s")), None)
    H = first.get("H_m") or lobovsky_height(LOB_SCENES[min(LOB_SCENES)])
    own = ", ".join("`scenes/%s` at H/%d" % (name, round(H / l0))
                    for l0, name in sorted(LOB_SCENES.items(), reverse=True))
    l0, name = LOB_EXTRA
    return ("**Lobovsky et al. 2014 dam break, H = %s m** (`swell-validate --json --threads 1 "
            "[--set solver.scheme=textbook] lobovsky SCENE`: %s, each with its own dt; the full run "
            "adds l0 = %g m on `scenes/%s` with dt scaled from it and the tank's height rounded up to "
            "whole spacings, when the same scheme's l0 = %g m run predicts it under %g s (its wall "
            "time x (%g / l0)^3)). Water height at the gauges (x from the upstream wall, m: %s) "
            "against the records over t in [%s] s; per gauge the mean |h_sim - h_record| / H; "
            "**worst** = the largest of the gauges' means:" % (
                bl.fmt(H), own, l0, name, min(LOB_SCENES), LOB_LIMIT_S, min(LOB_SCENES),
                xs, window.replace("-", ", ") if window else "-"))


def lobovsky_height(scene_name):
    w = bl.load_scene(scene_name)["geometry"]["water"][0]
    return w["y1"] - w["y0"]


def lobovsky_table(rows):
    cols = [("resolution", "resolution"), ("scheme", scheme_of), ("scene", "scene"), ("tank (m)", "tank_m"),
            ("particles", "particles"), ("steps", "steps"), ("outcome", lambda r: (r.get("outcome") or "")[:60]),
            ("worst mean abs dh / H", "worst_mean_abs_error_over_H"), ("worst gauge", "worst_gauge"),
            ("worst over the first impact and run-up", "run_up_worst_mean_abs_error_over_H"),
            ("lands on the far gauge (s)", "far_gauge_landing_s"),
            ("P1: run-up's collapse, t (g/H)^0.5 (delta-SPH 6.43, experiment 5.87)", "p1_collapse_t"),
            ("P1: mean abs dp / rho g H against delta-SPH", "p1_mean_abs_error_delta_sph")]
    cols += [("%s mean abs dh / H" % n, "%s_mean_abs_error_over_H" % n) for n in gauge_names(rows)]
    cols += [("%s: experiment's two series, mean abs dh / H" % n, "%s_experiment_scatter_over_H" % n)
             for n in gauge_names(rows) if any(r.get("%s_experiment_scatter_over_H" % n) is not None for r in rows)]
    cols += [("PPE iter.", "ppe_iterations_mean"), ("wall s", "wall_s"),
             ("µs / particle-step", "us_per_particle_step")]
    return bl.md_table(rows, cols)


def standing_wave_text():
    scenes = ", ".join("`scenes/%s` (h/%d)" % (name, per) for per, name in SLOSH_SCENES)
    return ("**Standing wave against linear theory** (held out: added after the default's settings "
            "were chosen; `swell-validate --json --threads 1 [--set solver.scheme=textbook] "
            "standing-wave SCENE`: %s, the quick run the first only). The first sloshing mode of a 1 m "
            "tank, h = 0.5 m, from rest with a 2 cm cosine top; the surface one spacing in from each "
            "wall after every step. **Period error** = T / T_linear - 1 (T_linear from omega^2 = "
            "g k tanh kh, 1.1818 s); **decay / period** = the fractional amplitude loss per period "
            "(linear theory: none at this scale); **first amplitude** = the first period's over the "
            "cosine's (about 1 for a clean first mode; the textbook scheme's surface churns and shows "
            "no wave: its period is the noise's). docs/validation.md, Standing wave:" % scenes)


def standing_wave_table(rows):
    return bl.md_table(rows, [
        ("resolution", "resolution"), ("scheme", scheme_of), ("particles", "particles"),
        ("steps", "steps"), ("outcome", lambda r: (r.get("outcome") or "")[:60]),
        ("period error", "period_error"), ("decay / period", "decay_per_period"),
        ("first amplitude / theory", "first_amplitude_over_theory"), ("wall s", "wall_s"),
        ("µs / particle-step", "us_per_particle_step")])


def solitary_wave_text():
    scenes = ", ".join("`scenes/%s` (h/%d)" % (name, per) for per, name in SOLITARY_SCENES)
    return ("**Solitary wave against theory** (held out: added after the default's settings were "
            "chosen; `swell-validate --json --threads 1 [--set solver.scheme=textbook] solitary-wave "
            "SCENE`: %s, the quick run the first only). A piston's Goring (1978) stroke for H = 0.04 m "
            "in h = 0.2 m, read by five gauges at 10-30 h. **Celerity error** = the crests' speed over "
            "sqrt(g (h + A)) - 1, A the crests' mean height (Rayleigh 1876); **first crest / H** at "
            "10 h; **lost over 20 h** = 1 - A(30 h) / A(10 h) (theory: about 1 %%, the bed's laminar "
            "friction); **width error** = the time a record stays above A / 2 over Boussinesq's "
            "sech^2 for that A, - 1. docs/validation.md, Solitary wave:" % scenes)


def solitary_wave_table(rows):
    return bl.md_table(rows, [
        ("resolution", "resolution"), ("scheme", scheme_of), ("particles", "particles"),
        ("steps", "steps"), ("outcome", lambda r: (r.get("outcome") or "")[:60]),
        ("celerity error", "celerity_error"), ("first crest / H", "first_amplitude_over_height"),
        ("lost over 20 h", "decay_total"), ("width error", "mean_width_error"), ("wall s", "wall_s"),
        ("µs / particle-step", "us_per_particle_step")])


def wet_dam_break_text():
    scenes = ", ".join("`scenes/%s` (h0/%d)" % (name, per) for per, name in WET_SCENES)
    return ("**Dam break onto a wet bed against Stoker** (held out: added after the default's "
            "settings were chosen; `swell-validate --json --threads 1 [--set solver.scheme=textbook] "
            "wet-dam-break SCENE`: %s, the quick run the first only). A reservoir h0 = 0.1 m deep "
            "breaks onto a layer h1 = 0.2 h0; ten gauges compared with Stoker's (1957) shallow-water "
            "solution from t = 5 sqrt(h0 / g) until a reflection could return. **Bore speed error** "
            "= the fitted speed of the bore's arrivals over Stoker's 0.939 m/s, - 1; **depth behind "
            "the bore** over his h2 = 0.0508 m, - 1; **worst gauge** = the largest mean |h - "
            "h_Stoker| / h0. docs/validation.md, Dam break onto a wet bed:" % scenes)


def wet_dam_break_table(rows):
    return bl.md_table(rows, [
        ("resolution", "resolution"), ("scheme", scheme_of), ("particles", "particles"),
        ("steps", "steps"), ("outcome", lambda r: (r.get("outcome") or "")[:60]),
        ("bore speed error", "bore_speed_error"), ("depth behind the bore", "plateau_depth_error"),
        ("worst gauge / h0", "mean_abs_error_over_h0_worst"), ("wall s", "wall_s"),
        ("µs / particle-step", "us_per_particle_step")])


def shoaling_text():
    scenes = ", ".join("`scenes/%s` (h0/%d)" % (name, per) for per, name in SHOAL_SCENES)
    return ("**Solitary wave up a beach against Grilli et al. (1994)** (held out: added after the "
            "default's settings were chosen; `swell-validate --json --threads 1 [--set "
            "solver.scheme=textbook] shoaling SCENE`: %s, the quick run the first only). A solitary "
            "wave H = 0.2 h0 runs over 15 h0 of flat bed and up a 1:34.7 slope until it breaks; six "
            "gauges compared with the experiment's records, the clocks aligned on g0's crest. "
            "**Incident crest** = g0's crest over the record's, - 1; **worst crest** = the slope "
            "gauge whose crest is furthest from the record's, its ratio - 1; **worst gauge** = the "
            "largest mean |eta - eta_record| / h0 over a record's span; **climb time** = the crest's "
            "time from g1 to g9 over the record's, - 1. docs/validation.md, Solitary wave shoaling on a beach:" % scenes)


def shoaling_table(rows):
    return bl.md_table(rows, [
        ("resolution", "resolution"), ("scheme", scheme_of), ("particles", "particles"),
        ("steps", "steps"), ("outcome", lambda r: (r.get("outcome") or "")[:60]),
        ("incident crest", "incident_crest_error"), ("worst crest", "crest_error_worst"),
        ("worst gauge / h0", "mean_abs_error_over_h0_worst"), ("climb time", "travel_time_error"),
        ("wall s", "wall_s"), ("µs / particle-step", "us_per_particle_step")])


# ---------------------------------------------------------------- the plot
SWEEP = WAVE_SCENE[:-len(".json")]


def at_default_tolerance(r):
    return r.get("ppe_tolerance") in (None, 1e-6)


# (CSV, label, field, plotted as its absolute value, rows kept or None for all, joined by a
# line): one colour each; an ensemble's rows also draw FIELD_sd as an error bar.
PLOT_CASES = [
    ("dam_break", "dam break: raw mean |dZ| / a", "front_error_mean_a", False, at_default_tolerance, True),
    ("dam_break", "dam break: aligned mean |dZ| / a", "aligned_front_error_mean_a", False, at_default_tolerance,
     True),
    ("still_tank", "still tank: |bed p / rho g H - 1|", "pressure_error", False, None, True),
    ("still_tank", "still tank: max speed / sqrt(gH)", "max_speed_over_sqrt_gH", False, None, True),
    ("regular_wave", "regular wave, h/N sweep: |H / H_Biesel - 1|", "height_error", True,
     lambda r: r.get("scene") in (None, SWEEP), True),
    ("regular_wave", "progressive waves (one scene each): |H / H_Biesel - 1|", "height_error", True,
     lambda r: r.get("scene") not in (None, SWEEP), False),
    ("lobovsky", "Lobovsky: worst gauge mean |dh| / H", "worst_mean_abs_error_over_H", False, None, True),
    ("standing_wave", "standing wave: |T / T_linear - 1|", "period_error", True, None, True),
    ("solitary_wave", "solitary wave: |c / sqrt(g (h + A)) - 1|", "celerity_error", True, None, True),
    ("wet_dam_break", "wet dam break: worst gauge mean |dh| / h0", "mean_abs_error_over_h0_worst", False,
     None, True),
    ("shoaling", "shoaling: worst gauge mean |d eta| / h0", "mean_abs_error_over_h0_worst", False, None, True),
]
# Scheme -> line style: the default solid with filled circles, textbook dashed with open squares.
SCHEME_STYLES = {DEFAULT_SCHEME: {"linestyle": "-", "marker": "o"},
                 "textbook": {"linestyle": "--", "marker": "s", "markerfacecolor": "none"}}
STYLE_WORDS = {DEFAULT_SCHEME: "solid lines, filled circles", "textbook": "dashed lines, open squares"}


def plot_text():
    return ("**Error against cost** (the plot): each case's error (y, log) against its µs per "
            "particle-step (x, log); one colour per case, one style per scheme (%s); points labelled "
            "with their resolution (progressive waves: kh, not joined); with an ensemble's rows, a bar of "
            "one sd of the members either side of their mean (on the log axis a bar that reaches zero "
            "or below runs off the bottom of the plot). Dam break at PPE tolerance 1e-6 only." % "; ".join(
                "%s: %s" % (n, STYLE_WORDS[n]) for n in SCHEME_STYLES))


def plot(rows, out_dir):
    series, annotate, extra = [], {}, []
    for k, (csv_name, label, field, absolute, keep, line) in enumerate(PLOT_CASES):
        colour = "C%d" % k if k < 10 else "black"  # ten cycle colours, then black

        def error(r):
            v = r.get(field)
            return abs(v) if absolute and v is not None else v
        drawn = False
        for sname, style in SCHEME_STYLES.items():
            rs = [r for r in rows.get(csv_name, []) if scheme_of(r) == sname and (keep is None or keep(r))
                  and r.get("us_per_particle_step") is not None and error(r) is not None]
            if not rs:
                continue
            rs.sort(key=lambda r: r["us_per_particle_step"])
            drawn = True
            key = "_%s / %s" % (label, sname)  # "_": out of the legend (legend_extra names them)
            st = dict(style, color=colour, yerr=[r.get(field + "_sd") for r in rs])
            if not line:
                st["linestyle"] = "none"
            series.append((key, [r["us_per_particle_step"] for r in rs], [error(r) for r in rs], st))
            annotate[key] = [point_label(r) for r in rs]
        if drawn:
            extra.append((label, {"color": colour, "linestyle": "-", "linewidth": 3}))
    extra += [(sname, dict(style, color="black")) for sname, style in SCHEME_STYLES.items()]
    bl.plot(os.path.join(out_dir, "bake_error_vs_cost.png"),
            "Bake error against cost: %s and textbook MPS schemes" % DEFAULT_SCHEME,
            "solver time per particle-step (µs, 1 thread)", "error (see legend)", series, logx=True, logy=True,
            annotate=annotate, legend_extra=extra, figsize=(12, 6), plain_x=True,
            legend_outside=True)


def point_label(r):
    if r.get("scene") not in (None, SWEEP) and r.get("kh") is not None:
        return "kh %.2g" % r["kh"]
    return r.get("resolution") or ""
