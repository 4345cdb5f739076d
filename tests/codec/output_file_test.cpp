// Every write checked (codec/output_file.h): a full device (/dev/full), a path that cannot be opened
// and a file written whole.
#include "codec/output_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/error_of.h"

namespace spinfold {
namespace {

std::string message_of(const auto& write) {
  return test::error_of<WriteError>(write);
}

TEST(OutputFile, AFullDeviceFailsAtTheWriteOrTheCloseNamingThePathAndTheReason) {
  // Buffered: the bytes reach the device at the close, which reports it.
  const std::string at_close = message_of([] {
    OutputFile file("/dev/full");
    file.write("a line\n");
    file.close();
  });
  EXPECT_EQ(at_close, "cannot write '/dev/full': No space left on device");
  // Line by line: the first line's write reports it.
  const std::string at_line = message_of([] {
    OutputFile file("/dev/full", OutputFile::Buffering::line);
    file.write("a line\n");
  });
  EXPECT_EQ(at_line, "cannot write '/dev/full': No space left on device");
  EXPECT_EQ(message_of([] { write_whole_file("/dev/full", "bytes"); }),
            "cannot write '/dev/full': No space left on device");
  EXPECT_EQ(message_of([] {
              OutputFile file("/dev/full");
              file.write("x");
              file.flush();
            }),
            "cannot write '/dev/full': No space left on device");
}

TEST(OutputFile, APathThatCannotBeOpenedIsNamed) {
  EXPECT_EQ(message_of([] { OutputFile file("/nonexistent/dir/x.csv"); }),
            "cannot write '/nonexistent/dir/x.csv': No such file or directory");
}

TEST(OutputFile, WritesEveryByteAndClosesOnce) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("spinfold_output_file_" + std::to_string(::getpid()));
  {
    OutputFile file(path.string());
    for (int i = 0; i < 1000; ++i) file.write(std::to_string(i) + "\n");
    file.close();
    file.close();  // a second close does nothing
  }
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string expected;
  for (int i = 0; i < 1000; ++i) expected += std::to_string(i) + "\n";
  EXPECT_EQ(text.str(), expected);
  std::filesystem::remove(path);
  EXPECT_THROW(
      {
        OutputFile file(path.string());
        file.close();
        file.write("after the close");
      },
      WriteError);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace spinfold
