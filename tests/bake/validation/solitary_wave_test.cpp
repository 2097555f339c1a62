#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "swell/bake/error.h"
#include "swell/bake/validation/solitary_wave.h"

using namespace swell::bake;
using namespace swell::bake::validation;

namespace {

PistonParams goring() { // scenes/solitary_wave.json: H = 0.04 m in h = 0.2 m
    PistonParams p;
    p.kind = PistonKind::Solitary;
    p.height = 0.04;
    p.depth = 0.2;
    p.gravity = 9.81;
    return p;
}

/// Boussinesq's record of a crest A passing x at time tc, over a still level `still`.
double record(double A, double tc, double still, double t) {
    const SolitaryWaveShape w = solitaryWaveShape(A, 0.2, 9.81);
    const double s = 1.0 / std::cosh(w.wavenumber * w.celerity * (t - tc));
    return still + A * s * s;
}

struct Synthetic {
    std::vector<double> gauges{2.0, 3.0, 4.0, 5.0, 6.0};
    std::vector<double> times;
    std::vector<std::vector<double>> eta;
};

/// Crests of height H (1 - loss g) at gauge g, travelling at `celerity` from the paddle's
/// theoretical launch (x = c t - 4 / k), over a still level 2 mm below the nominal one.
Synthetic synthetic(double celerity, double loss) {
    const PistonParams p = goring();
    const double lead = 4.0 / solitaryWaveShape(p.height, p.depth, p.gravity).wavenumber;
    Synthetic s;
    for (int k = 0; k <= 6000; ++k)
        s.times.push_back(k * 1e-3);
    for (std::size_t g = 0; g < s.gauges.size(); ++g) {
        const double A = p.height * (1.0 - loss * static_cast<double>(g));
        const double tc = (s.gauges[g] + lead) / celerity;
        std::vector<double> e;
        for (double t : s.times)
            e.push_back(record(A, tc, -0.002, t));
        s.eta.push_back(std::move(e));
    }
    return s;
}

} // namespace

TEST(SolitaryWave, WindowsFollowTheoryAndRefuseGaugesOutsideTheTank) {
    const PistonParams p = goring();
    const std::vector<double> gauges{2.0, 6.0};
    const std::vector<CrestWindow> w = solitaryCrestWindows(p, 0.0, 7.5, gauges);
    ASSERT_EQ(w.size(), 2u);
    // scenes/solitary_wave.json: the crest reaches 6 m at 5.256 s, the reflection's front
    // returns there at 6.202 s; the front (eta = 1 % of H) reaches 2 m at 1.640 s.
    EXPECT_NEAR(w[1].until, 6.2020, 1e-3);
    EXPECT_NEAR(w[0].stillTo, 2.6496 - 1.0096, 1e-3);
    EXPECT_NEAR(w[0].stillFrom, 0.5 * w[0].stillTo, 1e-12);
    EXPECT_THROW(solitaryCrestWindows(p, 0.0, 7.5, std::vector<double>{8.0}),
                 std::invalid_argument);
    EXPECT_THROW(solitaryCrestWindows(p, 1.0, 7.5, std::vector<double>{0.5}),
                 std::invalid_argument);
}

TEST(SolitaryWave, AnalysisRecoversCelerityHeightLossAndWidthOfBoussinesqsWave) {
    const PistonParams p = goring();
    const Synthetic s = synthetic(1.50, 0.02);
    const std::vector<CrestWindow> w = solitaryCrestWindows(p, 0.0, 7.5, s.gauges);
    const SolitaryWaveCheck c = analyseSolitaryWave(p, s.gauges, s.times, s.eta, w);
    ASSERT_EQ(c.crests.size(), 5u);
    EXPECT_NEAR(c.celerity, 1.50, 1e-3);
    for (std::size_t g = 0; g < 5; ++g) {
        // The still window ends where theory's front reaches 1 % of H: its mean takes in up to
        // 0.25 % of H of the front's foot.
        EXPECT_NEAR(c.crests[g].stillLevel, -0.002, 1e-4) << g;
        EXPECT_NEAR(c.crests[g].amplitude / (0.04 * (1.0 - 0.02 * g)), 1.0, 2e-3) << g;
        EXPECT_NEAR(c.crests[g].widthError, 0.0, 5e-3) << g; // Boussinesq's own shape
    }
    EXPECT_NEAR(c.firstAmplitudeOverHeight, 1.0, 2e-3);
    EXPECT_NEAR(c.decayTotal, 0.08, 2e-3);
    // Against sqrt(g (h + mean A)) = sqrt(9.81 (0.2 + 0.0384)) = 1.5294 m/s.
    EXPECT_NEAR(c.celerityError, 1.50 / std::sqrt(9.81 * 0.2384) - 1.0, 1e-3);

    // A wave twice Boussinesq's width for its height reads about +100 % (+90 %: its broader
    // front has risen a little inside the still window, so its crest reads a little lower and
    // theory's width for that crest a little wider).
    Synthetic wide = s;
    for (std::size_t g = 0; g < wide.gauges.size(); ++g) {
        const double tc = (wide.gauges[g] + 4.0 / std::sqrt(3.75)) / 1.5;
        for (std::size_t k = 0; k < wide.times.size(); ++k)
            wide.eta[g][k] = record(0.04, tc, -0.002, tc + 0.5 * (wide.times[k] - tc));
    }
    const SolitaryWaveCheck cw = analyseSolitaryWave(p, wide.gauges, wide.times, wide.eta, w);
    EXPECT_GT(cw.meanWidthError, 0.8);
    EXPECT_LT(cw.meanWidthError, 1.02);
}

TEST(SolitaryWave, AnalysisRefusesRecordsWithoutACrest) {
    const PistonParams p = goring();
    Synthetic s = synthetic(1.50, 0.0);
    const std::vector<CrestWindow> w = solitaryCrestWindows(p, 0.0, 7.5, s.gauges);
    // A run that ends before the last crest has passed its gauge.
    Synthetic early = s;
    early.times.resize(5000);
    for (auto& e : early.eta)
        e.resize(5000);
    EXPECT_THROW(analyseSolitaryWave(p, early.gauges, early.times, early.eta, w),
                 std::invalid_argument);
    // A dry sample, a record of the wrong length, one gauge.
    Synthetic dry = s;
    dry.eta[2][100] = std::nan("");
    EXPECT_THROW(analyseSolitaryWave(p, dry.gauges, dry.times, dry.eta, w), std::invalid_argument);
    Synthetic shortRecord = s;
    shortRecord.eta[1].pop_back();
    EXPECT_THROW(analyseSolitaryWave(p, shortRecord.gauges, shortRecord.times, shortRecord.eta, w),
                 std::invalid_argument);
    const std::vector<double> one{2.0};
    const std::vector<std::vector<double>> oneRecord{s.eta[0]};
    EXPECT_THROW(analyseSolitaryWave(p, one, s.times, oneRecord, std::span(w).first(1)),
                 std::invalid_argument);
    // Still water: no crest rises.
    Synthetic flat = s;
    for (auto& e : flat.eta)
        std::fill(e.begin(), e.end(), -0.002);
    EXPECT_THROW(analyseSolitaryWave(p, flat.gauges, flat.times, flat.eta, w),
                 std::invalid_argument);
}
