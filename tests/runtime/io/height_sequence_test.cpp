// A folder of height maps and its sidecar (height_sequence.h): format names, file names
// (Blender's disp_#### from 0001), what each format writes, and what heights.json records.
#include "swell/runtime/io/height_sequence.h"

#include "temp_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace swell::runtime {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

HeightField fieldAt(double t) {
    HeightField f{12, 8, {}};
    for (int m = 0; m < f.cellsZ; ++m) {
        for (int n = 0; n < f.cellsX; ++n)
            f.heights.push_back(0.5 + 0.03 * std::sin(0.5 * n - 0.3 * m + t));
    }
    return f;
}

Grid smallGrid() {
    Grid g;
    g.cellsX = 12;
    g.cellsZ = 8;
    g.slices = 4;
    g.x0 = 0.4;
    g.dx = 0.05;
    g.dz = 0.1;
    g.extentZ = 0.8;
    return g;
}

const HeightScale kPngScale{0.0, 1.0 / 65535.0};

} // namespace

TEST(HeightSequence, FormatNamesParseAndABadOneListsTheValidOnes) {
    EXPECT_EQ(parseHeightFormat("png16", "--format"), HeightFormat::Png16);
    EXPECT_EQ(parseHeightFormat("exr-half", "--format"), HeightFormat::ExrHalf);
    EXPECT_EQ(parseHeightFormat("exr-float", "--format"), HeightFormat::ExrFloat);
    for (HeightFormat f : {HeightFormat::Png16, HeightFormat::ExrHalf, HeightFormat::ExrFloat})
        EXPECT_EQ(parseHeightFormat(heightFormatName(f), "--format"), f);
    try {
        parseHeightFormat("exr", "--heights-format");
        ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        for (const char* needle : {"--heights-format", "'exr'", "png16", "exr-half", "exr-float"})
            EXPECT_NE(what.find(needle), std::string::npos) << what;
    }
}

TEST(HeightSequence, FileNamesFollowTheFrameAndBlendersNumbering) {
    EXPECT_EQ(heightFileName(0, HeightFormat::Png16), "height_00000.png");
    EXPECT_EQ(heightFileName(12, HeightFormat::ExrHalf), "height_00012.exr");
    EXPECT_EQ(normalFileName(3), "normal_00003.exr");
    EXPECT_EQ(displacementFileName(0), "disp_0001.exr"); // Blender's frame 1
    EXPECT_EQ(displacementFileName(41), "disp_0042.exr");
    EXPECT_EQ(displacementFileName(9999), "disp_10000.exr"); // as Blender's %04d goes on
}

TEST(HeightSequence, ExrSequenceWritesEveryFileAndASidecarThatNamesThem) {
    const swell::test::TempDir temp("swell_height_sequence_");
    HeightSequenceParams params;
    params.format = HeightFormat::ExrFloat;
    params.normals = true;
    params.displacement = true;
    HeightSequence sequence(temp.path(), params, kPngScale, smallGrid(),
                            {0.5, "still_water_level"});
    for (std::size_t i = 0; i < 3; ++i) {
        const json& entry = sequence.write(i, fieldAt(0.1 * i), 0.25 * i, 0.1 * i);
        EXPECT_EQ(entry["file"], heightFileName(i, HeightFormat::ExrFloat));
        EXPECT_EQ(entry["normals"], normalFileName(i));
        EXPECT_EQ(entry["disp"], displacementFileName(i));
        EXPECT_DOUBLE_EQ(entry["tau"].get<double>(), 0.25 * i);
    }
    const HeightField back = readHeightExr(temp / "height_00002.exr");
    const HeightField want = fieldAt(0.2);
    for (std::size_t i = 0; i < want.heights.size(); ++i)
        EXPECT_EQ(back.heights[i], static_cast<float>(want.heights[i]));
    const ExrImage disp = readExr(temp / "disp_0003.exr");
    EXPECT_FLOAT_EQ(disp.at(4, 5, disp.channel("G")), static_cast<float>(want.at(4, 5) - 0.5));
    EXPECT_TRUE(fs::exists(temp / "normal_00002.exr"));
    EXPECT_FALSE(fs::exists(temp / "disp_0000.exr"));

    const fs::path sidecarPath = sequence.writeSidecar({{"seed", 3}}, "test renderer");
    EXPECT_EQ(sidecarPath, temp / "heights.json");
    const json meta = json::parse(std::ifstream(sidecarPath));
    EXPECT_EQ(meta["seed"], 3); // the caller's parameters stay
    EXPECT_EQ(meta["renderer"], "test renderer");
    EXPECT_EQ(meta["height_format"], "exr-float");
    EXPECT_EQ(meta["exr"]["channel"], "Y");
    EXPECT_EQ(meta["exr"]["pixel_type"], "float");
    EXPECT_EQ(meta["exr"]["compression"], "zip");
    EXPECT_EQ(meta["scale"]["offset"], 0.0); // EXR holds metres
    EXPECT_EQ(meta["scale"]["scale"], 1.0);
    EXPECT_EQ(meta["cells"], json({12, 8}));
    EXPECT_EQ(meta["x0"], 0.4);
    EXPECT_EQ(meta["dx"], 0.05);
    EXPECT_EQ(meta["dz"], 0.1);
    EXPECT_NE(meta["orientation"].get<std::string>().find("row 0"), std::string::npos);
    EXPECT_EQ(meta["count"], 3);
    EXPECT_EQ(meta["frames"][1]["disp"], "disp_0002.exr");
    EXPECT_EQ(meta["frames"][2]["file"], "height_00002.exr");
    EXPECT_EQ(meta["displacement"]["reference_level_m"], 0.5);
    EXPECT_EQ(meta["displacement"]["reference"], "still_water_level");
    EXPECT_EQ(meta["displacement"]["first_number"], 1);
    EXPECT_EQ(meta["displacement"]["pixel_type"], "float");
    EXPECT_EQ(meta["normals"]["pixel_type"], "float");
}

TEST(HeightSequence, Png16SequenceKeepsTheDomainScaleAndHalfMakesEveryExrHalf) {
    const swell::test::TempDir temp("swell_height_sequence_");
    HeightSequence png(temp.path(), {}, kPngScale, smallGrid(), {});
    png.write(0, fieldAt(0.0), 0.0, 0.0);
    EXPECT_TRUE(fs::exists(temp / "height_00000.png"));
    EXPECT_FALSE(fs::exists(temp / "normal_00000.exr"));
    EXPECT_FALSE(fs::exists(temp / "disp_0001.exr"));
    const json meta = png.sidecar(json::object(), "r");
    EXPECT_EQ(meta["height_format"], "png16");
    EXPECT_EQ(meta["scale"]["scale"], kPngScale.scale);
    EXPECT_FALSE(meta.contains("exr"));
    EXPECT_FALSE(meta.contains("normals"));
    EXPECT_FALSE(meta.contains("displacement"));
    const HeightField back = readHeightPng(temp / "height_00000.png", png.scale());
    EXPECT_NEAR(back.at(3, 2), fieldAt(0.0).at(3, 2), 0.5 * kPngScale.scale + 1e-12);

    HeightSequenceParams half;
    half.format = HeightFormat::ExrHalf;
    half.normals = half.displacement = true;
    HeightSequence seq(temp.path(), half, kPngScale, smallGrid(), {});
    seq.write(0, fieldAt(0.0), 0.0, 0.0);
    for (const char* name : {"height_00000.exr", "normal_00000.exr", "disp_0001.exr"}) {
        for (const std::string& type : readExr(temp / name).types)
            EXPECT_EQ(type, "half") << name;
    }
}

} // namespace swell::runtime
