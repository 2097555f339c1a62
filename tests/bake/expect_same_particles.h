#pragma once
// Test helper: two particle sets are the same bit for bit (each array reported on its own).
#include <gtest/gtest.h>

#include "swell/bake/particles.h"

inline void expectSameParticles(const swell::bake::Particles& a, const swell::bake::Particles& b) {
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    EXPECT_EQ(a.vx, b.vx);
    EXPECT_EQ(a.vy, b.vy);
    EXPECT_EQ(a.p, b.p);
    EXPECT_EQ(a.n, b.n);
    EXPECT_EQ(a.kind, b.kind);
}
