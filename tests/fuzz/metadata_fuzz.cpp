// libFuzzer target for a cache's metadata (docs/cache-format.md): any byte string is written,
// verbatim, as the metadata of a one-frame cache. Opening it must either succeed, or be refused
// with one CacheError line that names the file; an opened cache's metadata is JSON nested at
// most 64 levels (json_depth.h) that parses and prints, and the runtime's record of the bake
// (bakeRecord, the `replay` block) is read or refused with one line naming its key. Nothing
// may crash, recurse without bound or allocate without bound.
#include "fuzz_check.h"

#include "swell/cache/error.h"
#include "swell/cache/json_depth.h"
#include "swell/cache/reader.h"
#include "swell/cache/writer.h"
#include "swell/runtime/replay/bake_record.h"

#include "temp_dir.h"

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

using swell::fuzz::require;
namespace cache = swell::cache;

namespace {

/// Writes a one-frame cache whose metadata is `metadata`; its path.
std::filesystem::path writeCache(const std::string& metadata) {
    static const swell::test::TempDir folder("swell-metadata-fuzz-");
    const std::filesystem::path path = folder.path() / "m.swell";
    cache::Header header;
    header.metadataJson = metadata;
    cache::Writer writer(path, header);
    cache::Frame frame;
    frame.surface = {0.25f, 0.5f, 0.75f, 0.5f};
    writer.addFrame(frame);
    writer.finish();
    return path;
}

void checkOpened(const cache::Reader& reader) {
    const std::string& text = reader.header().metadataJson;
    require(cache::jsonDepthAcceptable(text), "metadata deeper than the limit was accepted");
    nlohmann::json meta;
    try {
        meta = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        swell::fuzz::fail("the reader accepted metadata that does not parse", e.what());
    }
    (void)meta.dump(); // swell-cache info prints it
    try {
        (void)swell::runtime::bakeRecord(reader.header());
    } catch (const std::invalid_argument& e) {
        swell::fuzz::requireClearError(e.what(), "cache metadata replay");
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size > (16u << 20))
        return 0; // the writer's own limit (16 MiB), refused before a file is written
    const std::string metadata(reinterpret_cast<const char*>(data), size);
    const std::filesystem::path path = writeCache(metadata);
    try {
        const cache::Reader reader(path);
        checkOpened(reader);
    } catch (const cache::CacheError& e) {
        swell::fuzz::requireClearError(e.what(), path.string() + ": ");
    }
    return 0;
}
