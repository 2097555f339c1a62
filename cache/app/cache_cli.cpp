#include "cache_cli.h"

#include "command_line.h"

namespace swell::cache {
namespace {

void addEncodingOptions(CLI::App* cmd, CacheOptions& o) {
    cmd->add_option("--encoding", o.encoding, "float32 or quantized16")
        ->check(CLI::IsMember({"float32", "quantized16"}));
    cmd->add_flag("--no-shuffle", o.noShuffle, "disable the byte-shuffle filter");
    cmd->add_flag("--no-delta", o.noDelta, "disable the delta filter");
    cmd->add_option("--level", o.level, "zstd level")->check(CLI::Range(1, 19));
}

} // namespace

std::optional<int> parseCacheCommandLine(int argc, const char* const* argv, CacheOptions& o,
                                         CacheCommand& command, std::ostream& out,
                                         std::ostream& err) {
    CLI::App app{"swell-cache: inspect, verify, dump and synthesize .swell caches"};
    app.require_subcommand(1);
    auto* info = app.add_subcommand("info", "Summarize a cache (header, counts, sizes)");
    info->add_option("CACHE", o.path, "cache file")->required();
    info->add_flag("--json", o.asJson, "print one JSON object");
    auto* verify = app.add_subcommand("verify", "Decode every frame and check every checksum");
    verify->add_option("CACHE", o.path, "cache file")->required();
    verify->add_flag("--json", o.asJson, "print one JSON object");
    auto* dump = app.add_subcommand("dump", "Print one frame's particles as CSV");
    dump->add_option("CACHE", o.path, "cache file")->required();
    dump->add_option("--frame", o.frameIndex, "frame index (0 first)")
        ->required()
        ->check(CLI::Validator(
            [](std::string& text) {
                return !text.empty() && text.find_first_not_of("0123456789") == std::string::npos
                           ? std::string()
                           : "Value " + text + " is not a frame index (0, 1, 2, ...)";
            },
            "INDEX"));
    auto* recode = app.add_subcommand(
        "recode",
        "Copy a cache with another encoding or filters (frames, header and metadata kept)");
    recode->add_option("CACHE", o.path, "input cache file")->required();
    recode->add_option("OUT", o.recodeOut, "output cache file")->required();
    auto* synth = app.add_subcommand(
        "synth", "Write a synthetic cache (travelling wave) for demos and benchmarks");
    synth->add_option("OUT", o.path, "output cache file")->required();
    synth->add_option("--frames", o.frames, "number of frames")->check(CLI::Range(1, 1000000));
    synth->add_option("--surface", o.wave.surfaceCount, "surface particles per frame")
        ->check(CLI::Range(0, 10000000));
    synth->add_option("--splash", o.wave.splashCount, "splash particles per frame")
        ->check(CLI::Range(0, 10000000));
    synth->add_option("--seed", o.wave.seed, "seed of the jitter and splash placement");
    addEncodingOptions(synth, o);
    addEncodingOptions(recode, o);
    if (const auto rc = cli::parse(app, argc, argv, "swell-cache", out, err))
        return rc;
    const std::pair<CLI::App*, CacheCommand> commands[] = {{info, CacheCommand::Info},
                                                           {verify, CacheCommand::Verify},
                                                           {dump, CacheCommand::Dump},
                                                           {recode, CacheCommand::Recode},
                                                           {synth, CacheCommand::Synth}};
    for (const auto& [cmd, which] : commands) {
        if (*cmd)
            command = which;
    }
    for (const std::string* p : {&o.path, &o.recodeOut}) {
        if (p->empty() && (p == &o.path || command == CacheCommand::Recode)) {
            err << "swell-cache: " << (p == &o.path ? "CACHE" : "OUT")
                << ": an empty path (see --help)\n";
            return cli::kExitBadInput;
        }
    }
    return std::nullopt;
}

} // namespace swell::cache
