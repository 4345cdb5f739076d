#include "cli/commands/gl_option.h"

#include <memory>
#include <stdexcept>

#include "cli/commands/command.h"
#include "render/renderer.h"

namespace spinfold::cli {

// --gl auto|egl|osmesa (default: SPINFOLD_GL, else auto); CLI11 refuses other values (exit 2).
void add_gl_option(CLI::App* command, std::string& choice) {
  command
      ->add_option("--gl", choice,
                   "GL backend: auto (an EGL GPU device, else EGL surfaceless, else OSMesa) | egl | osmesa "
                   "(default: SPINFOLD_GL, else auto)")
      ->check(CLI::IsMember({"auto", "egl", "osmesa"}));
}

// The process's backend from --gl, else SPINFOLD_GL (a bad value is bad input, exit 2).
void apply_gl_choice(const std::string& choice) {
  if (!choice.empty()) {
    render::set_gl_backend(*render::parse_gl_backend(choice));
    return;
  }
  try {
    render::set_gl_backend(render::gl_backend_setting());
  } catch (const std::invalid_argument& e) {
    throw BadInput{e.what()};
  }
}

// For --version: the backends built in and the context SPINFOLD_GL (else auto) gives here.
std::string gl_version_lines() {
  std::string lines = "GL backends built in: " + render::compiled_gl_backends() + "\n";
  try {
    const std::unique_ptr<render::GlContext> context = render::make_gl_context();
    lines += "GL in use: " + context->name() + " (" + context->renderer() + ")";
  } catch (const std::exception& e) {
    lines += std::string("GL in use: none (") + e.what() + ")";
  }
  return lines;
}

}  // namespace spinfold::cli
