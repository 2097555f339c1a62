#pragma once
// Vertex + fragment shader programs for the renderer (the compute side is gl_objects.h).

#include "swell/runtime/gl/gl_objects.h"

#include <initializer_list>
#include <string_view>

namespace swell::runtime {

/// The GL shader stage of a shader file by its extension: .vert, .frag or .comp (GLenum).
/// Throws std::logic_error for any other name.
std::uint32_t shaderStageOf(std::string_view name);
/// Compiles one shader of the stage its name implies and deletes it again; throws RuntimeError
/// with the driver's log, naming the shader (used to check every embedded shader).
/// Compiles one shader of the stage its file name says (.vert, .frag, .comp); returns the GL
/// shader name (the caller deletes it). Throws RuntimeError with the compiler's log.
GlName compileShader(std::string_view name, std::string_view source);
/// Links `shaders` into a program and deletes them; throws RuntimeError "what: <log>".
GlProgram linkProgram(std::initializer_list<GlName> shaders, std::string_view what);

void checkShaderCompiles(std::string_view name, std::string_view source);
/// Compiles and links the embedded shaders `vertexName` and `fragmentName`. Throws
/// RuntimeError naming the shader with the driver's log.
GlProgram makeGraphicsProgram(std::string_view vertexName, std::string_view fragmentName);

} // namespace swell::runtime
