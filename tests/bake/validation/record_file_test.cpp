// The record files of the validation (swell/bake/validation/record_file.h): comments, header and
// rows read as written; a damaged file refused with its name and line; the shipped files found
// where the build puts them.
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "swell/bake/validation/buchner2002.h"
#include "swell/bake/validation/grilli1994.h"
#include "swell/bake/validation/lobovsky2014.h"
#include "swell/bake/validation/martin_moyce1952.h"
#include "swell/bake/validation/record_file.h"
#include "temp_dir.h"

using namespace swell::bake::validation;

namespace {

constexpr std::array<std::string_view, 3> kColumns{"name", "t", "h"};

std::filesystem::path write(const swell::test::TempDir& dir, const std::string& text) {
    const std::filesystem::path p = dir / "records.csv";
    std::ofstream(p) << text;
    return p;
}

/// The message of the RecordFileError that reading `text` throws ("" if none).
std::string refusal(const std::string& text) {
    const swell::test::TempDir dir("swell_record_file_");
    try {
        const RecordFile f = readRecordFile(write(dir, text), kColumns);
        for (const RecordRow& row : f.rows)
            (void)f.number(row, 1);
    } catch (const RecordFileError& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(RecordFile, ReadsTheRowsAfterTheCommentsAndTheHeader) {
    const swell::test::TempDir dir("swell_record_file_");
    const auto path = write(dir, "# source: a paper\n#\nname,t,h\r\ng1,0.5,-1e-3\n\n# a note\n"
                                 "g2,1.25,2\n");
    const RecordFile f = readRecordFile(path, kColumns);
    ASSERT_EQ(f.rows.size(), 2u);
    EXPECT_EQ(f.rows[0].line, 4u);
    EXPECT_EQ(f.rows[0].fields[0], "g1");
    EXPECT_DOUBLE_EQ(f.number(f.rows[0], 1), 0.5);
    EXPECT_DOUBLE_EQ(f.number(f.rows[0], 2), -1e-3);
    EXPECT_EQ(f.rows[1].line, 7u);
    EXPECT_EQ(f.rows[1].fields[0], "g2");
    EXPECT_DOUBLE_EQ(f.number(f.rows[1], 2), 2.0);
}

TEST(RecordFile, RefusesADamagedFileNamingItsLine) {
    EXPECT_NE(refusal("name,h,t\ng1,1,2\n").find("records.csv:1: header 'name,h,t'"),
              std::string::npos);
    EXPECT_NE(refusal("name,t,h\ng1,1\n").find("records.csv:2: 2 fields, expected 3"),
              std::string::npos);
    EXPECT_NE(refusal("name,t,h\ng1,1,2\ng2,x1,2\n").find("records.csv:3: column 2: 'x1'"),
              std::string::npos);
    EXPECT_NE(refusal("name,t,h\ng1,1.5e,2\n").find("records.csv:2: column 2"), std::string::npos);
    EXPECT_NE(refusal("name,t,h\ng1,inf,2\n").find("not a finite number"), std::string::npos);
    EXPECT_NE(refusal("name,t,h\ng1,,2\n").find("records.csv:2: column 2"), std::string::npos);
    EXPECT_NE(refusal("# only a comment\n").find("no header line"), std::string::npos);
    EXPECT_NE(refusal("name,t,h\n# no rows\n").find("no rows"), std::string::npos);
}

TEST(RecordFile, RefusesAMissingFileByName) {
    try {
        (void)readRecordFile("/nonexistent/swell/none.csv", kColumns);
        FAIL() << "a missing file was read";
    } catch (const RecordFileError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/swell/none.csv"), std::string::npos);
    }
}

TEST(RecordFile, TheDataFolderIsTheEnvironmentsOrTheOneBesideBin) {
    const char* old = std::getenv("SWELL_VALIDATION_DATA");
    const std::string saved = old ? old : "";
    ::setenv("SWELL_VALIDATION_DATA", "/some/folder", 1);
    EXPECT_EQ(validationDataDir(), std::filesystem::path("/some/folder"));
    ::unsetenv("SWELL_VALIDATION_DATA");
    const std::filesystem::path beside = validationDataDir();
    if (old)
        ::setenv("SWELL_VALIDATION_DATA", saved.c_str(), 1);
    EXPECT_EQ(beside.filename(), "validation");
    EXPECT_EQ(beside.parent_path().filename(), "swell");
    // The build copies the shipped files there (the tests run from the build's bin folder).
    EXPECT_TRUE(std::filesystem::is_regular_file(beside / kMartinMoyceFile)) << beside;
}

TEST(RecordFile, TheShippedRecordsHoldEveryRowOfTheirSources) {
    EXPECT_EQ(martinMoyceA225().size(), 15u);
    EXPECT_EQ(martinMoyceA1125().size(), 10u);
    EXPECT_DOUBLE_EQ(martinMoyceA225().front().T, 0.832);
    EXPECT_DOUBLE_EQ(martinMoyceA1125().back().Z, 6.717);
    EXPECT_EQ(buchnerP1Records().size(), 525u);
    EXPECT_EQ(grilli1994Gauges().size(), 6u);
    const auto lobovsky = lobovskyH300Gauges();
    ASSERT_EQ(lobovsky.size(), 4u);
    for (const LevelGauge& g : lobovsky) {
        EXPECT_EQ(g.series.size(), 75u) << g.name;
        EXPECT_EQ(g.repeat.size(), g.name == "H1" ? 0u : 75u) << g.name;
    }
    // The last row of H1, t sqrt(g / H) = 11.2271 and h / H = 0.418011 in the file.
    EXPECT_DOUBLE_EQ(lobovsky[0].series.back().h, 0.418011 * 0.3);
}
