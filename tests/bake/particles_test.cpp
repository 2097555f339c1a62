// Particles (particles.h): the structure of arrays stays in step.
#include <gtest/gtest.h>

#include "swell/bake/particles.h"

using namespace swell::bake;

TEST(Particles, AddKeepsEveryArrayInStepAndCountsKinds) {
    Particles p;
    EXPECT_TRUE(p.consistent());
    p.add(0.1, 0.2, ParticleKind::Water);
    p.add(0.3, 0.4, ParticleKind::Wall);
    EXPECT_EQ(p.size(), 2u);
    EXPECT_TRUE(p.consistent());
    EXPECT_EQ(p.count(ParticleKind::Water), 1u);
    EXPECT_EQ(p.count(ParticleKind::Dummy), 0u);
}

TEST(Particles, AnArrayOfAnotherLengthIsInconsistent) {
    Particles p;
    p.add(0.1, 0.2, ParticleKind::Water);
    for (auto member :
         {&Particles::y, &Particles::vx, &Particles::vy, &Particles::p, &Particles::n}) {
        Particles q = p;
        (q.*member).pop_back();
        EXPECT_FALSE(q.consistent());
    }
    Particles q = p;
    q.kind.push_back(ParticleKind::Dummy);
    EXPECT_FALSE(q.consistent());
}
