#include "swell/runtime/replay/slice_sampler.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

namespace swell::runtime {
namespace {

ReplayParams params(double F, FramePolicy policy = FramePolicy::Clamp, int K = 32) {
    ReplayParams p;
    p.fluctuation = F;
    p.policy = policy;
    p.slices = K;
    p.seed = 11;
    return p;
}

} // namespace

TEST(ReplayParams, JsonRoundTripAndKeyedErrors) {
    ReplayParams p;
    p.cellsX = 97;
    p.policy = FramePolicy::Clamp;
    p.noise.filter = NoiseFilter::HighPass;
    p.seed = 1234567890123ULL;
    const nlohmann::json j = toJson(p);
    EXPECT_EQ(j["policy"], "clamp");
    EXPECT_EQ(j["noise"]["filter"], "high");
    const ReplayParams q = replayParamsFromJson(j);
    EXPECT_EQ(toJson(q), j);
    EXPECT_EQ(replayParamsFromJson(nlohmann::json::object()).slices, 256); // paper defaults
    auto message = [](const nlohmann::json& bad) {
        try {
            replayParamsFromJson(bad);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message({{"slicez", 3}}).find("slicez"), std::string::npos);
    EXPECT_NE(message({{"fluctuation", 2.0}}).find("eq. (6)"), std::string::npos);
    EXPECT_NE(message({{"noise", {{"filter", "band"}}}}).find("noise.filter"), std::string::npos);
    EXPECT_NE(message({{"noise", {{"beta", "x"}}}}).find("noise.beta"), std::string::npos);
    EXPECT_NE(message({{"policy", "bounce"}}).find("policy"), std::string::npos);
}

TEST(SliceSampler, APerTimeUnitFromThePaper) {
    cache::Header h;
    h.dt = 0.001;
    h.frameInterval = 1;
    EXPECT_DOUBLE_EQ(framesPerTimeUnit(h, ReplayParams{}), 4.0 / 0.001); // A = 4/dt steps
    h.frameInterval = 10;
    EXPECT_DOUBLE_EQ(framesPerTimeUnit(h, ReplayParams{}), 400.0);
    h.dt = 0.0;
    EXPECT_THROW(framesPerTimeUnit(h, ReplayParams{}), std::invalid_argument);
}

TEST(SliceSampler, WithoutNoiseEverySliceShowsTheNearestFrame) {
    const SliceSampler s(params(0.0), 100, 4.0);
    EXPECT_EQ(s.noise(), nullptr); // F = 0 builds no noise
    EXPECT_EQ(s.sliceCount(), 63); // K real + K - 1 inserted
    for (int j = 0; j < s.sliceCount(); ++j) {
        EXPECT_EQ(s.frame(0.125, j), 1u); // 0.5 rounds up
        EXPECT_EQ(s.frame(0.124, j), 0u); // 0.496
        EXPECT_EQ(s.frame(2.6, j), 10u);  // 10.4
    }
}

TEST(SliceSampler, OutOfRangeFramesClampOrLoop) {
    const SliceSampler clamp(params(0.0, FramePolicy::Clamp), 100, 100.0);
    const SliceSampler loop(params(0.0, FramePolicy::Loop), 100, 100.0);
    EXPECT_EQ(clamp.frame(1.5, 0), 99u);
    EXPECT_EQ(loop.frame(1.5, 0), 50u);
    EXPECT_EQ(clamp.frame(-0.2, 3), 0u);
    EXPECT_EQ(loop.frame(-0.2, 3), 80u);
    EXPECT_EQ(loop.frame(-1.0, 3), 0u);
    EXPECT_EQ(loop.frame(0.99, 3), 99u);
}

TEST(SliceSampler, Eq5WithLinearNoiseInTimeAndHalfSlices) {
    const SliceSampler s(params(1.0), 100000, 50.0);
    ASSERT_NE(s.noise(), nullptr);
    const FbmNoise& N = *s.noise();
    const double tau = 3.25; // between noise samples 3 and 4
    for (int k = 0; k < 32; ++k) {
        const double nk = 0.75 * N.at(3, k) + 0.25 * N.at(4, k);
        const auto expected = static_cast<std::uint32_t>(std::floor((tau + nk) * 50.0 + 0.5));
        EXPECT_EQ(s.frame(tau, 2 * k), expected) << "slice " << k;
        EXPECT_NEAR(s.noiseAt(tau, 2 * k), nk, 1e-15);
        if (k + 1 < 32) {
            const double nk1 = 0.75 * N.at(3, k + 1) + 0.25 * N.at(4, k + 1);
            EXPECT_NEAR(s.noiseAt(tau, 2 * k + 1), 0.5 * (nk + nk1), 1e-15); // N at k + 1/2
        }
    }
    // At a noise sample the noise is that sample; the time axis is periodic with period T.
    EXPECT_DOUBLE_EQ(s.noiseAt(5.0, 6), N.at(5, 3));
    EXPECT_DOUBLE_EQ(s.noiseAt(5.0 + 16.0, 6), N.at(5, 3));
    EXPECT_DOUBLE_EQ(s.noiseAt(-1.0, 6), N.at(15, 3));
    EXPECT_DOUBLE_EQ(s.noiseAt(15.5, 0), 0.5 * N.at(15, 0) + 0.5 * N.at(0, 0));
}

TEST(SliceSampler, Eq6BoundsTheFrameOffset) {
    // F |N| <= 1: no slice is further than F A (+ rounding) from the noiseless frame.
    const double F = 0.3, A = 400.0;
    const SliceSampler s(params(F, FramePolicy::Clamp, 256), 1000000, A);
    bool someOffset = false;
    for (double tau = 100.0; tau < 116.0; tau += 0.37) {
        for (int j = 0; j < s.sliceCount(); ++j) {
            const double offset = static_cast<double>(s.frame(tau, j)) - tau * A;
            EXPECT_LE(std::abs(offset), F * A + 0.5 + 1e-9);
            someOffset = someOffset || std::abs(offset) > 10.0;
        }
    }
    EXPECT_TRUE(someOffset); // the noise does move the slices
}

TEST(SliceSampler, FluctuationAboveOneBreaksEq6) {
    try {
        SliceSampler(params(1.5), 100, 4.0);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("eq. (6)"), std::string::npos) << e.what();
    }
    EXPECT_THROW(SliceSampler(params(-0.1), 100, 4.0), std::invalid_argument);
    EXPECT_THROW(SliceSampler(params(0.3), 0, 4.0), std::invalid_argument);
    EXPECT_THROW(SliceSampler(params(0.3), 10, 0.0), std::invalid_argument);
    const SliceSampler ok(params(0.3), 10, 4.0);
    EXPECT_THROW(ok.frame(std::nan(""), 0), std::invalid_argument);
    EXPECT_THROW(ok.frame(1e12, 0), std::invalid_argument);
}

TEST(SliceSampler, FramesUsedIsTheUnionOverTaus) {
    const SliceSampler s(params(0.4, FramePolicy::Loop, 64), 500, 400.0);
    const std::vector<double> taus = {0.0, 0.1, 0.2, 0.9, 1.3};
    std::set<std::uint32_t> expected;
    for (double t : taus) {
        for (std::uint32_t f : s.frames(t))
            expected.insert(f);
    }
    const std::vector<std::uint32_t> used = s.framesUsed(taus);
    EXPECT_EQ(std::vector<std::uint32_t>(expected.begin(), expected.end()), used);
    EXPECT_LT(used.size(), 500u); // not every frame
}

TEST(SliceSampler, SeedChangesTheFrames) {
    ReplayParams a = params(0.3, FramePolicy::Clamp, 256);
    ReplayParams b = a;
    b.seed = a.seed + 1;
    const SliceSampler sa(a, 100000, 400.0), sb(b, 100000, 400.0);
    int differ = 0;
    const auto fa = sa.frames(50.3), fb = sb.frames(50.3);
    for (std::size_t j = 0; j < fa.size(); ++j)
        differ += fa[j] != fb[j];
    EXPECT_GT(differ, static_cast<int>(fa.size()) / 2);
}

} // namespace swell::runtime
