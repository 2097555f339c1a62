#pragma once
// A test suite with one headless GL context (swell::runtime::EglContext) for all its tests:
// `class MySuite : public swell::test::GlSuite {};` then TEST_F(MySuite, ...).

#include "swell/runtime/gl/egl_context.h"

#include <gtest/gtest.h>
#include <memory>

namespace swell::test {

class GlSuite : public ::testing::Test {
protected:
    static void SetUpTestSuite() { s_context = std::make_unique<runtime::EglContext>(); }
    static void TearDownTestSuite() { s_context.reset(); }
    static inline std::unique_ptr<runtime::EglContext> s_context;
};

} // namespace swell::test
