// GLSL sources of shaders/, embedded at build time (cmake/embed_files.cmake).
#pragma once

#include <string_view>

namespace spinfold::render {

// The source of shaders/<file_name>; throws std::out_of_range for an unknown name.
std::string_view shader_source(std::string_view file_name);

}  // namespace spinfold::render
