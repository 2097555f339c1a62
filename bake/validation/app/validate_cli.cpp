#include "validate_cli.h"

#include "command_line.h"

namespace swell::bake {
namespace {

CLI::Option* addEnsemble(CLI::App& run, ValidateCommandLine& cl) {
    return run
        .add_option("--ensemble", cl.ensemble,
                    "run N members, seeds 1..N, the water jittered by geometry.jitter (1e-6 l0 "
                    "unless set): each member's figures and their mean, spread and range")
        ->check(CLI::Range(1, 64));
}

/// The options before the subcommand: --set, --threads, --json.
void addSharedOptions(CLI::App& app, ValidateCommandLine& cl) {
    app.add_option("--set", cl.sets, "override a scene key: section.key=value (repeatable)")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option("--threads", cl.threads, "OpenMP threads (default: all)")
        ->check(CLI::Range(1, 1024));
    app.add_flag("--json", cl.asJson, "print one JSON object on stdout");
}

/// dam-break: a dam break against Martin & Moyce (1952).
CLI::App* addDamBreak(CLI::App& app, ValidateCommandLine& cl) {
    auto* dam =
        app.add_subcommand("dam-break", "run a dam-break scene and compare the surge front with "
                                        "Martin & Moyce (1952) over T in [0.8, 3.0]");
    dam->add_option("scene", cl.scene, "scene JSON (the first water rectangle is the column)")
        ->required();
    dam->add_option("--until", cl.damUntil, "stop at this T = t sqrt(2g/a)")
        ->check(cli::finiteRange(0.0, 1e6));
    dam->add_option("--csv", cl.csv, "write the front series T,Z to this file");
    dam->add_option("--records", cl.records,
                    "write Martin & Moyce's two series (series,T,Z) to this file");
    addEnsemble(*dam, cl)->excludes("--csv");
    return dam;
}

/// lobovsky: the Lobovsky et al. (2014) dam break against its records.
CLI::App* addLobovsky(CLI::App& app, ValidateCommandLine& cl) {
    auto* lob = app.add_subcommand(
        "lobovsky", "run the Lobovsky et al. (2014) H = 300 mm dam break and compare the water "
                    "height at gauges H1..H4 with the records over t in [0, 1.5] s, and over the "
                    "first impact and run-up (until the record's water lands on H4), and the far "
                    "wall's pressure at sensor P1 with Buchner (2002) and Marrone et al. (2011)");
    lob->add_option("scene", cl.scene, "scene JSON (the first water rectangle is the column)")
        ->required();
    lob->add_option("--until", cl.lobovskyUntil, "stop at this time (s)")
        ->check(cli::finiteRange(0.0, 1e6));
    lob->add_option("--csv", cl.csv,
                    "write the series t,h_H1..h_H4,p_P1_over_rho_g_H (s, m) to this file");
    lob->add_option("--records", cl.records,
                    "write the experimental gauge records (gauge,x,t,h; m, s) to this file");
    lob->add_option("--pressure-records", cl.pressureRecords,
                    "write the far-wall pressure records (series,t,p; t sqrt(g/H), p/(rho g H)) "
                    "to this file");
    addEnsemble(*lob, cl)->excludes("--csv");
    return lob;
}

/// still-tank: a still tank's hydrostatics.
CLI::App* addStillTank(CLI::App& app, ValidateCommandLine& cl) {
    auto* still = app.add_subcommand("still-tank", "run a still-tank scene and check hydrostatics");
    still->add_option("scene", cl.scene, "scene JSON (the first water rectangle sets H)")
        ->required();
    still->add_option("--settle", cl.settle, "time (s) after which averages start")
        ->check(cli::finiteRange(0.0, 1e6));
    still->add_option("--steps", cl.steps, "steps to run (default: end_time / dt)")
        ->check(CLI::Range(1L, 1000000000L));
    still->add_option("--trace", cl.trace, "print step stats to stderr every N steps")
        ->check(CLI::Range(0L, 1000000000L));
    addEnsemble(*still, cl);
    return still;
}

/// regular-wave: a bake of a sinusoidal piston against linear theory.
CLI::App* addRegularWave(CLI::App& app, ValidateCommandLine& cl) {
    auto* wave = app.add_subcommand("regular-wave",
                                    "bake a sinusoidal-piston scene and compare the wave height "
                                    "with Biesel's transfer function and the wavelength with the "
                                    "dispersion relation");
    wave->add_option("scene", cl.scene,
                     "scene JSON with piston.kind sinusoidal and two or more gauges")
        ->required();
    wave->add_option("--from", cl.waveFrom,
                     "start of the fit window (s); default: after the ramp and the wave's arrival")
        ->check(cli::finiteRange(0.0, 1e6));
    wave->add_option("--to", cl.waveTo,
                     "end of the fit window (s); default: before reflections return")
        ->check(cli::finiteRange(0.0, 1e6));
    auto* keep =
        wave->add_option("--keep", cl.keep, "keep the cache and probes CSV in this folder");
    auto* probes = wave->add_option("--probes", cl.probes,
                                    "fit this probes CSV (from --keep or swell-bake --probes of "
                                    "the same scene and --set values) instead of baking")
                       ->excludes(keep);
    addEnsemble(*wave, cl)->excludes(keep)->excludes(probes);
    return wave;
}

/// standing-wave: a closed tank sloshing from a cosine top.
CLI::App* addStandingWave(CLI::App& app, ValidateCommandLine& cl) {
    auto* slosh = app.add_subcommand(
        "standing-wave", "run a closed tank whose water starts at rest with a cosine top "
                         "(geometry.water[0].surface) and compare the period at the walls with "
                         "linear theory and the decay per period with none");
    slosh->add_option("scene", cl.scene, "scene JSON (the first water rectangle, in a tank)")
        ->required();
    slosh->add_option("--csv", cl.csv, "write the elevation series t,eta_left,eta_right (m)");
    addEnsemble(*slosh, cl)->excludes("--csv");
    return slosh;
}

/// solitary-wave: one solitary wave against theory.
CLI::App* addSolitaryWave(CLI::App& app, ValidateCommandLine& cl) {
    auto* solitary = app.add_subcommand(
        "solitary-wave", "run a tank whose piston makes one solitary wave (piston.kind solitary) "
                         "and compare its celerity, height and width at output.gauges with "
                         "theory");
    solitary
        ->add_option("scene", cl.scene,
                     "scene JSON with piston.kind solitary and two or more output.gauges")
        ->required();
    solitary->add_option("--csv", cl.csv, "write the elevation series t,eta_<x>... (m)");
    addEnsemble(*solitary, cl)->excludes("--csv");
    return solitary;
}

/// wet-dam-break: a dam breaking onto a wet bed against Stoker's solution.
CLI::App* addWetDamBreak(CLI::App& app, ValidateCommandLine& cl) {
    auto* wet = app.add_subcommand(
        "wet-dam-break", "run a dam that breaks onto a wet bed (a reservoir and a lower layer) and "
                         "compare the depth at output.gauges and the bore's speed with Stoker's "
                         "shallow-water solution");
    wet->add_option("scene", cl.scene,
                    "scene JSON: two water rectangles on the tank's bed, two or more "
                    "output.gauges")
        ->required();
    wet->add_option("--csv", cl.csv, "write the depth series t,h_<x>... (m)");
    addEnsemble(*wet, cl)->excludes("--csv");
    return wet;
}

/// shoaling: a solitary wave up a beach against Grilli et al. (1994).
CLI::App* addShoaling(CLI::App& app, ValidateCommandLine& cl) {
    auto* shoal = app.add_subcommand(
        "shoaling", "run a solitary wave up a 1:34.7 beach until it breaks and compare the "
                    "elevation at the six gauges with Grilli et al. (1994)'s experiment");
    shoal
        ->add_option("scene", cl.scene,
                     "scene JSON: a solitary piston (H / h0 = 0.2), geometry.bed rising "
                     "1:34.7 from its first point, output.gauges at the experiment's gauges")
        ->required();
    shoal->add_option("--csv", cl.csv, "write the elevation series t,eta_<x>... (m)");
    shoal->add_option("--records", cl.records,
                      "write the experiment's gauge records (gauge,x_over_h0,t,eta; "
                      "t sqrt(g/h0), eta/h0) to this file");
    addEnsemble(*shoal, cl)->excludes("--csv");
    return shoal;
}

/// Refuses what CLI11 cannot: an empty scene path, and a regular-wave window that ends before
/// it starts. Returns 2 after one line on `err`; nullopt when the values hold.
std::optional<int> refuseValues(const ValidateCommandLine& cl, std::ostream& err) {
    if (cl.scene.empty()) {
        err << "swell-validate: scene: an empty path (see --help)\n";
        return cli::kExitBadInput;
    }
    if (cl.waveFrom >= 0.0 && cl.waveTo >= 0.0 && !(cl.waveTo > cl.waveFrom)) {
        err << "swell-validate: --to " << cl.waveTo << " must be after --from " << cl.waveFrom
            << " (see --help)\n";
        return cli::kExitBadInput;
    }
    return std::nullopt;
}

} // namespace

std::optional<int> parseValidateCommandLine(int argc, const char* const* argv,
                                            ValidateCommandLine& cl, std::ostream& out,
                                            std::ostream& err) {
    CLI::App app{"swell-validate: dam-break, lobovsky, still-tank, regular-wave, standing-wave, "
                 "solitary-wave, wet-dam-break and shoaling validation runs of the MPS solver"};
    app.require_subcommand(1);
    app.fallthrough();
    addSharedOptions(app, cl);
    // The subcommands, in the order --help lists them.
    CLI::App* dam = addDamBreak(app, cl);
    CLI::App* lob = addLobovsky(app, cl);
    CLI::App* still = addStillTank(app, cl);
    CLI::App* wave = addRegularWave(app, cl);
    CLI::App* slosh = addStandingWave(app, cl);
    addSolitaryWave(app, cl);
    CLI::App* wet = addWetDamBreak(app, cl);
    CLI::App* shoal = addShoaling(app, cl);

    if (const auto rc = cli::parse(app, argc, argv, "swell-validate", out, err))
        return rc;
    cl.run = *dam     ? ValidateCommandLine::Run::DamBreak
             : *lob   ? ValidateCommandLine::Run::Lobovsky
             : *still ? ValidateCommandLine::Run::StillTank
             : *wave  ? ValidateCommandLine::Run::RegularWave
             : *slosh ? ValidateCommandLine::Run::StandingWave
             : *wet   ? ValidateCommandLine::Run::WetDamBreak
             : *shoal ? ValidateCommandLine::Run::Shoaling
                      : ValidateCommandLine::Run::SolitaryWave;
    return refuseValues(cl, err);
}

Scene loadValidateScene(const ValidateCommandLine& cl) {
    return loadScene(cl.scene, cl.sets);
}

} // namespace swell::bake
