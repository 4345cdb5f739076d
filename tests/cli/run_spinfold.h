// The spinfold binary run as a user runs it, for the CLI tests: its exit code, stdout and stderr.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace spinfold::cli_test {

struct Result {
  int exit_code;
  std::string out;
  std::string err;
};

// `args` go through the shell. One stderr file per process and call: ctest runs test cases in
// parallel processes.
inline Result run_spinfold(const std::string& args) {
  static int calls = 0;
  const std::string err_file =
      std::filesystem::temp_directory_path() /
      ("spinfold_cli_stderr_" + std::to_string(getpid()) + "_" + std::to_string(++calls));
  const std::string command = std::string(SPINFOLD_BINARY) + " " + args + " 2>" + err_file;
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int status = pclose(pipe);
  std::ifstream err_in(err_file);
  std::stringstream err;
  err << err_in.rdbuf();
  std::filesystem::remove(err_file);
  return {WEXITSTATUS(status), out, err.str()};
}

}  // namespace spinfold::cli_test
