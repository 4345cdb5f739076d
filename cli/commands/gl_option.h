// --gl of render, record and serve, and the GL lines of --version.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace spinfold::cli {

// --gl auto|egl|osmesa (default: SPINFOLD_GL, else auto); CLI11 refuses other values (exit 2).
void add_gl_option(CLI::App* command, std::string& choice);

// The process's backend from --gl, else SPINFOLD_GL (a bad value is BadInput, exit 2).
void apply_gl_choice(const std::string& choice);

// For --version: the backends built in and the context SPINFOLD_GL (else auto) gives here.
std::string gl_version_lines();

}  // namespace spinfold::cli
