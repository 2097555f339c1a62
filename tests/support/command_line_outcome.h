#pragma once
// A program's command line parsed as a test runs it: the status its parser returns and what it
// wrote on its output and error streams, and the check that a value was refused in one line.
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace swell::test {

struct Outcome {
    std::optional<int> rc;
    std::string err;
    std::string out;
};

/// Calls `p(argc, argv, out, err)` with `args` as argv.
template <class Parse> Outcome run(const std::vector<std::string>& args, Parse p) {
    std::vector<const char*> argv;
    for (const std::string& a : args)
        argv.push_back(a.c_str());
    std::ostringstream out, err;
    const auto rc = p(static_cast<int>(argv.size()), argv.data(), out, err);
    return {rc, err.str(), out.str()};
}

/// Parses `args` with a parser of the shape parseBakeCommandLine(argc, argv, Line&, out, err).
template <class Line, class Parse> Outcome parse(std::vector<std::string> args, Parse p) {
    Line cl;
    return run(args, [&](int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
        return p(argc, argv, cl, out, err);
    });
}

/// The same with `program` (argv[0]) before `args`.
template <class Line, class Parse>
Outcome parseAs(const std::string& program, std::vector<std::string> args, Parse p) {
    args.insert(args.begin(), program);
    return parse<Line>(std::move(args), p);
}

/// Refused: a non-zero status and one line starting with the program's name.
inline void expectRefused(const Outcome& o, const std::string& program,
                          const std::string& mention) {
    ASSERT_TRUE(o.rc.has_value()) << mention;
    EXPECT_NE(*o.rc, 0);
    EXPECT_EQ(o.err.rfind(program + ": ", 0), 0u) << o.err;
    EXPECT_EQ(o.err.find('\n'), o.err.size() - 1) << o.err;
    EXPECT_NE(o.err.find(mention), std::string::npos) << o.err;
}

} // namespace swell::test
