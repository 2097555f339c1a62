#pragma once
// Probes of a bake (README.md "Programs": swell-bake --probes): per stored frame the surge
// front and the free-surface elevation at wave gauges. Pure functions; the driver writes
// the CSV.

#include <span>
#include <string>
#include <vector>

#include "swell/bake/particles.h"

namespace swell::bake {

/// What the probes read at one moment.
struct ProbeSample {
    double time = 0.0;   ///< simulated time (s)
    double frontX = 0.0; ///< surge front: largest x of a non-splash water particle (m); NaN if none
    /// Free-surface elevation (m) above the still-water level at each gauge: the top of the
    /// highest non-splash water particle (its centre + l0/2) within l0 of the gauge's x;
    /// NaN where the gauge is dry.
    std::vector<double> elevations;
};

/// Settings of the probes.
struct ProbeParams {
    double n0 = 0.0;           ///< standard number density (eq. (4))
    double splashRatio = 0.49; ///< d1 of eq. (4): water with n < d1 n0 is splash, ignored by probes
    double spacing = 0.01;     ///< l0 (m): gauge half-width and particle size
    double stillWaterLevel = 0.0; ///< elevations are measured from this y (m)
    std::vector<double> gauges;   ///< gauge x positions (m)
};

ProbeSample sampleProbes(const Particles& particles, double time, const ProbeParams& params);

/// CSV header "time,front_x,gauge_<x>..." (x in m as written by {:g}).
std::string probeCsvHeader(std::span<const double> gauges);
/// One CSV row (no newline), values with 9 significant digits, "nan" for NaN.
std::string probeCsvRow(const ProbeSample& sample);

} // namespace swell::bake
