#pragma once
// swell-validate's checks, one function each: runs the check's scene and turns what the
// validation library measured into the check's JSON report (outcome, figures, cost). A run
// that names a file (`csv`, `keep`) writes it; an empty name writes nothing.

#include <string>

#include <nlohmann/json.hpp>

#include "swell/bake/scene.h"

namespace swell::bake {

/// A dam break (dam_break_run.h, runDamBreak) until T = t sqrt(2g/a) reaches tEnd: the surge
/// front against Martin & Moyce (1952)'s two series over T in [0.8, 3.0], raw and with the time
/// origin tied to the front, and the experiment against itself under the same rule. `csv`: the
/// front series T,Z.
nlohmann::json damBreak(const Scene& scene, double tEnd, const std::string& csv);

/// Lobovsky et al. (2014) dam break: water height at the gauges H1..H4 against the records.
/// Sampled after every solver step (denser than the records' 300 Hz); the simulated series is
/// interpolated at the record times (compareLevel). Height: top of the highest non-splash water
/// particle within l0 of the gauge (sampleProbes with the tank floor as level), 0 where dry
/// (runLobovsky). Over [0, 1.5] s, and over the first impact and run-up alone, until the
/// record's water lands on the far gauge (lobovskyRunUpEnd), with the time the run's lands there.
/// `csv`: the gauges' heights and the far wall's pressure at P1.
nlohmann::json lobovsky(const Scene& scene, double tEnd, const std::string& csv);

/// A still tank (still_tank.h, runStillTank): the bottom pressure against rho g H and the
/// water's speeds and excursions after `settle` (s), over `steps` steps; `trace` > 0 prints a
/// step's figures and its fastest water particle to stderr every `trace` steps.
nlohmann::json stillTank(const Scene& scene, double settle, long steps, long trace);

/// The regular-wave check (regular_wave.h) of a bake of `scene` (regularWaveRecord): each
/// gauge's height in its own window and the phases in the common one, or every figure in
/// [from, to] where --from / --to set it. `keep`: the folder the bake's cache and probes stay
/// in; `probes`: a probes CSV a bake of the scene wrote, fitted instead of baking.
nlohmann::json regularWave(const Scene& scene, double from, double to, const std::string& keep,
                           const std::string& probes);

/// A standing wave (standing_wave.h, runStandingWave): the period at the two side walls
/// against linear theory's and the decay per period against none.
nlohmann::json standingWave(const Scene& scene, const std::string& csv);

/// A solitary wave (solitary_wave.h, runSolitaryWave): its crest at each gauge, its celerity
/// against sqrt(g (h + A)), the height it loses and its width against Boussinesq's.
nlohmann::json solitaryWave(const Scene& scene, const std::string& csv);

/// A dam breaking onto a wet bed (wet_dam_break.h, runWetDamBreak): the depth at each gauge and
/// the bore's speed against Stoker's shallow-water solution.
nlohmann::json wetDamBreak(const Scene& scene, const std::string& csv);

/// A solitary wave shoaling up a beach (shoaling.h, runShoaling): the elevation at the six
/// gauges against Grilli et al. (1994)'s records, on the clock of g0's crest.
nlohmann::json shoaling(const Scene& scene, const std::string& csv);

} // namespace swell::bake
