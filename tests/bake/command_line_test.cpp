// The command lines of swell-bake and swell-mps-bench (bake/app/*_cli.h): nonsense values are
// refused with one line and a non-zero status, without running anything. The options fuzz target
// (tests/fuzz) checks every refusal is one line; these check that the values below are refused at
// all.
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "bake_cli.h"
#include "mps_bench_cli.h"

#include "command_line_outcome.h"

#include "swell/bake/error.h"

using namespace swell::bake;
using swell::test::expectRefused;
using swell::test::Outcome;

namespace {

Outcome bake(const std::vector<std::string>& a) {
    return swell::test::parseAs<BakeCommandLine>("swell-bake", a, parseBakeCommandLine);
}
Outcome bench(const std::vector<std::string>& a) {
    return swell::test::parseAs<MpsBenchCommandLine>("swell-mps-bench", a,
                                                     parseMpsBenchCommandLine);
}

} // namespace

TEST(CommandLine, SwellBakeAcceptsABakeAndRefusesEmptyPathsAndControlCharacters) {
    EXPECT_FALSE(bake({"s.json", "-o", "c.swell", "--threads", "2"}).rc.has_value());
    expectRefused(bake({"s.json", "-o", ""}), "swell-bake", "--output");
    expectRefused(bake({"", "-o", "c.swell"}), "swell-bake", "SCENE");
    expectRefused(bake({"s.json", "-o", "c.swell", "--threads", "0"}), "swell-bake", "--threads");
    expectRefused(bake({"s.json", "-o", "c.swell", "x\ry"}), "swell-bake", "x\\x0dy");
}

TEST(CommandLine, SwellMpsBenchRefusesNoStepsAndTakesItsSceneOverrides) {
    EXPECT_FALSE(bench({"--steps", "10", "--warmup", "0"}).rc.has_value());
    expectRefused(bench({"--steps", "0"}), "swell-mps-bench", "--steps");
    expectRefused(bench({"--warmup", "-1"}), "swell-mps-bench", "--warmup");
    MpsBenchCommandLine cl;
    cl.sets = {"geometry.particle_spacing=0.02", "solver.dt=0.001"};
    EXPECT_DOUBLE_EQ(mpsBenchScene(cl).geometry.particleSpacing, 0.02);
    cl.sets = {"solver.scheme=nope"};
    EXPECT_THROW((void)mpsBenchScene(cl), SceneError);
}
