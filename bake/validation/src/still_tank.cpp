#include "swell/bake/validation/still_tank.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "swell/bake/error.h"
#include "swell/bake/solver_run.h"

namespace swell::bake::validation {

FastestParticle fastestWaterParticle(const MpsSolver& solver, const Box& tank, double l0) {
    const Particles& P = solver.particles();
    FastestParticle f;
    double best = -1.0;
    double top = -INFINITY;
    for (std::size_t i = 0; i < P.size(); ++i) {
        if (P.kind[i] != ParticleKind::Water)
            continue;
        top = std::max(top, P.y[i]);
        const double s2 = P.vx[i] * P.vx[i] + P.vy[i] * P.vy[i];
        if (s2 > best) {
            best = s2;
            f.index = i;
        }
    }
    const std::size_t i = f.index;
    f.time = solver.time();
    f.x = P.x[i];
    f.y = P.y[i];
    f.u = P.vx[i];
    f.v = P.vy[i];
    f.freeSurface = solver.surfaceFlags()[i] == 1;
    f.depthOverL0 = (top - P.y[i]) / l0;
    f.wallDistanceOverL0 = std::min(P.x[i] - tank.x0, tank.x1 - P.x[i]) / l0;
    return f;
}

StillTankReport runStillTank(const Scene& scene, double settle, long steps,
                             const StillTankStep& onStep) {
    if (!scene.geometry.tank)
        throw SceneError("geometry.tank", "the still-tank check needs a tank");
    if (scene.geometry.water.empty())
        throw SceneError("geometry.water", "the still-tank check needs water");
    const Box tank = *scene.geometry.tank;
    const double l0 = scene.geometry.particleSpacing;
    const double H = scene.geometry.water.front().height();
    const double waveSpeed = std::sqrt(scene.physics.gravity * H);
    MpsSolver solver = makeSolver(scene);
    const Particles& P = solver.particles();
    std::vector<std::size_t> gauge;
    for (std::size_t i = 0; i < P.size(); ++i) {
        if (P.kind[i] == ParticleKind::Wall &&
            std::abs(P.y[i] - (tank.y0 - 0.5 * l0)) < 0.25 * l0 &&
            P.x[i] > tank.x0 + 0.25 * tank.width() && P.x[i] < tank.x1 - 0.25 * tank.width()) {
            gauge.push_back(i);
        }
    }
    StillTankReport r;
    r.particles = P.size();
    r.water = P.count(ParticleKind::Water);
    r.gaugeParticles = gauge.size();
    r.rhoGH = scene.physics.density * scene.physics.gravity * H;
    double pSum = 0.0, speedSum = 0.0, maxExcursion2 = 0.0, maxDrift = 0.0;
    StepTotals totals;
    long pCount = 0, speedCount = 0;
    std::vector<double> settledX, settledY, windowX, windowY;
    double windowStart = -1.0;
    const auto afterStep = [&](const StepStats& s) {
        if (onStep)
            onStep(solver, s);
        if (solver.time() < settle)
            return;
        double p = 0.0;
        for (std::size_t i : gauge)
            p += P.p[i];
        pSum += gauge.empty() ? 0.0 : p / static_cast<double>(gauge.size());
        ++pCount;
        r.maxSpeedBeforeShift = std::max(r.maxSpeedBeforeShift, s.maxSpeed);
        if (settledX.empty()) {
            settledX = P.x;
            settledY = P.y;
        }
        if (windowStart < 0.0) {
            windowStart = solver.time();
            windowX = P.x;
            windowY = P.y;
        } else if (solver.time() >= windowStart + kDriftWindow - 1e-9) {
            const double span = solver.time() - windowStart;
            for (std::size_t i = 0; i < P.size(); ++i) {
                if (P.kind[i] == ParticleKind::Water) {
                    maxDrift = std::max(
                        maxDrift, std::hypot(P.x[i] - windowX[i], P.y[i] - windowY[i]) / span);
                }
            }
            windowStart = solver.time();
            windowX = P.x;
            windowY = P.y;
        }
        double stepMax = 0.0;
        for (std::size_t i = 0; i < P.size(); ++i) {
            if (P.kind[i] != ParticleKind::Water)
                continue;
            const double speed = std::hypot(P.vx[i], P.vy[i]);
            speedSum += speed;
            stepMax = std::max(stepMax, speed);
            ++speedCount;
            const double dx = P.x[i] - settledX[i], dy = P.y[i] - settledY[i];
            maxExcursion2 = std::max(maxExcursion2, dx * dx + dy * dy);
        }
        if (stepMax > r.maxSpeed) {
            r.maxSpeed = stepMax;
            r.fastest = fastestWaterParticle(solver, tank, l0);
        }
    };
    r.outcome = runSteps(
        solver, totals, [&](const MpsSolver&) { return totals.steps >= steps; }, afterStep);
    for (std::size_t i = 0; i < P.size(); ++i) {
        if (P.kind[i] == ParticleKind::Water && !tank.contains(P.x[i], P.y[i]))
            ++r.escaped;
    }
    r.time = solver.time();
    r.bottomPressureMean = pCount ? pSum / static_cast<double>(pCount) : 0.0;
    r.bottomPressureRatio = r.bottomPressureMean / r.rhoGH;
    r.maxSpeedOverSqrtGH = r.maxSpeed / waveSpeed;
    r.maxSpeedBeforeShiftOverSqrtGH = r.maxSpeedBeforeShift / waveSpeed;
    r.meanSpeedOverSqrtGH =
        speedCount ? speedSum / static_cast<double>(speedCount) / waveSpeed : 0.0;
    r.maxDriftSpeedOverSqrtGH = maxDrift / waveSpeed;
    r.maxExcursionOverL0 = std::sqrt(maxExcursion2) / l0;
    r.steps = totals.steps;
    r.ppeIterationsMean = totals.ppeIterationsMean();
    r.solverSeconds = totals.seconds;
    return r;
}

} // namespace swell::bake::validation
