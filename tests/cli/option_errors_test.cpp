// Every option of every program, given values it may refuse, is refused in the user's words: the
// one error line names the option as --help lists it (any of its names: -F or --fluctuation).
// The options are read from each program's and subcommand's --help, so an option added later is
// covered without a change here; the command lines are parsed and checked in-process (the
// programs' *_cli libraries: what each program checks before it reads a file or starts work).
#include <cstdio>
#include <functional>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bake_cli.h"
#include "cache_cli.h"
#include "mps_bench_cli.h"
#include "play_cli.h"
#include "validate_cli.h"

#include "command_line_outcome.h"

namespace {

using swell::test::Outcome;
using Parse = std::function<Outcome(const std::vector<std::string>&)>;

template <class Line, class F> Parse parser(F f) {
    return [f](const std::vector<std::string>& args) { return swell::test::parse<Line>(args, f); };
}

Parse playParser() {
    return [](const std::vector<std::string>& args) {
        swell::play::PlayCommandLine cl;
        return swell::test::run(args,
                                [&](int argc, const char* const* argv, std::ostream& out,
                                    std::ostream& err) { return cl.parse(argc, argv, out, err); });
    };
}

Parse cacheParser() {
    return [](const std::vector<std::string>& args) {
        swell::cache::CacheOptions o;
        swell::cache::CacheCommand command{};
        return swell::test::run(
            args, [&](int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
                return swell::cache::parseCacheCommandLine(argc, argv, o, command, out, err);
            });
    };
}

/// An option as --help lists it: its names ("-F", "--fluctuation") and how many values it takes.
struct Option {
    std::vector<std::string> names;
    int values = 1;
};

/// The options that take a value in a --help text (its "Options:" section; flags take none).
std::vector<Option> optionsOf(const std::string& help) {
    static const std::regex line(
        R"(^  ((?:-{1,2}[A-Za-z0-9][\w-]*)(?:,-{1,2}[A-Za-z0-9][\w-]*)*) ([A-Z]+)(.*)$)");
    static const std::regex times(R"( x (\d+))");
    std::vector<Option> options;
    std::istringstream in(help);
    bool inOptions = false;
    for (std::string l; std::getline(in, l);) {
        if (l == "Options:") {
            inOptions = true;
            continue;
        }
        if (!l.empty() && l[0] != ' ')
            inOptions = false;
        std::smatch m;
        if (!inOptions || !std::regex_match(l, m, line))
            continue;
        Option o;
        std::stringstream names(m[1].str());
        for (std::string n; std::getline(names, n, ',');)
            o.names.push_back(n);
        std::smatch t;
        const std::string rest = m[3].str();
        if (std::regex_search(rest, t, times))
            o.values = std::stoi(t[1].str());
        options.push_back(o);
    }
    return options;
}

/// Values a user may mistype; each option is given each in turn.
const std::vector<std::string> kBadValues = {"abc",    "nan", "-1",  "0",   "1e300",
                                             "-1e300", "",    "0x0", "1:1", "99999999999999999999"};

struct Program {
    std::string name;
    Parse parse;
    std::vector<std::string> before; ///< arguments before the subcommand (none: "")
    /// Each subcommand ("" for a program without) and the arguments that make it valid.
    std::vector<std::pair<std::string, std::vector<std::string>>> commands;
};

std::vector<Program> programs() {
    using namespace swell::bake;
    const std::vector<std::string> cacheArgs = {"c.swell"};
    std::vector<std::pair<std::string, std::vector<std::string>>> validate;
    for (const char* c : {"dam-break", "lobovsky", "still-tank", "regular-wave", "standing-wave",
                          "solitary-wave", "wet-dam-break", "shoaling"})
        validate.push_back({c, {"s.json"}});
    return {
        {"swell-bake",
         parser<BakeCommandLine>(parseBakeCommandLine),
         {},
         {{"", {"s.json", "-o", "c.swell"}}}},
        {"swell-mps-bench", parser<MpsBenchCommandLine>(parseMpsBenchCommandLine), {}, {{"", {}}}},
        {"swell-validate", parser<ValidateCommandLine>(parseValidateCommandLine), {}, validate},
        {"swell-cache",
         cacheParser(),
         {},
         {{"info", cacheArgs},
          {"verify", cacheArgs},
          {"dump", {"c.swell", "--frame", "0"}},
          {"recode", {"c.swell", "d.swell", "--encoding", "float32"}},
          {"synth", cacheArgs}}},
        {"swell-play",
         playParser(),
         {},
         {{"bench", cacheArgs},
          {"heights", {"c.swell", "--out", "o"}},
          {"render", {"c.swell", "--out", "o"}},
          {"fidelity", cacheArgs},
          {"look", cacheArgs}}},
    };
}

std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

} // namespace

TEST(OptionErrors, EveryOptionOfEveryProgramIsNamedInItsRefusal) {
    std::size_t options = 0, refusals = 0;
    for (const Program& p : programs()) {
        const std::vector<Option> top = optionsOf(p.parse({p.name, "--help"}).out);
        for (const auto& [sub, base] : p.commands) {
            SCOPED_TRACE(p.name + " " + sub);
            const std::vector<std::string> head = sub.empty()
                                                      ? std::vector<std::string>{p.name}
                                                      : std::vector<std::string>{p.name, sub};
            const Outcome valid = p.parse(concat(head, base));
            ASSERT_FALSE(valid.rc.has_value()) << "the base command line is refused: " << valid.err;
            std::vector<Option> all =
                sub.empty() ? top : optionsOf(p.parse(concat(head, {"--help"})).out);
            for (const Option& o : all) {
                if (o.names.back() == "--help")
                    continue;
                ++options;
                for (const std::string& v : kBadValues) {
                    std::vector<std::string> args = concat(head, base);
                    args.push_back(o.names.back());
                    for (int i = 0; i < o.values; ++i)
                        args.push_back(v);
                    const Outcome r = p.parse(args);
                    if (!r.rc.has_value() || *r.rc == 0)
                        continue; // accepted
                    ++refusals;
                    const std::string typed = o.names.back() + " '" + v + "'";
                    EXPECT_EQ(*r.rc, 2) << typed << ": " << r.err;
                    bool named = false;
                    for (const std::string& n : o.names)
                        named = named || r.err.find(n) != std::string::npos;
                    EXPECT_TRUE(named) << typed << ": " << r.err;
                    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << typed << ": " << r.err;
                }
            }
        }
    }
    std::printf("%zu options, %zu refusals\n", options, refusals);
    // The sweep is real: every program's options were read and most values refused somewhere.
    EXPECT_GT(options, 150u);
    EXPECT_GT(refusals, 600u);
}
