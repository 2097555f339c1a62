// The guard of the numerics version (numerics_version.h): a small fixed scene (a sinusoidal
// piston and a dam-break column in one tank, written out here so that editing a shipped scene
// cannot change it), run on one thread for kSteps steps; the digest of its state must be the
// one recorded for kNumericsVersion. A change to the solver that changes its results fails
// here until the version is bumped, so checkpoints of the old numerics are refused.
//
// Portability: the thread count changes nothing (numerics_version.h); the build uses the x86-64
// baseline (no -march=native, so no FMA contraction). The digest is still of the state rounded to a
// grid (positions to 1e-7 m, velocities to 1e-6 m/s, pressures to 1e-2 Pa), not of the exact bits:
// glibc picks its sin, cos, pow and hypot at run time by CPU (FMA variants or not), whose last bits
// may differ on another x86-64 machine with the same compiler and flags. Measured on this guard
// scene: a 1-ulp change of one particle's x at the start moves positions by at most 1.9e-13 m,
// velocities by 6.4e-12 m/s and pressures by 1.3e-8 Pa after kSteps, far below the grid,
// while a relative change of gravity of 1e-8 already changes the digest (1e-6 is tested:
// DigestSeesASmallChangeOfTheNumbers).
#include <cmath>
#include <cstdint>
#include <map>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "swell/bake/mps_solver.h"
#include "swell/bake/numerics_version.h"
#include "swell/bake/scene.h"

using namespace swell::bake;
using nlohmann::json;

namespace {

constexpr long kSteps = 120;

// The digest of each numerics version. Append only: a new version gets a new line.
const std::map<int, std::string> kDigests = {
    {1, "e2a0d8b78e7c2be8"},
    {2, "437508a02c584e2f"},
    // 3 split steps into sub-steps where a scene raises solver.courant_limit above
    // solver.substep_courant (0.5); the guard keeps the default limit, so its state is that of 2.
    {3, "437508a02c584e2f"},
    // 4: the default scheme's density term aims at n0 times the packing factor (re_packing).
    {4, "2010c855bbab618b"},
    // 5: the default scheme takes from free-surface particles the velocity their shift undoes
    // (solver.shift_damping).
    {5, "273f98b93e7f969b"},
};

json guardScene() {
    return json::parse(R"({
      "name": "numerics_guard",
      "seed": 3,
      "physics": { "kinematic_viscosity": 1e-6 },
      "geometry": {
        "particle_spacing": 0.02,
        "tank": { "x0": 0.0, "y0": 0.0, "x1": 1.2, "y1": 0.5 },
        "water": [ { "x0": 0.0, "y0": 0.0, "x1": 1.2, "y1": 0.12 },
                   { "x0": 1.0, "y0": 0.12, "x1": 1.2, "y1": 0.3 } ]
      },
      "piston": { "kind": "sinusoidal", "period": 0.5, "stroke": 0.06, "ramp_time": 0.05 },
      "solver": { "dt": 0.002, "end_time": 1.0 },
      "output": { "frame_interval": 0.02 }
    })");
}

/// FNV-1a 64 of the state rounded to the grid above, as 16 hex digits.
std::string digest(const MpsState& s) {
    std::uint64_t h = 1469598103934665603ull;
    const auto add = [&](double v, double quantum) {
        const auto q = static_cast<std::int64_t>(std::llround(v / quantum));
        for (int b = 0; b < 8; ++b) {
            h ^= static_cast<std::uint64_t>(q) >> (8 * b) & 0xffu;
            h *= 1099511628211ull;
        }
    };
    const Particles& p = s.particles;
    add(static_cast<double>(p.size()), 1.0);
    for (std::size_t i = 0; i < p.size(); ++i) {
        add(static_cast<double>(p.kind[i]), 1.0);
        add(p.x[i], 1e-7);
        add(p.y[i], 1e-7);
        add(p.vx[i], 1e-6);
        add(p.vy[i], 1e-6);
        add(p.p[i], 1e-2);
    }
    return fmt::format("{:016x}", h);
}

MpsState run(const json& j) {
    MpsSolver solver = makeSolver(parseScene(j));
    for (long k = 0; k < kSteps; ++k)
        solver.step();
    return solver.exportState();
}

} // namespace

TEST(NumericsVersion, SolverOutputMatchesTheDigestRecordedForThisVersion) {
    const MpsState s = run(guardScene());
    const auto it = kDigests.find(kNumericsVersion);
    ASSERT_NE(it, kDigests.end()) << "no digest recorded for numerics version " << kNumericsVersion
                                  << ": add {" << kNumericsVersion << ", \"" << digest(s)
                                  << "\"} to kDigests in tests/bake/numerics_version_test.cpp";
    EXPECT_EQ(digest(s), it->second)
        << "the solver's results changed, but the numerics version did not: set kNumericsVersion "
           "in bake/include/swell/bake/numerics_version.h to "
        << kNumericsVersion + 1 << " and add {" << kNumericsVersion + 1 << ", \"" << digest(s)
        << "\"} to kDigests in tests/bake/numerics_version_test.cpp (checkpoints of the old "
           "numerics are then refused, as they must be)";
}

TEST(NumericsVersion, DigestSeesASmallChangeOfTheNumbers) {
    json j = guardScene();
    const std::string base = digest(run(j));
    j["physics"]["gravity"] = 9.81 * (1.0 + 1e-6);
    EXPECT_NE(digest(run(j)), base);
}
