// The far-wall pressure records of Buchner (2002) and Marrone et al. (2011) (buchner2002.h):
// the stored rows are the source's, in order, and say what docs/validation.md, Far-wall
// pressure, reads.
#include <algorithm>
#include <cstddef>

#include <gtest/gtest.h>

#include "swell/bake/validation/buchner2002.h"

using namespace swell::bake;
using namespace swell::bake::validation;

TEST(Buchner2002, StoresEverySourceRowInTimeOrder) {
    const auto rows = buchnerP1Records();
    ASSERT_EQ(rows.size(), 525u);
    // The source file's first and last rows, columns reordered to (t, exp, 40, 80, 320).
    EXPECT_DOUBLE_EQ(rows.front().t, 2.00471);
    EXPECT_DOUBLE_EQ(rows.front().experiment, -0.05335);
    EXPECT_DOUBLE_EQ(rows.front().deltaSph40, 0.00625);
    EXPECT_DOUBLE_EQ(rows.front().deltaSph80, 0.00373);
    EXPECT_DOUBLE_EQ(rows.front().deltaSph320, 0.00282);
    EXPECT_DOUBLE_EQ(rows.back().t, 7.31516);
    EXPECT_DOUBLE_EQ(rows.back().deltaSph320, 0.3537);
    for (std::size_t i = 1; i < rows.size(); ++i)
        EXPECT_LT(rows[i - 1].t, rows[i].t) << "row " << i;
}

TEST(Buchner2002, TheRunUpsCollapseComesLaterInDeltaSphThanInTheExperiment) {
    // The largest value of each column after the impact's plateau (t sqrt(g/H) in [5, 7]).
    const auto rows = buchnerP1Records();
    const auto peak = [&](double FarWallPressureSample::*column) {
        const FarWallPressureSample* best = nullptr;
        for (const FarWallPressureSample& r : rows)
            if (r.t >= 5.0 && r.t <= 7.0 && (!best || r.*column > best->*column))
                best = &r;
        return best;
    };
    EXPECT_DOUBLE_EQ(peak(&FarWallPressureSample::experiment)->t, 5.83288);
    EXPECT_DOUBLE_EQ(peak(&FarWallPressureSample::experiment)->experiment, 0.87672);
    EXPECT_DOUBLE_EQ(peak(&FarWallPressureSample::deltaSph40)->t, 6.31337);
    EXPECT_DOUBLE_EQ(peak(&FarWallPressureSample::deltaSph80)->t, 6.37461);
    EXPECT_DOUBLE_EQ(peak(&FarWallPressureSample::deltaSph320)->t, 6.42328);
    EXPECT_DOUBLE_EQ(peak(&FarWallPressureSample::deltaSph320)->deltaSph320, 0.90047);
}

TEST(Buchner2002, SensorP1SitsLowOnTheFarWall) {
    EXPECT_DOUBLE_EQ(kBuchnerP1TopOverH * 0.6, 0.16); // m at the experiment's H = 0.6 m
    EXPECT_DOUBLE_EQ(kBuchnerP1HeightOverH * 0.6, 0.09);
    EXPECT_GT(kBuchnerP1TopOverH - kBuchnerP1HeightOverH, 0.0);
}
