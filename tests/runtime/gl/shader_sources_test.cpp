#include "swell/runtime/error.h"
#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/gl/gl_objects.h"
#include "swell/runtime/gl/graphics_program.h"
#include "swell/shaders/shaders.h"

#include <gtest/gtest.h>

#include <string>

namespace swell::runtime {

TEST(ShaderSources, EveryEmbeddedShaderCompilesAndLinks) {
    EglContext context;
    ASSERT_GE(shaders::all().size(), 3u);
    for (const shaders::Source& s : shaders::all()) {
        SCOPED_TRACE(std::string(s.name));
        EXPECT_NE(s.text.find("#version 450 core"), std::string_view::npos);
        if (s.name.ends_with(".comp")) {
            EXPECT_NO_THROW({
                GlProgram p = makeComputeProgram(s.name, s.text);
                EXPECT_NE(p.get(), 0u);
            });
        } else { // vertex and fragment shaders of the renderer: compiled for their own stage
            EXPECT_NO_THROW(checkShaderCompiles(s.name, s.text));
        }
    }
}

TEST(ShaderSources, ABrokenShaderFailsWithItsNameAndTheLog) {
    EglContext context;
    try {
        makeComputeProgram("broken.comp", "#version 450 core\nlayout(local_size_x = 1) in;\n"
                                          "void main() { undefined_thing = 1; }\n");
        FAIL() << "a broken shader compiled";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("broken.comp"), std::string::npos) << e.what();
    }
}

TEST(ShaderSources, LookupByNameAndUnknownName) {
    EXPECT_NE(shaders::get("reconstruct.comp").find("eq. (7)"), std::string_view::npos);
    EXPECT_THROW(shaders::get("nope.comp"), std::logic_error);
}

} // namespace swell::runtime
