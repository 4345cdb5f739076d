#include "codec/output_file.h"

#include <cerrno>
#include <cstring>

namespace spinfold {

OutputFile::OutputFile(const std::string& path, Buffering buffering) : path_(path) {
  stdout_ = path.empty() || path == "-";
  if (stdout_) {
    path_ = "standard output";
    file_ = stdout;
  } else {
    file_ = std::fopen(path.c_str(), "wb");
    if (!file_) fail(errno);
  }
  if (buffering == Buffering::line) std::setvbuf(file_, nullptr, _IOLBF, 1 << 16);
}

OutputFile::~OutputFile() {
  if (file_ && !stdout_) std::fclose(file_);
}

void OutputFile::fail(int error) const {
  throw WriteError("cannot write '" + path_ + "': " + std::strerror(error != 0 ? error : EIO));
}

void OutputFile::write(std::string_view bytes) {
  if (!file_) throw WriteError("cannot write '" + path_ + "': it is closed");
  errno = 0;
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size() || std::ferror(file_)) fail(errno);
}

void OutputFile::flush() {
  if (!file_) throw WriteError("cannot write '" + path_ + "': it is closed");
  errno = 0;
  if (std::fflush(file_) != 0 || std::ferror(file_)) fail(errno);
}

void OutputFile::close() {
  if (!file_) return;
  std::FILE* file = file_;
  file_ = nullptr;
  errno = 0;
  const bool flushed = std::fflush(file) == 0 && !std::ferror(file);
  const int flush_error = errno;
  if (stdout_) {
    if (!flushed) fail(flush_error);
    return;
  }
  errno = 0;
  const bool closed = std::fclose(file) == 0;
  if (!flushed) fail(flush_error);
  if (!closed) fail(errno);
}

void write_whole_file(const std::string& path, std::string_view bytes) {
  OutputFile file(path);
  file.write(bytes);
  file.close();
}

}  // namespace spinfold
