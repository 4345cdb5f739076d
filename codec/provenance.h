// Where an output came from: the build (version, commit), the scene (a hash of its canonical JSON),
// the integrator with its parameters, and the command or request that made it. Every output carries
// it: JSON Lines as a header record, CSV as comment lines, PNG as text chunks, recordings as
// container metadata, the API as a header and a member. Nothing in it depends on the clock or the
// host, so the same scene and command give the same bytes.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/scene.h"

namespace spinfold {

// From the build (cmake/build_info.cmake): the project's version, which follows CHANGELOG.md, and
// the commit, "<12 hex digits>", "<…>-dirty" for uncommitted changes, or "unknown".
std::string_view build_version();
std::string_view build_commit();
// "0.3.0 (commit 1a2b3c4d5e6f)": what --version and the Software text of a PNG say.
std::string version_line();

// FNV-1a, 64 bits, as 16 hex digits: an identity for texts (scenes, sweep definitions), not a
// defence against anyone who crafts collisions.
std::string fnv1a64_hex(std::string_view text);

// The hash of the scene's canonical JSON (scene_to_json, keys sorted, shortest numbers): two
// scenes that read the same have the same hash, whatever their files' spacing or key order.
std::string scene_hash(const Scene& scene);

// {"software": "spinfold", "version", "commit", "scene_hash", "integrator": {"name", "runs", "dt",
// "tolerance"}, "command", "scene"}: `runs` is what auto resolved to; `command` the command line or
// the request ("POST /api/v1/sessions"), omitted when empty; where there is a command, `scene` is
// the scene itself as run (scene_to_json, canonical), so the output re-runs without its scene file
// (`spinfold rerun`, codec/provenance_reader.h).
nlohmann::ordered_json provenance_json(const Scene& scene, std::string_view command);

// The same as `key=value; …` on one line (an HTTP header; no command).
std::string provenance_header(const Scene& scene);

// A picture's text chunks (PNG tEXt; render/png_encoder.h): "Software" = "spinfold <version_line>",
// "Source" = the provenance JSON with the frame's time [time] and view added.
std::vector<std::pair<std::string, std::string>> picture_texts(const Scene& scene, std::string_view command,
                                                               double t, std::string_view view);

// argv as one shell-readable line (arguments with spaces or quotes in single quotes; a line break
// in an argument becomes a space).
std::string command_line(int argc, const char* const* argv);

// The arguments of such a line, as a POSIX shell splits it (words apart at blanks; '…' quotes,
// backslash escapes outside quotes): command_words(command_line(argc, argv)) is argv. A quote left
// open is std::invalid_argument.
std::vector<std::string> command_words(std::string_view line);

}  // namespace spinfold
