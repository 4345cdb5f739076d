// The figures' external checks (scripts/setup.sh installs them): xmllint for SVG, pdfinfo and
// pdftotext for PDF. A test whose tool is missing is skipped, saying which package brings it.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace spinfold::figure_test {

inline bool have_tool(const std::string& name) {
  return std::system(("command -v " + name + " >/dev/null 2>&1").c_str()) == 0;
}

// The bytes in a temporary file named for this process (ctest runs cases in parallel processes).
inline std::string temporary_file(const std::vector<std::uint8_t>& bytes, const std::string& extension) {
  static int count = 0;
  const std::string path =
      (std::filesystem::temp_directory_path() /
       ("spinfold_figure_" + std::to_string(getpid()) + "_" + std::to_string(++count) + extension))
          .string();
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return path;
}

struct ToolResult {
  int exit_code = -1;
  std::string out;  // stdout and stderr
};

inline ToolResult run_tool(const std::string& command) {
  ToolResult r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  char buffer[4096];
  while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) r.out.append(buffer, n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// A field of pdfinfo's output ("Pages", "Title", "Page size"), its value trimmed; "" when absent.
inline std::string pdfinfo_field(const std::string& out, const std::string& field) {
  const std::size_t at = out.find("\n" + field + ":") != std::string::npos ? out.find("\n" + field + ":") + 1
                         : out.starts_with(field + ":")                    ? 0
                                                                           : std::string::npos;
  if (at == std::string::npos) return "";
  std::size_t begin = at + field.size() + 1;
  const std::size_t end = out.find('\n', begin);
  while (begin < end && out[begin] == ' ') ++begin;
  return out.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

}  // namespace spinfold::figure_test
