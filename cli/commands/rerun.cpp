// `spinfold rerun FILE [--out NEW] [--crossings NEW] [--trajectories DIR]`: runs again the command an
// output records (codec/provenance_reader.h), from any folder, with the scene it records instead of
// the file or preset it named, and writes the output anew where asked. The same build gives the
// same bytes (the command recorded in the new output is the old one); another build is said.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands/command.h"
#include "codec/provenance.h"
#include "codec/provenance_reader.h"
#include "codec/scene_source.h"

namespace spinfold::cli {
namespace {

struct RerunOptions {
  std::string file;
  std::optional<std::string> out, crossings, trajectories;
};

// What a recorded command wrote to, and the re-run's new place for each.
struct Output {
  std::string_view option;
  const std::optional<std::string>* replacement;
};

// The recorded command's words with each output's value replaced by the re-run's: every output the
// command wrote must be given anew (a re-run never writes over an output), and none it did not.
std::vector<std::string> rewritten(const std::vector<std::string>& words, const RerunOptions& opt) {
  const Output outputs[] = {
      {"--out", &opt.out}, {"--crossings", &opt.crossings}, {"--trajectories", &opt.trajectories}};
  std::vector<std::string> result(words.begin(), words.begin() + 2);
  std::vector<std::string_view> seen;
  for (std::size_t i = 2; i < words.size(); ++i) {
    const std::string& word = words[i];
    const Output* output = nullptr;
    for (const Output& o : outputs)
      if (word == o.option || word.starts_with(std::string(o.option) + "=")) output = &o;
    if (!output) {
      result.push_back(word);
      continue;
    }
    const bool joined = word.size() > output->option.size();
    const std::string recorded = joined                 ? word.substr(output->option.size() + 1)
                                 : i + 1 < words.size() ? words[i + 1]
                                                        : "";
    if (!joined) ++i;
    seen.push_back(output->option);
    if (*output->replacement) {
      result.emplace_back(output->option);
      result.push_back(**output->replacement);
    } else {
      const std::string what = output->option == "--trajectories" ? " DIR" : " FILE";
      throw BadInput{"rerun: the recorded command wrote " + std::string(output->option) + " " + recorded +
                     "; give rerun " + std::string(output->option) + what +
                     " for the new one (a re-run never writes over the old)"};
    }
  }
  for (const Output& o : outputs)
    if (*o.replacement && std::ranges::find(seen, o.option) == seen.end())
      throw BadInput{"rerun: " + std::string(o.option) + ": the recorded command wrote no " +
                     std::string(o.option)};
  return result;
}

int rerun(const RerunOptions& opt) {
  RecordedRun recorded;
  try {
    recorded = recorded_run(opt.file);
  } catch (const ProvenanceError& e) {
    throw BadInput{std::string("rerun: ") + e.what()};
  }
  std::vector<std::string> words;
  try {
    words = command_words(recorded.command);
  } catch (const std::invalid_argument& e) {
    throw BadInput{"rerun: '" + opt.file + "' records a command that does not read (" + e.what() + ")"};
  }
  if (words.size() < 2)
    throw BadInput{"rerun: '" + opt.file + "' records no subcommand: " + recorded.command};
  if (words[1] == "rerun" || words[1] == "serve")
    throw BadInput{"rerun: '" + opt.file + "' was made by `spinfold " + words[1] + "`, which is not re-run"};
  if (std::ranges::find(words, "#") != words.end())
    throw BadInput{"rerun: '" + opt.file + "' is one run of a sweep (" + recorded.command +
                   "): re-run the sweep's own output, or simulate its scene"};
  std::error_code ec;
  for (const auto* given : {&opt.out, &opt.crossings})
    if (*given && std::filesystem::equivalent(**given, opt.file, ec))
      throw BadInput{"rerun: --out: '" + **given + "' is the file re-run (a re-run never writes over it)"};
  const std::vector<std::string> argv_words = rewritten(words, opt);
  if (recorded.version != build_version() || recorded.commit != build_commit())
    std::cerr << "spinfold rerun: recorded by spinfold " << recorded.version << " (commit " << recorded.commit
              << "); this is " << version_line() << ": the bytes may differ\n";

  // The recorded scene in place of the named one, the recorded line in the new provenance.
  const RecordedScene scene(recorded.scene.dump());
  recorded_command() = recorded.command;
  std::vector<std::string> storage = argv_words;
  std::vector<char*> argv;
  for (std::string& w : storage) argv.push_back(w.data());
  argv.push_back(nullptr);
  const int code = run_command_line(static_cast<int>(storage.size()), argv.data());
  recorded_command().reset();
  return code;
}

}  // namespace

Command register_rerun(CLI::App& app) {
  auto options = std::make_shared<RerunOptions>();
  CLI::App* cmd = app.add_subcommand(
      "rerun", "Run again the command an output records, with the scene it records, from any folder");
  cmd->add_option("file", options->file,
                  "An output of spinfold (CSV, JSON Lines, npz, PNG, SVG, PDF, summary.md)")
      ->required();
  cmd->add_option("--out", options->out,
                  "Where the new output goes (needed where the recorded command wrote --out)");
  cmd->add_option("--crossings", options->crossings,
                  "Where simulate's crossings go (needed where it wrote them)");
  cmd->add_option("--trajectories", options->trajectories,
                  "Where a sweep's trajectories go (needed where it wrote them)");
  return {cmd, [options](int, char**) { return rerun(*options); }};
}

}  // namespace spinfold::cli
