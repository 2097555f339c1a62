#pragma once
// A GL test suite that holds the synthetic frame set most replay tests use:
// test::syntheticSet(260, 320, 21) (2.6 s of travelling waves with gaps, a dry region and an
// empty frame; A = 400 frames per time unit), made once per suite.

#include "gl_fixture.h"
#include "synthetic_frames.h"

#include <memory>

namespace swell::runtime::test {

class SyntheticGlSuite : public swell::test::GlSuite {
protected:
    static void SetUpTestSuite() {
        GlSuite::SetUpTestSuite();
        s_frames = std::make_unique<FrameSet>(syntheticSet(260, 320, 21));
    }
    static void TearDownTestSuite() {
        s_frames.reset();
        GlSuite::TearDownTestSuite();
    }
    static inline std::unique_ptr<FrameSet> s_frames;
};

} // namespace swell::runtime::test
