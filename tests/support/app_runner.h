#pragma once
// Runs a program of ours as a user would (through the shell) and captures its exit code,
// stdout and stderr: the end-to-end tests of every program share it.

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace swell::test {

struct AppResult {
    int code = -1;
    std::string out;
    std::string err;
};

inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

/// `env exe args`, with stdout and stderr captured through files in `scratch`.
inline AppResult runApp(const std::string& exe, const std::string& args, const std::string& env,
                        const std::filesystem::path& scratch) {
    const std::filesystem::path out = scratch / "stdout.txt", err = scratch / "stderr.txt";
    const std::string cmd =
        env + " " + exe + " " + args + " >" + out.string() + " 2>" + err.string();
    const int status = std::system(cmd.c_str());
    AppResult r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
}

} // namespace swell::test
