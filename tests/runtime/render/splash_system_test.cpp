#include "swell/runtime/render/splash_system.h"

#include "synthetic_frames.h"

#include <gtest/gtest.h>

#include <cmath>

namespace swell::runtime {
namespace {

struct Fixture {
    FrameSet set;
    Grid grid;
    Fixture() {
        set = test::syntheticSet(12, 40, 9);
        ReplayParams p = test::sized(32, 16, 8, ReplayParams{});
        grid = makeGrid(set.header, p);
    }
    /// Every slice shows frame `f`.
    std::vector<std::uint32_t> allFrame(std::uint32_t f) const {
        return std::vector<std::uint32_t>(static_cast<std::size_t>(grid.sliceCount()), f);
    }
};

/// Where the documented formula puts artificial splash `p` of the real splash `real` (x, y, ...)
/// of a slice at `z` at time `t` (SplashSystem::sprites): ballistic from its start, age cycling
/// through the lifetime, fading with age.
SplashSprite expectedSprite(const ArtificialSplash& p, const float* real, double z, double t) {
    double life = t / p.lifetime + p.phase;
    life -= std::floor(life);
    const double age = life * p.lifetime;
    return {
        static_cast<float>(real[0] + p.offset[0] + p.velocity[0] * age),
        static_cast<float>(real[1] + p.offset[1] + p.velocity[1] * age - 0.5 * 9.81 * age * age),
        static_cast<float>(z + p.offset[2] + p.velocity[2] * age), static_cast<float>(1.0 - life)};
}

TEST(SplashSystem, CountsRealAndArtificialSplashesOfTheRealSlices) {
    const Fixture fx;
    SplashParams params;
    params.artificialPerReal = 4;
    const SplashSystem s(fx.set, fx.grid, params, 1);
    ASSERT_TRUE(s.active());
    // 8 real slices x 3 splash particles x (1 real + 4 artificial).
    EXPECT_EQ(s.sprites(fx.allFrame(2), 0.3).size(), 8u * 3u * 5u);
    params.sliceStride = 2;
    EXPECT_EQ(SplashSystem(fx.set, fx.grid, params, 1).sprites(fx.allFrame(2), 0.3).size(),
              4u * 3u * 5u);
    // Frame 5 of the synthetic set is empty: those slices show no splash.
    auto frames = fx.allFrame(2);
    for (std::size_t j = 0; j < frames.size(); j += 4)
        frames[j] = 5;
    EXPECT_EQ(s.sprites(frames, 0.3).size(), 4u * 3u * 5u);
    EXPECT_THROW((void)s.sprites(std::vector<std::uint32_t>(3, 0), 0.0), std::logic_error);
}

TEST(SplashSystem, RealSplashesSitAtTheirSliceAndFrame) {
    const Fixture fx;
    SplashParams params;
    params.artificialPerReal = 0;
    const SplashSystem s(fx.set, fx.grid, params, 1);
    auto frames = fx.allFrame(3);
    frames[2] = 7; // real slice k = 1 shows frame 7
    const auto sprites = s.sprites(frames, 0.0);
    ASSERT_EQ(sprites.size(), 8u * 3u);
    const cache::Frame& f7 = *fx.set.find(7);
    const cache::Frame& f3 = *fx.set.find(3);
    for (std::size_t i = 0; i < 3; ++i) {
        const SplashSprite& a = sprites[i];     // slice j = 0, frame 3
        const SplashSprite& b = sprites[3 + i]; // slice j = 2, frame 7
        EXPECT_EQ(a.x, f3.splash[4 * i]);
        EXPECT_EQ(a.y, f3.splash[4 * i + 1]);
        EXPECT_FLOAT_EQ(a.z, static_cast<float>(fx.grid.sliceZCells(0) * fx.grid.dz));
        EXPECT_EQ(b.x, f7.splash[4 * i]);
        EXPECT_FLOAT_EQ(b.z, static_cast<float>(fx.grid.sliceZCells(2) * fx.grid.dz));
        EXPECT_EQ(a.alpha, 1.0f);
    }
}

TEST(SplashSystem, ArtificialSplashesFollowSection5) {
    const Fixture fx;
    SplashParams params;
    params.artificialPerReal = 50;
    const SplashSystem s(fx.set, fx.grid, params, 42);
    const float real[4] = {1.0f, 0.6f, 1.5f, 2.0f}; // speed 2.5 m/s
    double meanVx = 0.0;
    for (int a = 0; a < params.artificialPerReal; ++a) {
        const ArtificialSplash p = s.artificial(real, 4, 1, a);
        const double r = std::sqrt(p.offset[0] * p.offset[0] + p.offset[1] * p.offset[1] +
                                   p.offset[2] * p.offset[2]);
        EXPECT_LE(r, params.spawnRadius + 1e-12); // random offset in a sphere
        EXPECT_GE(p.lifetime, params.minLifetime);
        EXPECT_LE(p.lifetime, params.maxLifetime);
        // Lifetime from the particle: 2 |v| / g = 0.51 s, times a factor in [0.5, 1].
        EXPECT_GE(p.lifetime, 0.5 * 2.0 * 2.5 / 9.81 - 1e-12);
        EXPECT_LE(p.lifetime, 2.0 * 2.5 / 9.81 + 1e-12);
        EXPECT_GE(p.phase, 0.0);
        EXPECT_LT(p.phase, 1.0);
        meanVx += p.velocity[0] / params.artificialPerReal;
    }
    // Velocity derived from the real one: on average the real velocity (scale 0.7..1.3, jitter
    // of mean 0), so the mean of 50 is near 1.5 m/s.
    EXPECT_NEAR(meanVx, 1.5, 0.35);
}

TEST(SplashSystem, SpritesMoveBallisticallyAndFadeOverTheirLife) {
    const Fixture fx;
    SplashParams params;
    params.artificialPerReal = 3;
    const SplashSystem s(fx.set, fx.grid, params, 7);
    const double t = 0.37;
    const auto sprites = s.sprites(fx.allFrame(4), t);
    const cache::Frame& f = *fx.set.find(4);
    const double z0 = fx.grid.sliceZCells(0) * fx.grid.dz;
    for (int a = 0; a < 3; ++a) {
        const SplashSprite e =
            expectedSprite(s.artificial(&f.splash[0], 0, 0, a), &f.splash[0], z0, t);
        const SplashSprite& sp = sprites[1 + static_cast<std::size_t>(a)];
        EXPECT_NEAR(sp.x, e.x, 1e-5);
        EXPECT_NEAR(sp.y, e.y, 1e-5);
        EXPECT_NEAR(sp.z, e.z, 1e-5);
        EXPECT_NEAR(sp.alpha, e.alpha, 1e-6);
        EXPECT_LT(sp.alpha, 1.0f); // artificial: fading
    }
}

TEST(SplashSystem, ManySplashesAreBuiltInParallelInTheOrderOfOneAtATime) {
    // 8 real slices x 3 particles x 1001 sprites: enough to be split over threads. Every sprite
    // is where the serial formula puts it: slice by slice, particle by particle.
    const Fixture fx;
    SplashParams params;
    params.artificialPerReal = 1000;
    const SplashSystem s(fx.set, fx.grid, params, 5);
    const double t = 0.8;
    auto frames = fx.allFrame(4);
    frames[6] = 2; // real slice k = 3 shows another frame
    const auto sprites = s.sprites(frames, t);
    ASSERT_EQ(sprites.size(), 8u * 3u * 1001u);
    std::size_t checked = 0;
    for (int k = 0; k < 8; ++k) {
        const int j = 2 * k;
        const cache::Frame& f = *fx.set.find(frames[static_cast<std::size_t>(j)]);
        const double z = fx.grid.sliceZCells(j) * fx.grid.dz;
        for (std::size_t i = 0; i < 3; ++i) {
            const SplashSprite* o = &sprites[(static_cast<std::size_t>(k) * 3 + i) * 1001];
            EXPECT_EQ(o[0].x, f.splash[4 * i]);
            EXPECT_EQ(o[0].z, static_cast<float>(z));
            for (int a = 0; a < 1000; a += 97) {
                const float* real = &f.splash[4 * i];
                const SplashSprite e = expectedSprite(s.artificial(real, j, i, a), real, z, t);
                const SplashSprite& sp = o[1 + a];
                EXPECT_EQ(sp.x, e.x);
                EXPECT_EQ(sp.y, e.y);
                EXPECT_EQ(sp.z, e.z);
                EXPECT_EQ(sp.alpha, e.alpha);
                ++checked;
            }
        }
    }
    EXPECT_EQ(checked, 8u * 3u * 11u);
}

TEST(SplashSystem, RandomNumbersDrawnOnceOrEveryFrameGiveTheSameSprites) {
    const Fixture fx;
    SplashParams once;
    once.artificialPerReal = 40;
    SplashParams everyFrame = once;
    everyFrame.drawTableBytes = 0;
    const SplashSystem a(fx.set, fx.grid, once, 3), b(fx.set, fx.grid, everyFrame, 3);
    auto frames = fx.allFrame(4);
    frames[2] = 9;
    for (double t : {0.0, 0.45, 2.7}) {
        const auto sa = a.sprites(frames, t), sb = b.sprites(frames, t);
        ASSERT_EQ(sa.size(), sb.size());
        for (std::size_t k = 0; k < sa.size(); ++k) {
            ASSERT_EQ(sa[k].x, sb[k].x) << k;
            ASSERT_EQ(sa[k].y, sb[k].y) << k;
            ASSERT_EQ(sa[k].z, sb[k].z) << k;
            ASSERT_EQ(sa[k].alpha, sb[k].alpha) << k;
        }
    }
}

TEST(SplashSystem, SameSeedSameSpritesOtherSeedOthers) {
    const Fixture fx;
    const SplashParams params;
    const SplashSystem a(fx.set, fx.grid, params, 11), b(fx.set, fx.grid, params, 11),
        c(fx.set, fx.grid, params, 12);
    const auto sa = a.sprites(fx.allFrame(6), 1.25);
    const auto sb = b.sprites(fx.allFrame(6), 1.25);
    const auto sc = c.sprites(fx.allFrame(6), 1.25);
    ASSERT_EQ(sa.size(), sb.size());
    ASSERT_EQ(sa.size(), sc.size());
    std::size_t same = 0, differ = 0;
    for (std::size_t i = 0; i < sa.size(); ++i) {
        same += sa[i].x == sb[i].x && sa[i].y == sb[i].y && sa[i].z == sb[i].z &&
                sa[i].alpha == sb[i].alpha;
        differ += sa[i].x != sc[i].x;
    }
    EXPECT_EQ(same, sa.size());
    // Real sprites (1 in 7) coincide; the artificial ones differ.
    EXPECT_GE(differ, sa.size() * 6 / 7 - 2);
}

TEST(SplashSystem, NoSplashNoPassAndBadParametersThrow) {
    Fixture fx;
    SplashParams off;
    off.enabled = false;
    EXPECT_FALSE(SplashSystem(fx.set, fx.grid, off, 1).active());
    EXPECT_TRUE(SplashSystem(fx.set, fx.grid, off, 1).sprites(fx.allFrame(1), 0.0).empty());
    for (cache::Frame& f : fx.set.frames)
        f.splash.clear();
    EXPECT_FALSE(SplashSystem(fx.set, fx.grid, SplashParams{}, 1).active());
    SplashParams bad;
    bad.artificialPerReal = -1;
    EXPECT_THROW(SplashSystem(fx.set, fx.grid, bad, 1), std::invalid_argument);
    bad = SplashParams{};
    bad.spriteRadius = 0.0;
    EXPECT_THROW(SplashSystem(fx.set, fx.grid, bad, 1), std::invalid_argument);
    bad = SplashParams{};
    bad.minLifetime = 2.0;
    EXPECT_THROW(SplashSystem(fx.set, fx.grid, bad, 1), std::invalid_argument);
}

} // namespace
} // namespace swell::runtime
