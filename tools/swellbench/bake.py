"""Bake accuracy against cost: dam break against Martin & Moyce, still-tank bed pressure and
regular waves against Biesel, at several particle spacings (full: also PPE tolerances and the
MPS variants), each with wall time and solver time per particle-step.

CSV: dam_break, still_tank, regular_wave (+ regular_wave.note); docs section: bake."""

import os

from . import common as bl

CSVS = ("dam_break", "still_tank", "regular_wave")
NOTE = "regular_wave.note"
SECTIONS = ("bake",)
PLOTS = ("bake_error_vs_cost",)

DAM_SCENE, TANK_SCENE, WAVE_SCENE = "dam_break_small.json", "still_tank_small.json", "regular_wave_small.json"
DAM_DT = (0.0005, 0.005)  # dt = 0.5 ms at l0 = 5 mm, proportional to l0
WAVE_DT = ((0.04, 0.004), (0.02, 0.002), (0.0, 0.001))  # (l0 at least, dt): frames every 20 ms
VARIANTS = [("gradient_correction", {"solver.gradient_correction": "true"}),
            ("symmetric, gamma 0.05", {"solver.symmetric_gradient": "true", "solver.relaxation": "0.05"})]


def variants(quick):
    return [("textbook", {})] + ([] if quick else VARIANTS)


def validate(ctx, kind, scene_name, settings, extra=(), timeout=900):
    """One swell-validate run: (Run, its JSON or {})."""
    r = ctx.run([bl.exe("swell-validate"), "--json", "--threads", "1"] + bl.sets(settings) +
                [kind, bl.scene(scene_name)] + [str(e) for e in extra], timeout)
    return r, r.json or {}


def validate_outcome(r, j):
    """The outcome a swell-validate run reports, or its exit status and last error line."""
    return j.get("outcome", "exit %s: %s" % (r.rc, r.last_err_line()))


def us_per_particle_step(j, steps, particles):
    """Solver time per step and particle (us) of a swell-validate run, None if it did not run."""
    return 1e6 * j["solver_seconds"] / steps / particles if steps and particles else None


# ---------------------------------------------------------------- dam break
def dam_break_cases(quick):
    """(spacing a/per, variant, settings, PPE tolerance): variants and tolerances other than the
    textbook 1e-6 at a/20 and a/40 only, variants at 1e-6 only."""
    spacings = [10, 20, 40] if quick else [10, 20, 40, 50]
    tolerances = [1e-6] if quick else [1e-3, 1e-4, 1e-6]
    for per in spacings:
        for vname, vset in variants(quick):
            for tol in tolerances:
                if (vname != "textbook" or tol != 1e-6) and per not in (20, 40):
                    continue
                if vname != "textbook" and tol != 1e-6:
                    continue
                yield per, vname, vset, tol


def dam_break(ctx):
    ctx.note_load("dam break")
    a = bl.load_scene(DAM_SCENE)["geometry"]["water"][0]
    a = a["x1"] - a["x0"]
    rows = []
    for per, vname, vset, tol in dam_break_cases(ctx.quick):
        l0 = a / per
        dt = DAM_DT[0] * (l0 / DAM_DT[1])
        s = {"geometry.particle_spacing": "%.6g" % l0, "solver.dt": "%.6g" % dt,
             "solver.ppe_tolerance": "%g" % tol}
        s.update(vset)
        r, j = validate(ctx, "dam-break", DAM_SCENE, s)
        steps, parts = j.get("steps") or 0, j.get("particles") or 0
        rows.append({
            "resolution": "a/%d" % per, "l0_m": l0, "dt_s": dt, "variant": vname,
            "ppe_tolerance": tol, "particles": parts, "water": j.get("water"),
            "steps": steps, "outcome": validate_outcome(r, j),
            "front_error_mean_a": j.get("front_error_mean"), "front_error_max_a": j.get("front_error_max"),
            "ppe_iterations_mean": j.get("ppe_iterations_mean"), "wall_s": j.get("wall_seconds", r.wall),
            "us_per_particle_step": us_per_particle_step(j, steps, parts)})
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
        for vname, vset in variants(ctx.quick):
            if vname != "textbook" and per == 40:
                continue
            s = {"geometry.particle_spacing": "%.6g" % l0}
            s.update(vset)
            r, j = validate(ctx, "still-tank", TANK_SCENE, s, ["--steps", steps, "--settle", settle])
            n, parts = j.get("steps") or 0, j.get("particles") or 0
            ratio = j.get("bottom_pressure_ratio")
            rows.append({
                "resolution": "H/%d" % per, "l0_m": l0, "variant": vname, "particles": parts,
                "water": j.get("water"), "steps": n, "outcome": validate_outcome(r, j),
                "bed_pressure_ratio": ratio, "pressure_error": abs(ratio - 1.0) if ratio is not None else None,
                "max_speed_over_sqrt_gH": j.get("max_speed_over_sqrt_gH"), "escaped": j.get("escaped"),
                "wall_s": j.get("wall_seconds", r.wall), "us_per_particle_step": us_per_particle_step(j, n, parts)})
    return rows


# ---------------------------------------------------------------- regular waves
def wave_setup():
    """Depth h, period T, stroke S and the gauges of scenes/regular_wave_small.json."""
    sc = bl.load_scene(WAVE_SCENE)
    w = sc["geometry"]["water"][0]
    return {"h": w["y1"] - w["y0"], "T": sc["piston"]["period"], "S": sc["piston"]["stroke"],
            "gauges": sc["output"].get("gauges", [])}


def wave_dt(l0):
    return next(dt for at_least, dt in WAVE_DT if l0 >= at_least)


def regular_wave(ctx):
    ctx.note_load("regular wave")
    spacings = [0.04, 0.02, 0.2 / 15] + ([] if ctx.quick else [0.01])
    w = wave_setup()
    rows = []
    for l0 in spacings:
        dt = wave_dt(l0)
        r, j = validate(ctx, "regular-wave", WAVE_SCENE,
                        {"geometry.particle_spacing": repr(l0), "solver.dt": repr(dt)}, timeout=3600)
        hs, he = j.get("heights") or [None], j.get("height_errors") or [None]
        win = j.get("window")
        rows.append({"resolution": "h/%d" % round(w["h"] / l0), "l0_m": l0, "dt_s": dt,
                     "particles": (j.get("water") or 0) + (j.get("fixed") or 0) or None,
                     "water": j.get("water"), "steps": j.get("steps"), "outcome": validate_outcome(r, j),
                     "window_s": "%.1f-%.1f" % tuple(win) if win else None,
                     "H_m": hs[0], "height_error": he[0], "theory_H_m": j.get("height_theory"),
                     "L_m": j.get("wavelength"), "wavelength_error": j.get("wavelength_error"),
                     "theory_L_m": j.get("wavelength_theory"), "wall_s": j.get("wall_seconds", r.wall),
                     "us_per_particle_step": j.get("us_per_particle_step"),
                     "source": "swell-validate regular-wave"})
    return rows


def wave_note():
    w = wave_setup()
    return ("h = %g m, T = %g s, S = %g cm; `swell-validate --json --threads 1 --set "
            "geometry.particle_spacing=L0 --set solver.dt=DT regular-wave scenes/%s`: its default fit "
            "window (after the ramp and the wave's arrival, before reflections)" % (
                w["h"], w["T"], 100 * w["S"], WAVE_SCENE))


# ---------------------------------------------------------------- the section
PARTS = {"dam_break": dam_break, "still_tank": still_tank, "regular_wave": regular_wave}


def run(ctx, parts=CSVS):
    """The bake runs named in parts; the others are read back from the last run's CSVs (a
    partial rerun, --only regular_wave, keeps the other bake tables)."""
    rows = {}
    for name in CSVS:
        if name in parts:
            print("== bake: %s" % name.replace("_", " ").replace("wave", "waves"), flush=True)
            rows[name] = PARTS[name](ctx)
        else:
            rows[name] = bl.read_csv(ctx.path(name + ".csv"))
    rows[NOTE] = wave_note() if "regular_wave" in parts else load_note(ctx.out)
    return rows


def load_note(out):
    try:
        with open(os.path.join(out, NOTE)) as f:
            return f.read().strip()
    except OSError:
        return ""


def table(rows, m):
    t = [bl.header(m), "", "Load average by section: " + bl.loads_text(m) + ".", "",
         dam_break_text(rows["dam_break"]), "", dam_break_table(rows["dam_break"]), "",
         still_tank_text(rows["still_tank"]), "", still_tank_table(rows["still_tank"]), "",
         regular_wave_text(rows.get(NOTE, "")), "", regular_wave_table(rows["regular_wave"]), "",
         "![bake error against cost](images/bench/bake_error_vs_cost.png)"]
    return {"bake": "\n".join(t)}


def dam_break_text(rows):
    return ("**Dam break against Martin & Moyce** (`swell-validate --json --threads 1 --set "
            "geometry.particle_spacing=L0 --set solver.dt=DT [--set ...] dam-break "
            "scenes/%s`; dt = %g ms x l0 / %g mm; error over T in [0.8, 3.0] "
            "in units of a; time per particle-step = solver time / steps / all particles):" % (
                DAM_SCENE, 1e3 * DAM_DT[0], 1e3 * DAM_DT[1]))


def dam_break_table(rows):
    return bl.md_table(rows, [
        ("resolution", "resolution"), ("variant", "variant"), ("PPE tol.", "ppe_tolerance"),
        ("particles", "particles"), ("steps", "steps"), ("outcome", lambda r: r["outcome"][:60]),
        ("mean abs dZ (a)", "front_error_mean_a"), ("max abs dZ (a)", "front_error_max_a"),
        ("PPE iter.", "ppe_iterations_mean"), ("wall s", "wall_s"),
        ("us / particle-step", "us_per_particle_step")])


def still_tank_text(rows):
    """H from the rows (l0 x the divisor of 'H/N'), dt from the scene the rows were run with."""
    H = next((r["l0_m"] * int(r["resolution"].split("/")[1]) for r in rows if r.get("l0_m")), None)
    dt = bl.load_scene(TANK_SCENE)["solver"]["dt"]
    return ("**Still tank** (`swell-validate --json --threads 1 --set geometry.particle_spacing=L0 "
            "still-tank scenes/%s --steps N --settle S`; H = %s m, dt = %g ms; "
            "pressure error = |bed pressure / rho g H - 1|):" % (TANK_SCENE, bl.fmt(H), 1e3 * dt))


def still_tank_table(rows):
    return bl.md_table(rows, [
        ("resolution", "resolution"), ("variant", "variant"), ("particles", "particles"),
        ("steps", "steps"), ("outcome", lambda r: r["outcome"][:60]),
        ("bed p / rho g H", "bed_pressure_ratio"), ("pressure error", "pressure_error"),
        ("max speed / sqrt(gH)", "max_speed_over_sqrt_gH"), ("wall s", "wall_s"),
        ("us / particle-step", "us_per_particle_step")])


def regular_wave_text(note):
    w = wave_setup()
    dts = [t for _, t in WAVE_DT]
    bounds = [a for a, _ in WAVE_DT[:-1]]
    rule = "dt %s ms at l0 >= %s, below %g mm" % (
        ", ".join("%g" % (1e3 * t) for t in dts), ", >= ".join("%g" % (1e3 * b) for b in bounds),
        1e3 * bounds[-1])
    g = w["gauges"][0] if w["gauges"] else None
    gauge = "(x = %g m = %g h)" % (g, g / w["h"]) if g is not None else ""
    return ("**Regular waves against Biesel** (`scenes/%s` with its other settings; %s; H at the "
            "first gauge %s, L from the phase lag between the first two gauges; %s):" % (
                WAVE_SCENE, rule, gauge, note))


def regular_wave_table(rows):
    return bl.md_table(rows, [
        ("resolution", "resolution"), ("particles", "particles"), ("steps", "steps"),
        ("outcome", lambda r: r["outcome"][:60]), ("window s", "window_s"),
        ("H (m)", "H_m"), ("H Biesel (m)", "theory_H_m"), ("H error", "height_error"),
        ("L (m)", "L_m"), ("L theory (m)", "theory_L_m"), ("L error", "wavelength_error"),
        ("wall s", "wall_s"), ("us / particle-step", "us_per_particle_step")])


def plot(rows, out_dir):
    tb = [r for r in rows.get("dam_break", []) if r["variant"] == "textbook" and r["ppe_tolerance"] == 1e-6]
    st = [r for r in rows.get("still_tank", []) if r["variant"] == "textbook"]
    rw = rows.get("regular_wave", [])
    labels = ("dam-break front: mean |dZ| / a", "still tank: |bed pressure / rho g H - 1|",
              "regular wave: |H / H_Biesel - 1|")
    errors = ([r["front_error_mean_a"] for r in tb], [r["pressure_error"] for r in st],
              [abs(r["height_error"]) if r.get("height_error") is not None else None for r in rw])
    series = [(lab, [r["wall_s"] for r in rs], err) for lab, rs, err in zip(labels, (tb, st, rw), errors)]
    bl.plot(os.path.join(out_dir, "bake_error_vs_cost.png"), "Bake accuracy against cost (textbook MPS)",
            "wall time of the run (s)", "relative error", series, logx=True, logy=True,
            annotate={lab: [r["resolution"] for r in rs] for lab, rs in zip(labels, (tb, st, rw))})
