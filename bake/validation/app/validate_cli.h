#pragma once
// swell-validate's command line: its eight runs and their options, parsed and checked without
// running, so that validate_main.cpp and the options fuzz target (tests/fuzz) share it.

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "swell/bake/scene.h"

namespace swell::bake {

struct ValidateCommandLine {
    enum class Run {
        DamBreak,
        Lobovsky,
        StillTank,
        RegularWave,
        StandingWave,
        SolitaryWave,
        WetDamBreak,
        Shoaling
    };
    Run run = Run::DamBreak;
    std::string scene;             ///< the run's scene file
    std::vector<std::string> sets; ///< --set overrides, in order
    int threads = 0;               ///< 0: all
    bool asJson = false;
    double damUntil = 3.2;       ///< dam-break --until (T = t sqrt(2g/a))
    double lobovskyUntil = 1.5;  ///< lobovsky --until (s)
    std::string csv;             ///< --csv of every run but still-tank and regular-wave
    std::string records;         ///< dam-break / lobovsky / shoaling --records
    std::string pressureRecords; ///< lobovsky --pressure-records
    double settle = 2.0;         ///< still-tank --settle (s)
    long steps = -1;             ///< still-tank --steps; -1: end_time / dt
    long trace = 0;              ///< still-tank --trace
    double waveFrom = -1.0;      ///< regular-wave --from (s); -1: the default window
    double waveTo = -1.0;        ///< regular-wave --to (s); -1: the default window
    std::string keep;            ///< regular-wave --keep
    std::string probes;          ///< regular-wave --probes: fit this record, bake nothing
    int ensemble = 0;            ///< --ensemble: members (0: one run of the scene)
};

/// Parses argv into `cl`. Returns the exit status when swell-validate should stop now: 0 after
/// --help (printed on `out`), CLI11's code after a bad command line (one line
/// "swell-validate: ... (see --help)" on `err`); nullopt when it should go on.
std::optional<int> parseValidateCommandLine(int argc, const char* const* argv,
                                            ValidateCommandLine& cl, std::ostream& out,
                                            std::ostream& err);

/// The run's scene with the --set overrides. Throws SceneError.
Scene loadValidateScene(const ValidateCommandLine& cl);

} // namespace swell::bake
