// A file a command writes, every write checked: each write, the flush and the close, so that a full
// disk or a closed pipe is an error naming the path and the system's reason instead of a short
// file and exit 0. Every writer of the CLI, the sweep and the work-precision folder writes through
// it (the recordings' and the .npz writers check their libraries' own calls).
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace spinfold {

// A write, flush or close that failed: "cannot write 'PATH': REASON" (strerror of errno).
struct WriteError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class OutputFile {
 public:
  enum class Buffering { full, line };
  // `path` "" or "-": standard output (closed by flushing it). WriteError when it cannot be opened.
  explicit OutputFile(const std::string& path, Buffering buffering = Buffering::full);
  ~OutputFile();  // closes without a check if close() was not called (an error is on its way)
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // WriteError at the first write the system refuses (with line buffering: at that line).
  void write(std::string_view bytes);
  // Hands what is buffered to the system now (a row a killed run keeps); WriteError on failure.
  void flush();
  // Flushes and closes, checking both; WriteError naming the path on failure.
  void close();
  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(int error) const;
  std::string path_;
  std::FILE* file_ = nullptr;
  bool stdout_ = false;
};

// The whole file at once (a PNG, a CSV): open, write, close, each checked.
void write_whole_file(const std::string& path, std::string_view bytes);

}  // namespace spinfold
