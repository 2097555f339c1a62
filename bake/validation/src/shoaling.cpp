#include "swell/bake/validation/shoaling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>

#include "swell/bake/error.h"
#include "swell/bake/piston_motion.h"
#include "swell/bake/probes.h"
#include "swell/bake/validation/solitary_wave.h"
#include "swell/bake/validation/validation.h"

namespace swell::bake::validation {
namespace {

/// A scene's H / h0 and slope may differ from the experiment's by this fraction.
constexpr double kSetupTolerance = 0.01;

/// The crest of samples (t, y) with t in [lo, hi]: the parabola top around the highest sample
/// (kShoalingCrestHalfWindow either side). Throws std::invalid_argument (naming `what`) where
/// no sample lies in [lo, hi].
std::pair<double, double> crestIn(std::span<const double> t, std::span<const double> y, double lo,
                                  double hi, const std::string& what) {
    std::size_t peak = t.size();
    for (std::size_t k = 0; k < t.size(); ++k) {
        if (t[k] >= lo && t[k] <= hi && (peak == t.size() || y[k] > y[peak]))
            peak = k;
    }
    if (peak == t.size())
        throw std::invalid_argument(
            fmt::format("{}: no sample between {:.4g} and {:.4g} sqrt(h0/g)", what, lo, hi));
    // The samples within the half-window, and at least one on each side (a sparse record).
    std::size_t a = peak > 0 ? peak - 1 : 0, b = std::min(peak + 1, t.size() - 1);
    while (a > 0 && t[a - 1] >= t[peak] - kShoalingCrestHalfWindow)
        --a;
    while (b + 1 < t.size() && t[b + 1] <= t[peak] + kShoalingCrestHalfWindow)
        ++b;
    return parabolaTop(t, y, a, b, peak);
}

/// The record's times and elevations as two arrays.
void split(std::span<const ShoalingSample> r, std::vector<double>& t, std::vector<double>& eta) {
    t.clear();
    eta.clear();
    for (const ShoalingSample& s : r) {
        t.push_back(s.t);
        eta.push_back(s.eta);
    }
}

/// The run's eta at time `at` (linear between its samples T, clamped to its ends).
double valueAt(std::span<const double> T, std::span<const double> eta, double at) {
    const auto next = std::lower_bound(T.begin(), T.end(), at);
    const std::size_t j = static_cast<std::size_t>(next - T.begin());
    const std::size_t j0 = j == 0 ? 0 : j - 1, j1 = std::min(j, T.size() - 1);
    const double f = T[j1] > T[j0] ? (at - T[j0]) / (T[j1] - T[j0]) : 0.0;
    return eta[j0] + f * (eta[j1] - eta[j0]);
}

/// The run in the experiment's units: time / tau, and each gauge's elevation above its still
/// level (its mean over the still window) / h0.
struct ScaledRun {
    std::vector<double> T;
    std::vector<std::vector<double>> eta;
    std::vector<double> stillLevels; ///< each gauge's still level (m)
};

/// Refuses a gauge whose samples do not match the times, or one with no sample in the still
/// window.
ScaledRun scaleRun(std::span<const ShoalingGauge> records, double depth, double tau,
                   std::span<const double> times,
                   const std::vector<std::vector<double>>& elevations, double stillFrom,
                   double stillTo) {
    ScaledRun run;
    std::vector<double>& T = run.T;
    T.resize(times.size());
    for (std::size_t k = 0; k < times.size(); ++k)
        T[k] = times[k] / tau;
    std::vector<std::vector<double>>& eta = run.eta;
    eta.resize(records.size());
    run.stillLevels.resize(records.size());
    for (std::size_t g = 0; g < records.size(); ++g) {
        if (elevations[g].size() != times.size())
            throw std::invalid_argument(
                fmt::format("analyseShoaling: gauge {}: {} samples for {} times", records[g].name,
                            elevations[g].size(), times.size()));
        double still = 0.0;
        std::size_t n = 0;
        for (std::size_t k = 0; k < times.size(); ++k) {
            if (times[k] >= stillFrom && times[k] <= stillTo && std::isfinite(elevations[g][k])) {
                still += elevations[g][k];
                ++n;
            }
        }
        if (n == 0)
            throw std::invalid_argument(fmt::format(
                "analyseShoaling: gauge {} has no sample in its still window [{}, {}] s",
                records[g].name, stillFrom, stillTo));
        still /= static_cast<double>(n);
        run.stillLevels[g] = still;
        eta[g].resize(times.size());
        for (std::size_t k = 0; k < times.size(); ++k)
            eta[g][k] = (elevations[g][k] - still) / depth;
    }
    return run;
}

/// The clock: the run's g0 crest (after the still window) on the record's.
struct CrestClock {
    double offset = 0.0;       ///< record time - run time (sqrt(h0/g))
    double recordCrest0 = 0.0; ///< the record's g0 crest / h0
    double runT0 = 0.0;        ///< when the run's g0 crest passes (sqrt(h0/g))
    double runCrest0 = 0.0;    ///< the run's g0 crest / h0
};

/// Puts the run's g0 crest on the record's: the offset, and both crests.
CrestClock alignCrests(const ShoalingGauge& g0, const ScaledRun& run, double stillTo, double tau) {
    CrestClock c;
    std::vector<double> rt, reta;
    split(g0.record, rt, reta);
    const auto [recordT0, recordCrest0] =
        crestIn(rt, reta, rt.front(), rt.back(), fmt::format("record {}", g0.name));
    const auto [runT0, runCrest0] =
        crestIn(run.T, run.eta[0], stillTo / tau, run.T.empty() ? 0.0 : run.T.back(),
                fmt::format("run at {}", g0.name));
    c.offset = recordT0 - runT0;
    c.recordCrest0 = recordCrest0;
    c.runT0 = runT0;
    c.runCrest0 = runCrest0;
    return c;
}

/// The run at each record sample, weighted by half the time to its neighbours: the mean
/// absolute and signed errors and the ratio of the energies.
void addRecordErrors(std::span<const double> rt, std::span<const double> reta,
                     std::span<const double> T, std::span<const double> eta, double clockOffset,
                     ShoalingGaugeError& e) {
    double sumAbs = 0.0, sumSigned = 0.0, sumW = 0.0, sumRun2 = 0.0, sumRecord2 = 0.0;
    for (std::size_t k = 0; k < rt.size(); ++k) {
        const double w = 0.5 * (rt[std::min(k + 1, rt.size() - 1)] - rt[k > 0 ? k - 1 : 0]);
        const double run = valueAt(T, eta, rt[k] - clockOffset);
        sumAbs += w * std::abs(run - reta[k]);
        sumSigned += w * (run - reta[k]);
        sumW += w;
        sumRun2 += w * run * run;
        sumRecord2 += w * reta[k] * reta[k];
    }
    e.meanAbsError = sumAbs / sumW;
    e.meanSignedError = sumSigned / sumW;
    e.energyRatio = sumRun2 / sumRecord2;
}

/// Gauge g of the run against its record: the crests, amplification since g0, half-height
/// times and the errors over the record. Refuses a run that does not cover the record once
/// aligned on g0's crest, or a gauge dry within it.
ShoalingGaugeError compareGauge(std::span<const ShoalingGauge> records, std::size_t g,
                                const ScaledRun& run, std::span<const double> times,
                                const CrestClock& clock, double tau) {
    const ShoalingGauge& rec = records[g];
    const std::vector<double>& T = run.T;
    const std::vector<double>& eta = run.eta[g];
    std::vector<double> rt, reta;
    split(rec.record, rt, reta);
    ShoalingGaugeError e;
    e.name = rec.name;
    e.from = rt.front();
    e.until = rt.back();
    e.stillLevel = run.stillLevels[g];
    const double lo = e.from - clock.offset, hi = e.until - clock.offset;
    if (T.empty() || T.front() > lo || T.back() < hi)
        throw std::invalid_argument(fmt::format(
            "analyseShoaling: the run ({:.4g} s) does not cover gauge {}'s record, which "
            "needs it from {:.4g} to {:.4g} s once aligned on {}'s crest",
            times.empty() ? 0.0 : times.back(), rec.name, lo * tau, hi * tau, records[0].name));
    for (std::size_t k = 0; k < T.size(); ++k) {
        if (T[k] >= lo && T[k] <= hi && !std::isfinite(eta[k]))
            throw std::invalid_argument(fmt::format(
                "analyseShoaling: gauge {} is dry at t = {:.4g} s", rec.name, times[k]));
    }
    std::tie(e.crestTimeRecord, e.crestRecord) =
        crestIn(rt, reta, e.from, e.until, fmt::format("record {}", rec.name));
    if (g == 0) {
        e.crestTime = clock.runT0 + clock.offset;
        e.crest = clock.runCrest0;
    } else {
        const auto [tc, crest] = crestIn(T, eta, lo, hi, fmt::format("run at {}", rec.name));
        e.crestTime = tc + clock.offset;
        e.crest = crest;
    }
    e.amplification = e.crest / clock.runCrest0;
    e.amplificationRecord = e.crestRecord / clock.recordCrest0;
    std::tie(e.riseRecord, e.fallRecord) =
        halfHeightTimes(rt, reta, e.from, e.until, e.crestTimeRecord, e.crestRecord);
    std::tie(e.rise, e.fall) = halfHeightTimes(T, eta, lo, hi, e.crestTime - clock.offset, e.crest);
    addRecordErrors(rt, reta, T, eta, clock.offset, e);
    return e;
}

} // namespace

std::pair<double, double> halfHeightTimes(std::span<const double> t, std::span<const double> y,
                                          double lo, double hi, double crestTime, double crest) {
    const auto [front, back] = crossingsAround(t, y, lo, hi, crestTime, 0.5 * crest);
    return {crestTime - front, back - crestTime}; // NaN stays NaN
}

ShoalingCheck analyseShoaling(std::span<const ShoalingGauge> records, double depth, double gravity,
                              std::span<const double> times,
                              const std::vector<std::vector<double>>& elevations, double stillFrom,
                              double stillTo) {
    if (records.size() < 2 || elevations.size() != records.size())
        throw std::invalid_argument(
            fmt::format("analyseShoaling: {} records and {} gauges: need two or more, one each",
                        records.size(), elevations.size()));
    if (!(depth > 0.0 && gravity > 0.0))
        throw std::invalid_argument("analyseShoaling: depth and gravity must be positive");
    const double tau = std::sqrt(depth / gravity);
    const ScaledRun run = scaleRun(records, depth, tau, times, elevations, stillFrom, stillTo);

    ShoalingCheck out;
    const CrestClock clock = alignCrests(records[0], run, stillTo, tau);
    out.clockOffset = clock.offset;
    for (std::size_t g = 0; g < records.size(); ++g) {
        const ShoalingGaugeError e = compareGauge(records, g, run, times, clock, tau);
        if (g > 0) {
            const double crestError = e.crest / e.crestRecord - 1.0;
            const double ampError = e.amplification / e.amplificationRecord - 1.0;
            if (std::abs(crestError) > std::abs(out.crestErrorWorst))
                out.crestErrorWorst = crestError;
            if (std::abs(ampError) > std::abs(out.amplificationErrorWorst))
                out.amplificationErrorWorst = ampError;
            out.meanAbsErrorWorst = std::max(out.meanAbsErrorWorst, e.meanAbsError);
        }
        out.gauges.push_back(e);
    }
    out.incidentCrestError = out.gauges.front().crest / out.gauges.front().crestRecord - 1.0;
    const ShoalingGaugeError& first = out.gauges[1];
    const ShoalingGaugeError& last = out.gauges.back();
    out.travelTimeError =
        records.size() < 3
            ? 0.0
            : (last.crestTime - first.crestTime) / (last.crestTimeRecord - first.crestTimeRecord) -
                  1.0;
    return out;
}

std::string grilli1994RecordsCsv() {
    std::string out = "gauge,x_over_h0,t,eta\n";
    for (const ShoalingGauge& g : grilli1994Gauges()) {
        for (const ShoalingSample& s : g.record)
            out += fmt::format("{},{},{},{}\n", g.name, g.xOverDepth, s.t, s.eta);
    }
    return out;
}

ShoalingReport runShoaling(const Scene& scene) {
    if (!scene.piston || scene.piston->kind != PistonKind::Solitary)
        throw SceneError("piston.kind", "the shoaling check needs a solitary piston");
    const PistonParams& piston = *scene.piston;
    const Box tank = *scene.geometry.tank; // a piston needs a tank (loadScene)
    const double l0 = scene.geometry.particleSpacing;
    ShoalingReport r;
    r.depth = piston.depth;
    r.height = piston.height;
    if (std::abs(r.height / r.depth / kGrilliHeightOverDepth - 1.0) > kSetupTolerance)
        throw SceneError("piston.height",
                         fmt::format("H / h0 = {:.4g}: the experiment's wave is H / h0 = {:g}",
                                     r.height / r.depth, kGrilliHeightOverDepth));
    const std::vector<BedPoint>& bed = scene.geometry.bed;
    if (bed.size() < 2 || bed[0].y != tank.y0)
        throw SceneError("geometry.bed", "the shoaling check needs a bed profile whose first "
                                         "point, on the tank's bed, is the slope's toe");
    r.toe = bed[0].x;
    r.slope = (bed[1].y - bed[0].y) / (bed[1].x - bed[0].x);
    if (std::abs(r.slope / kGrilliSlope - 1.0) > kSetupTolerance)
        throw SceneError("geometry.bed",
                         fmt::format("the first segment's slope is 1:{:.4g}: the experiment's "
                                     "beach is 1:{:g}",
                                     1.0 / r.slope, 1.0 / kGrilliSlope));
    const std::span<const ShoalingGauge> records = grilli1994Gauges();
    std::string expected;
    for (const ShoalingGauge& g : records)
        expected +=
            fmt::format("{}{:.6g}", expected.empty() ? "" : ", ", r.toe + g.xOverDepth * r.depth);
    r.gauges = scene.output.gauges;
    bool match = r.gauges.size() == records.size();
    for (std::size_t g = 0; match && g < records.size(); ++g)
        match = std::abs(r.gauges[g] - (r.toe + records[g].xOverDepth * r.depth)) <= 0.5 * l0;
    if (!match)
        throw SceneError("output.gauges",
                         fmt::format("must be the experiment's gauges g0, g1, g3, g5, g7, g9 at "
                                     "the toe + (-5, 20.96, 22.55, 23.68, 24.68, 25.91) h0: "
                                     "[{}] m (within l0 / 2)",
                                     expected));
    if (bed[1].x < r.gauges.back())
        throw SceneError("geometry.bed",
                         fmt::format("the slope's first segment must reach past the last gauge "
                                     "at {:.6g} m",
                                     r.gauges.back()));
    // The still window: g0's, before its front (solitaryCrestWindows); the run must last from
    // theory's crest at g0 to the end of g9's record, plus a second.
    double crestAtG0 = 0.0;
    try {
        const CrestWindow w = solitaryCrestWindows(piston, tank.x0, tank.x1, {&r.gauges[0], 1})[0];
        r.stillFrom = w.stillFrom;
        r.stillTo = w.stillTo;
        const SolitaryWaveShape s = solitaryWaveShape(piston.height, piston.depth, piston.gravity);
        crestAtG0 = (r.gauges[0] - tank.x0 + kSolitaryHalfWidth / s.wavenumber) / s.celerity;
    } catch (const std::invalid_argument& e) {
        throw SceneError("output.gauges", e.what());
    }
    const double tau = std::sqrt(r.depth / piston.gravity);
    double recordCrest0 = 0.0, peak = -1.0;
    for (const ShoalingSample& s : records[0].record) {
        if (s.eta > peak) {
            peak = s.eta;
            recordCrest0 = s.t;
        }
    }
    const double needed = crestAtG0 + (records.back().record.back().t - recordCrest0) * tau + 1.0;
    if (scene.run.endTime < needed)
        throw SceneError("solver.end_time",
                         fmt::format("{} s is too short: the run must reach g9's last record, "
                                     "about {:.3g} s",
                                     scene.run.endTime, needed));
    static_cast<GaugeRecords&>(r) = recordGauges(scene, stillWaterLevel(scene), r.gauges);
    if (r.outcome != kStable)
        return r;
    try {
        r.check = analyseShoaling(records, r.depth, piston.gravity, r.times, r.elevations,
                                  r.stillFrom, r.stillTo);
        for (std::size_t g = 0; g < r.gauges.size(); ++g)
            r.check.gauges[g].x = r.gauges[g];
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(fmt::format("shoaling: {}", e.what()));
    }
    return r;
}

} // namespace swell::bake::validation
