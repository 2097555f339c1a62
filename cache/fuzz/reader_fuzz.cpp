// libFuzzer target for the cache reader: any byte string, written to a file, must
// either read (and decode) or throw CacheError. Build with -DSWELL_FUZZ=ON and clang.
#include "swell/cache/error.h"
#include "swell/cache/reader.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string path =
        (std::filesystem::temp_directory_path() / ("swell-fuzz-" + std::to_string(::getpid())))
            .string();
    if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    try {
        const swell::cache::Reader r(path);
        (void)r.readAll();
    } catch (const swell::cache::CacheError&) {
    }
    return 0;
}
