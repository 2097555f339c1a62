// The command line of swell-validate (bake/validation/app/validate_cli.h): each subcommand is
// run by name, and nonsense values are refused with one line and a non-zero status, without
// running anything. The options fuzz target (tests/fuzz) checks every refusal is one line.
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "command_line_outcome.h"
#include "validate_cli.h"

using namespace swell::bake;
using swell::test::expectRefused;
using swell::test::Outcome;

namespace {

Outcome validate(const std::vector<std::string>& a) {
    return swell::test::parseAs<ValidateCommandLine>("swell-validate", a, parseValidateCommandLine);
}
} // namespace

TEST(CommandLine, SwellValidateRunsTheSubcommandNamed) {
    using Run = ValidateCommandLine::Run;
    for (const auto& [name, run] : {std::pair{"dam-break", Run::DamBreak},
                                    {"lobovsky", Run::Lobovsky},
                                    {"still-tank", Run::StillTank},
                                    {"regular-wave", Run::RegularWave},
                                    {"standing-wave", Run::StandingWave},
                                    {"solitary-wave", Run::SolitaryWave},
                                    {"wet-dam-break", Run::WetDamBreak},
                                    {"shoaling", Run::Shoaling}}) {
        const char* argv[] = {"swell-validate", name, "s.json"};
        ValidateCommandLine cl;
        std::ostringstream out, err;
        EXPECT_FALSE(parseValidateCommandLine(3, argv, cl, out, err).has_value()) << name;
        EXPECT_EQ(cl.run, run) << name;
        EXPECT_EQ(cl.scene, "s.json") << name;
    }
}

TEST(CommandLine, SwellValidateRefusesNonsenseValues) {
    EXPECT_FALSE(validate({"dam-break", "s.json", "--until", "2"}).rc.has_value());
    expectRefused(validate({"dam-break", "s.json", "--until", "nan"}), "swell-validate", "--until");
    expectRefused(validate({"lobovsky", "s.json", "--until", "-1"}), "swell-validate", "--until");
    expectRefused(validate({"still-tank", "s.json", "--steps", "-5"}), "swell-validate", "--steps");
    expectRefused(validate({"still-tank", "s.json", "--settle", "inf"}), "swell-validate",
                  "--settle");
    expectRefused(validate({"regular-wave", "s.json", "--from", "5", "--to", "2"}),
                  "swell-validate", "--to");
    expectRefused(validate({"--threads", "-3", "dam-break", "s.json"}), "swell-validate",
                  "--threads");
    EXPECT_FALSE(validate({"dam-break", "s.json", "--records", "mm.csv"}).rc.has_value());
    EXPECT_FALSE(validate({"lobovsky", "s.json", "--records", "lob.csv"}).rc.has_value());
    EXPECT_FALSE(validate({"lobovsky", "s.json", "--pressure-records", "p1.csv"}).rc.has_value());
    expectRefused(validate({"dam-break", "s.json", "--pressure-records", "p1.csv"}),
                  "swell-validate", "--pressure-records");
    expectRefused(validate({"still-tank", "s.json", "--records", "r.csv"}), "swell-validate",
                  "--records");
    EXPECT_FALSE(validate({"regular-wave", "s.json", "--ensemble", "4"}).rc.has_value());
    expectRefused(validate({"regular-wave", "s.json", "--ensemble", "0"}), "swell-validate",
                  "--ensemble");
    expectRefused(validate({"regular-wave", "s.json", "--ensemble", "2", "--keep", "d"}),
                  "swell-validate", "--keep");
    // A kept record is fitted again, with nothing baked: not with --keep or --ensemble.
    EXPECT_FALSE(validate({"regular-wave", "s.json", "--probes", "p.csv"}).rc.has_value());
    expectRefused(validate({"regular-wave", "s.json", "--probes", "p.csv", "--keep", "d"}),
                  "swell-validate", "--probes");
    expectRefused(validate({"regular-wave", "s.json", "--probes", "p.csv", "--ensemble", "2"}),
                  "swell-validate", "--probes");
    // The standing wave: a scene, a series to write, or an ensemble of members.
    EXPECT_FALSE(validate({"standing-wave", "s.json"}).rc.has_value());
    EXPECT_FALSE(validate({"standing-wave", "s.json", "--csv", "eta.csv"}).rc.has_value());
    EXPECT_FALSE(validate({"standing-wave", "s.json", "--ensemble", "4"}).rc.has_value());
    expectRefused(validate({"standing-wave", "s.json", "--ensemble", "2", "--csv", "eta.csv"}),
                  "swell-validate", "--csv");
    expectRefused(validate({"standing-wave", "s.json", "--settle", "2"}), "swell-validate",
                  "--settle");
    // The solitary wave: the same options.
    EXPECT_FALSE(validate({"solitary-wave", "s.json"}).rc.has_value());
    EXPECT_FALSE(validate({"solitary-wave", "s.json", "--csv", "eta.csv"}).rc.has_value());
    EXPECT_FALSE(validate({"solitary-wave", "s.json", "--ensemble", "4"}).rc.has_value());
    expectRefused(validate({"solitary-wave", "s.json", "--ensemble", "2", "--csv", "eta.csv"}),
                  "swell-validate", "--csv");
    expectRefused(validate({"solitary-wave", "s.json", "--keep", "d"}), "swell-validate", "--keep");
    // The wet-bed dam break: the same options.
    EXPECT_FALSE(validate({"wet-dam-break", "s.json", "--csv", "h.csv"}).rc.has_value());
    EXPECT_FALSE(validate({"wet-dam-break", "s.json", "--ensemble", "4"}).rc.has_value());
    expectRefused(validate({"wet-dam-break", "s.json", "--ensemble", "2", "--csv", "h.csv"}),
                  "swell-validate", "--csv");
    expectRefused(validate({"wet-dam-break", "s.json", "--settle", "2"}), "swell-validate",
                  "--settle");
    // The shoaling wave: a series, the experiment's records or an ensemble.
    EXPECT_FALSE(validate({"shoaling", "s.json", "--csv", "eta.csv"}).rc.has_value());
    EXPECT_FALSE(validate({"shoaling", "s.json", "--records", "g.csv"}).rc.has_value());
    EXPECT_FALSE(validate({"shoaling", "s.json", "--ensemble", "4"}).rc.has_value());
    expectRefused(validate({"shoaling", "s.json", "--ensemble", "2", "--csv", "eta.csv"}),
                  "swell-validate", "--csv");
    expectRefused(validate({"shoaling", "s.json", "--until", "2"}), "swell-validate", "--until");
    // The dam breaks and the still tank run as ensembles too; an ensemble has no single
    // series to write.
    EXPECT_FALSE(validate({"lobovsky", "s.json", "--ensemble", "4"}).rc.has_value());
    EXPECT_FALSE(validate({"dam-break", "s.json", "--ensemble", "3"}).rc.has_value());
    expectRefused(validate({"lobovsky", "s.json", "--ensemble", "65"}), "swell-validate",
                  "--ensemble");
    expectRefused(validate({"lobovsky", "s.json", "--ensemble", "2", "--csv", "h.csv"}),
                  "swell-validate", "--csv");
    expectRefused(validate({"dam-break", "s.json", "--ensemble", "2", "--csv", "f.csv"}),
                  "swell-validate", "--csv");
    EXPECT_FALSE(validate({"still-tank", "s.json", "--ensemble", "4"}).rc.has_value());
    expectRefused(validate({"still-tank", "s.json", "--ensemble", "-1"}), "swell-validate",
                  "--ensemble");
}
