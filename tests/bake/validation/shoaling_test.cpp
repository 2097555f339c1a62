#include <cmath>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "swell/bake/error.h"
#include "swell/bake/scene.h"
#include "swell/bake/validation/grilli1994.h"
#include "swell/bake/validation/shoaling.h"

using namespace swell::bake;
using namespace swell::bake::validation;

namespace {

constexpr double kG = 9.81;
constexpr double kH0 = 0.44;
const std::filesystem::path kScenes = SWELL_SCENES_DIR;

/// The record's eta / h0 at t, linear between its samples, 0 outside them.
double recordAt(std::span<const ShoalingSample> r, double t) {
    if (t < r.front().t || t > r.back().t)
        return 0.0;
    for (std::size_t k = 1; k < r.size(); ++k) {
        if (t <= r[k].t)
            return r[k - 1].eta +
                   (r[k].eta - r[k - 1].eta) * (t - r[k - 1].t) / (r[k].t - r[k - 1].t);
    }
    return r.back().eta;
}

/// Records of a run that is the experiment: every gauge's record `lag` sqrt(h0/g) late on the run's
/// clock, in metres over a still level `still` (m), sampled every 0.005 sqrt(h0/g) to T = 55.
/// `edit` may change a gauge's record (its index, the run's T, the record's value) first.
struct Records {
    std::vector<double> times;
    std::vector<std::vector<double>> elevations;
};
template <class Edit> Records syntheticRun(double lag, double still, Edit edit) {
    const double tau = std::sqrt(kH0 / kG);
    const auto gauges = grilli1994Gauges();
    Records r;
    r.elevations.resize(gauges.size());
    for (int k = 0; k * 0.005 <= 55.0; ++k) {
        const double T = k * 0.005;
        r.times.push_back(T * tau);
        for (std::size_t g = 0; g < gauges.size(); ++g)
            r.elevations[g].push_back(still +
                                      kH0 * edit(g, T, recordAt(gauges[g].record, T - lag)));
    }
    return r;
}

double tau() {
    return std::sqrt(kH0 / kG);
}

ShoalingCheck analyse(const Records& r) {
    // The still window: T in [1, 4], before the records start (g0's at 5 on its clock).
    return analyseShoaling(grilli1994Gauges(), kH0, kG, r.times, r.elevations, 1.0 * tau(),
                           4.0 * tau());
}

std::string sceneErrorKey(const Scene& s) {
    try {
        runShoaling(s);
    } catch (const SceneError& e) {
        return e.key();
    }
    return "<no SceneError>";
}

} // namespace

TEST(Grilli1994, TheRecordsAreTheDigitisedFigures) {
    const auto gauges = grilli1994Gauges();
    ASSERT_EQ(gauges.size(), 6u);
    const char* names[] = {"g0", "g1", "g3", "g5", "g7", "g9"};
    const double x[] = {-5.0, 20.96, 22.55, 23.68, 24.68, 25.91};
    const std::size_t rows[] = {123, 273, 268, 242, 200, 188}; // after the cuts (the data file)
    for (std::size_t g = 0; g < gauges.size(); ++g) {
        EXPECT_EQ(gauges[g].name, names[g]);
        EXPECT_EQ(gauges[g].xOverDepth, x[g]);
        EXPECT_EQ(gauges[g].record.size(), rows[g]) << names[g];
        for (std::size_t k = 1; k < gauges[g].record.size(); ++k)
            EXPECT_GT(gauges[g].record[k].t, gauges[g].record[k - 1].t) << names[g] << " " << k;
        for (const ShoalingSample& s : gauges[g].record) // no digitiser extrapolation kept
            EXPECT_TRUE(s.eta > -0.01 && s.eta < 0.35) << names[g] << " at " << s.t;
    }
    // The incident crest and the breaking one, as the figures show them.
    const auto top = [](std::span<const ShoalingSample> r) {
        ShoalingSample best = r.front();
        for (const ShoalingSample& s : r)
            best = s.eta > best.eta ? s : best;
        return best;
    };
    EXPECT_EQ(top(gauges[0].record).eta, 0.199163);
    EXPECT_EQ(top(gauges[0].record).t, 13.6392);
    EXPECT_EQ(top(gauges[5].record).eta, 0.34084);
    EXPECT_EQ(top(gauges[5].record).t, 44.2843);
    EXPECT_EQ(gauges[4].record.front().t, 41.3477); // g7 from 41.333 on
    const std::string csv = grilli1994RecordsCsv();
    EXPECT_EQ(csv.rfind("gauge,x_over_h0,t,eta\n", 0), 0u);
    EXPECT_NE(csv.find("g9,25.91,44.2843,0.34084\n"), std::string::npos);
}

TEST(Shoaling, TheExperimentAgainstItselfReadsNoError) {
    const Records r = syntheticRun(3.0, 0.002, [](std::size_t, double, double v) { return v; });
    const ShoalingCheck c = analyse(r);
    EXPECT_NEAR(c.clockOffset, -3.0, 0.02);
    ASSERT_EQ(c.gauges.size(), 6u);
    for (const ShoalingGaugeError& g : c.gauges) {
        EXPECT_NEAR(g.crest / g.crestRecord, 1.0, 0.005) << g.name;
        EXPECT_NEAR(g.crestTime, g.crestTimeRecord, 0.03) << g.name;
        EXPECT_NEAR(g.amplification, g.amplificationRecord, 0.01) << g.name;
        EXPECT_LT(g.meanAbsError, 0.002) << g.name;
        EXPECT_NEAR(g.stillLevel, 0.002, 1e-12) << g.name; // the run's level before the wave
        EXPECT_EQ(g.from, grilli1994Gauges()[&g - c.gauges.data()].record.front().t);
        EXPECT_NEAR(g.rise, g.riseRecord, 0.02) << g.name;
        EXPECT_NEAR(g.fall, g.fallRecord, 0.02) << g.name;
        EXPECT_NEAR(g.energyRatio, 1.0, 0.01) << g.name;
    }
    // The record's own shape, as the figures show it: g0 rises over about 2.1 sqrt(h0/g)
    // (Boussinesq's wave of H / h0 = 0.2 takes 2.08), g9 over a third of a unit.
    EXPECT_NEAR(c.gauges[0].riseRecord, 2.1, 0.1);
    EXPECT_NEAR(c.gauges[5].riseRecord, 0.36, 0.05);
    EXPECT_NEAR(c.incidentCrestError, 0.0, 0.005);
    EXPECT_NEAR(c.crestErrorWorst, 0.0, 0.005);
    EXPECT_NEAR(c.travelTimeError, 0.0, 0.01);
    EXPECT_LT(c.meanAbsErrorWorst, 0.002);
}

TEST(Shoaling, AHigherCrestALateWaveAndASmallIncidentWaveReadAsSuch) {
    // g5 (index 3) 10 % higher: its crest, amplification and signed error say so, and it is
    // the worst crest.
    {
        const Records r = syntheticRun(
            3.0, 0.0, [](std::size_t g, double, double v) { return g == 3 ? 1.1 * v : v; });
        const ShoalingCheck c = analyse(r);
        EXPECT_NEAR(c.gauges[3].crest / c.gauges[3].crestRecord, 1.1, 0.01);
        EXPECT_NEAR(c.crestErrorWorst, 0.1, 0.01);
        EXPECT_NEAR(c.amplificationErrorWorst, 0.1, 0.015);
        EXPECT_GT(c.gauges[3].meanSignedError, 0.005);
        EXPECT_NEAR(c.gauges[3].meanAbsError, c.gauges[3].meanSignedError, 1e-3);
        EXPECT_NEAR(c.gauges[2].meanAbsError, 0.0, 0.002);
    }
    // g9 (index 5) 0.5 sqrt(h0/g) late: its crest time and the climb from g1 to g9 say so.
    {
        const Records r = syntheticRun(3.0, 0.0, [](std::size_t, double, double v) { return v; });
        Records late = syntheticRun(3.0, 0.0, [](std::size_t, double, double v) { return v; });
        const auto& g9 = grilli1994Gauges()[5].record;
        for (std::size_t k = 0; k < late.times.size(); ++k)
            late.elevations[5][k] = kH0 * recordAt(g9, late.times[k] / tau() - 3.5);
        const ShoalingCheck c = analyse(late);
        EXPECT_NEAR(c.gauges[5].crestTime - c.gauges[5].crestTimeRecord, 0.5, 0.03);
        const double recordClimb = c.gauges[5].crestTimeRecord - c.gauges[1].crestTimeRecord;
        EXPECT_NEAR(c.travelTimeError, 0.5 / recordClimb, 0.01);
        EXPECT_GT(c.gauges[5].meanAbsError, 0.02);
        EXPECT_NEAR(analyse(r).travelTimeError, 0.0, 0.01);
    }
    // Every gauge 20 % lower: the incident crest reads -20 %, the amplification none.
    {
        const Records r =
            syntheticRun(3.0, 0.0, [](std::size_t, double, double v) { return 0.8 * v; });
        const ShoalingCheck c = analyse(r);
        EXPECT_NEAR(c.incidentCrestError, -0.2, 0.005);
        EXPECT_NEAR(c.crestErrorWorst, -0.2, 0.01);
        EXPECT_NEAR(c.amplificationErrorWorst, 0.0, 0.01);
    }
}

TEST(Shoaling, RecordsItCannotReadAreRefused) {
    const Records r = syntheticRun(3.0, 0.0, [](std::size_t, double, double v) { return v; });
    const auto gauges = grilli1994Gauges();
    // A run that ends before g9's record does once aligned.
    Records shortRun = r;
    const std::size_t keep = static_cast<std::size_t>(45.0 / 0.005);
    shortRun.times.resize(keep);
    for (auto& e : shortRun.elevations)
        e.resize(keep);
    EXPECT_THROW(analyse(shortRun), std::invalid_argument);
    // One gauge short of samples, or of a record.
    Records ragged = r;
    ragged.elevations[2].pop_back();
    EXPECT_THROW(analyse(ragged), std::invalid_argument);
    Records fewer = r;
    fewer.elevations.pop_back();
    EXPECT_THROW(analyse(fewer), std::invalid_argument);
    // No sample in the still window.
    EXPECT_THROW(analyseShoaling(gauges, kH0, kG, r.times, r.elevations, 100.0, 101.0),
                 std::invalid_argument);
    // A dry sample inside a compared span.
    Records dry = r;
    dry.elevations[4][static_cast<std::size_t>(46.0 / 0.005)] = std::nan(""); // in g7's span
    EXPECT_THROW(analyse(dry), std::invalid_argument);
}

TEST(Shoaling, ScenesThatAreNotTheExperimentNameTheirKey) {
    const Scene ok = loadScene(kScenes / "shoaling_small.json");
    EXPECT_EQ(ok.geometry.bed.size(), 2u);
    Scene s = ok;
    s.piston->height = 0.1;
    EXPECT_EQ(sceneErrorKey(s), "piston.height");
    s = ok;
    s.geometry.bed[1].y = 0.6;
    EXPECT_EQ(sceneErrorKey(s), "geometry.bed");
    s = ok;
    s.geometry.bed.clear();
    EXPECT_EQ(sceneErrorKey(s), "geometry.bed");
    s = ok;
    s.output.gauges[3] += 0.02; // more than l0 / 2 = 0.011 m off
    EXPECT_EQ(sceneErrorKey(s), "output.gauges");
    s = ok;
    s.output.gauges.pop_back();
    EXPECT_EQ(sceneErrorKey(s), "output.gauges");
    s = ok;
    s.run.endTime = 10.0;
    EXPECT_EQ(sceneErrorKey(s), "solver.end_time");
    s = ok;
    s.piston->kind = PistonKind::Sinusoidal;
    EXPECT_EQ(sceneErrorKey(s), "piston.kind");
}

TEST(Shoaling, HalfHeightTimesReadAPeaksSidesAndNothingBeyondTheSpan) {
    // A tent from 0 at t = 2 to 1 at t = 5 and back to 0 at t = 11, sampled every 0.5: half
    // height at t = 3.5 and t = 8.
    std::vector<double> t, y;
    for (int k = 0; k <= 26; ++k) {
        const double T = 0.5 * k;
        t.push_back(T);
        y.push_back(T <= 2.0    ? 0.0
                    : T <= 5.0  ? (T - 2.0) / 3.0
                    : T <= 11.0 ? (11.0 - T) / 6.0
                                : 0.0);
    }
    const auto [rise, fall] = halfHeightTimes(t, y, 0.0, 13.0, 5.0, 1.0);
    EXPECT_NEAR(rise, 1.5, 1e-12);
    EXPECT_NEAR(fall, 3.0, 1e-12);
    // A span that ends before the back falls to half, or starts after the front rose to it.
    EXPECT_TRUE(std::isnan(halfHeightTimes(t, y, 0.0, 7.5, 5.0, 1.0).second));
    EXPECT_NEAR(halfHeightTimes(t, y, 0.0, 7.5, 5.0, 1.0).first, 1.5, 1e-12);
    EXPECT_TRUE(std::isnan(halfHeightTimes(t, y, 4.0, 13.0, 5.0, 1.0).first));
}

TEST(Shoaling, ABroaderWaveReadsItsShapeAndItsEnergy) {
    // Every slope gauge's wave 1.3 times as long about its crest: each side reads 1.3 times the
    // record's and the energy through the gauge about 1.3 times it (the span cuts the stretched
    // wave's ends).
    const auto gauges = grilli1994Gauges();
    const double stretch = 1.3;
    std::vector<double> crestT;
    for (const ShoalingGauge& g : gauges) {
        ShoalingSample best = g.record.front();
        for (const ShoalingSample& s : g.record)
            best = s.eta > best.eta ? s : best;
        crestT.push_back(best.t);
    }
    const auto broad = [&](double scale) {
        return syntheticRun(3.0, 0.0, [&](std::size_t g, double T, double v) {
            if (g == 0)
                return v;
            const double c = crestT[g] + 3.0;
            return scale * recordAt(gauges[g].record, c + (T - c) / stretch - 3.0);
        });
    };
    const ShoalingCheck c = analyse(broad(1.0));
    for (std::size_t g = 1; g < gauges.size(); ++g) {
        const ShoalingGaugeError& e = c.gauges[g];
        EXPECT_NEAR(e.crest / e.crestRecord, 1.0, 0.01) << e.name;
        // Within 0.05 sqrt(h0/g): the crest's time moves by a few hundredths as the parabola
        // fits a broader top, which counts on g7's and g9's short fronts (0.4 sqrt(h0/g)).
        EXPECT_NEAR(e.rise, stretch * e.riseRecord, 0.05) << e.name;
        EXPECT_NEAR(e.fall, stretch * e.fallRecord, 0.05) << e.name;
        EXPECT_NEAR(e.energyRatio, stretch, 0.12) << e.name;
        EXPECT_GT(e.energyRatio, 1.1) << e.name;
    }
    // Lower by 1 / sqrt(1.3) as well: the same energy in a lower, broader wave reads about 1,
    // while the crest reads 12 % low.
    const ShoalingCheck same = analyse(broad(1.0 / std::sqrt(stretch)));
    for (std::size_t g = 1; g < gauges.size(); ++g) {
        const ShoalingGaugeError& e = same.gauges[g];
        EXPECT_NEAR(e.crest / e.crestRecord, 1.0 / std::sqrt(stretch), 0.01) << e.name;
        EXPECT_NEAR(e.energyRatio, 1.0, 0.1) << e.name;
    }
}
