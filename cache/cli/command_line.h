#pragma once
// What every program's command line shares (swell-bake, swell-cache, swell-play,
// swell-validate, swell-mps-bench): parsing with CLI11 into one clear error line, and a check
// for finite numbers. Header-only (target swell_cli); cache/ is the library every app uses.

#include <CLI/CLI.hpp>

#include "exit_codes.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace swell::cli {

/// `message` with control characters (an argument may hold any) escaped: one line.
inline std::string oneLine(const std::string& message) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    for (const char c : message) {
        const auto u = static_cast<unsigned char>(c);
        if (u < 0x20 || u == 0x7f) {
            out += "\\x";
            out += kHex[u >> 4];
            out += kHex[u & 0xf];
        } else {
            out += c;
        }
    }
    return out;
}

/// The edit distance between `a` and `b` (insertions, deletions, substitutions).
inline std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = up;
        }
    }
    return row[b.size()];
}

/// When `app` has subcommands and `word` (the first argument) is none of them: "unknown
/// subcommand 'word'" and the nearest name ("did you mean 'render'?"), or the list of names.
inline std::optional<std::string> unknownSubcommand(const CLI::App& app, const std::string& word) {
    const auto subs = app.get_subcommands([](const CLI::App*) { return true; });
    if (subs.empty() || word.empty() || word[0] == '-')
        return std::nullopt;
    std::string names, nearest;
    std::size_t best = 3; // at most two edits away
    for (const CLI::App* sub : subs) {
        if (sub->check_name(word))
            return std::nullopt;
        names += (names.empty() ? "" : ", ") + sub->get_name();
        const std::size_t d = editDistance(word, sub->get_name());
        if (d < best) {
            best = d;
            nearest = sub->get_name();
        }
    }
    std::string message = "unknown subcommand '" + oneLine(word) + "'";
    return message + (nearest.empty() ? "; the subcommands are " + names
                                      : "; did you mean '" + nearest + "'?");
}

/// Parses argv with `app`. Returns nullopt when the program should go on, else its exit status:
/// 0 after --help (printed on `out`); after a bad command line one line "PROGRAM: problem (see
/// --help)" on `err` and kExitBadInput.
inline std::optional<int> parse(CLI::App& app, int argc, const char* const* argv,
                                const std::string& program, std::ostream& out, std::ostream& err) {
    if (argc > 1) {
        if (const auto unknown = unknownSubcommand(app, argv[1])) {
            err << program << ": " << *unknown << " (see --help)\n";
            return kExitBadInput;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0)
            return app.exit(e, out, err);
        err << program << ": " << oneLine(e.what()) << " (see --help)\n";
        return kExitBadInput;
    }
    return std::nullopt;
}

/// "[lo, hi]" with the bounds as C++ streams print them (1e+06, not 1000000.000000).
inline std::string range(double lo, double hi) {
    std::ostringstream s;
    s << "[" << lo << ", " << hi << "]";
    return s.str();
}

/// A CLI11 check: a finite number in [lo, hi] (CLI::Range lets NaN through).
inline CLI::Validator finiteRange(double lo, double hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            double v = 0.0;
            std::size_t used = 0;
            try {
                v = std::stod(text, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used == 0 || used != text.size() || !std::isfinite(v) || v < lo || v > hi)
                return "Value " + text + " not a finite number in " + range(lo, hi);
            return std::string();
        },
        "FINITE in " + range(lo, hi));
}

} // namespace swell::cli
