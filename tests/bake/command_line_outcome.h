#pragma once
// A program's command line parsed as a test runs it: the status its parser returns and what it
// wrote on the error stream, and the check that a value was refused in one line.
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace swell::test {

struct Outcome {
    std::optional<int> rc;
    std::string err;
};

template <class Line, class Parse> Outcome parse(std::vector<std::string> args, Parse p) {
    std::vector<const char*> argv;
    for (const std::string& a : args)
        argv.push_back(a.c_str());
    Line cl;
    std::ostringstream out, err;
    const auto rc = p(static_cast<int>(argv.size()), argv.data(), cl, out, err);
    return {rc, err.str()};
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
