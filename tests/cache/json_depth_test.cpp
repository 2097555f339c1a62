#include "cache_test_util.h"

#include "swell/cache/error.h"
#include "swell/cache/json_depth.h"
#include "swell/cache/reader.h"

#include <string>

using namespace swell::cache;
using namespace swell::cache::testing;

namespace {

std::string nested(std::size_t levels) {
    return std::string(levels, '[') + std::string(levels, ']');
}

} // namespace

TEST(JsonDepth, CountsOpenArraysAndObjectsNotBracketsInStrings) {
    EXPECT_EQ(jsonNestingDepth(""), 0u);
    EXPECT_EQ(jsonNestingDepth("3.5"), 0u);
    EXPECT_EQ(jsonNestingDepth(R"("[[[{")"), 0u);
    EXPECT_EQ(jsonNestingDepth("[]"), 1u);
    EXPECT_EQ(jsonNestingDepth(R"({"a": [1, {"b": [2]}], "c": [[3]]})"), 4u);
    EXPECT_EQ(jsonNestingDepth(R"(["a\"[[[", ["\\"], "]]]"])"), 2u); // escapes end no string
    EXPECT_EQ(jsonNestingDepth("]]]][["), 2u); // unbalanced text: still a count, never negative
    EXPECT_EQ(jsonNestingDepth(nested(1000000)), 1000000u);
    EXPECT_TRUE(jsonDepthAcceptable(nested(kMaxJsonDepth)));
    EXPECT_FALSE(jsonDepthAcceptable(nested(kMaxJsonDepth + 1)));
    EXPECT_EQ(jsonDepthProblem(nested(kMaxJsonDepth)), "");
    EXPECT_EQ(jsonDepthProblem(nested(kMaxJsonDepth + 1)),
              "nests 65 levels deep, more than the 64 allowed");
}

TEST(JsonDepth, ReaderRefusesMetadataNestedAMillionLevelsNamingTheDepth) {
    TempDir dir;
    const auto w = smallWave(20, 1);
    Header h = headerFor(w);
    h.metadataJson = nested(1000000); // valid JSON, 2 MB
    writeSynthetic(dir / "deep.swell", h, w, 2);
    try {
        const Reader r(dir / "deep.swell");
        ADD_FAILURE() << "metadata nested 1,000,000 levels was accepted";
    } catch (const CacheError& e) {
        EXPECT_NE(std::string(e.what()).find("nests 1000000 levels deep"), std::string::npos)
            << e.what();
    }
    h.metadataJson = "{\"a\": " + nested(kMaxJsonDepth - 1) + "}"; // at the limit: read
    writeSynthetic(dir / "ok.swell", h, w, 2);
    const Reader r(dir / "ok.swell");
    EXPECT_EQ(r.header().metadataJson, h.metadataJson);
}
