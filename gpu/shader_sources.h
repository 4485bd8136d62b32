#pragma once
// The GLSL sources of gpu/shaders/, embedded at build time (gpu/embed_shaders.cmake).

namespace tyndall {

/// The text of gpu/shaders/<name> (e.g. "beam_estimator.glsl"); throws Error for an unknown name.
const char* shaderSource(const char* name);

}  // namespace tyndall
