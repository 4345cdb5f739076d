// The .npy arrays of an .npz (codec/npz_writer.h) as numpy.lib.format defines them; numpy.load reading
// the files is tests/python/test_csv_readers.py's.
#include "codec/npz_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace spinfold {
namespace {

using nlohmann::ordered_json;

std::string header_of(const std::vector<std::uint8_t>& npy) {
  const std::size_t length = npy[8] | (npy[9] << 8);
  return std::string(npy.begin() + 10, npy.begin() + 10 + static_cast<std::ptrdiff_t>(length));
}

TEST(NpzWriter, NumbersAreFloat64WithNullAsNaNAfterAHeaderPaddedTo64Bytes) {
  const std::vector<ordered_json> cells = {1.5, nullptr, -0.1};
  const std::vector<std::uint8_t> npy = npy_bytes(cells);
  EXPECT_EQ(std::string(npy.begin(), npy.begin() + 6), "\x93NUMPY");
  EXPECT_EQ(npy[6], 1);
  EXPECT_EQ(npy[7], 0);
  const std::string header = header_of(npy);
  EXPECT_EQ(header.rfind("{'descr': '<f8', 'fortran_order': False, 'shape': (3,), }", 0), 0u) << header;
  EXPECT_EQ(header.back(), '\n');
  const std::size_t data = 10 + header.size();
  EXPECT_EQ(data % 64, 0u);
  ASSERT_EQ(npy.size(), data + 3 * 8);
  double v[3];
  std::memcpy(v, npy.data() + data, sizeof v);
  EXPECT_EQ(v[0], 1.5);
  EXPECT_TRUE(std::isnan(v[1]));
  EXPECT_EQ(v[2], -0.1);  // the same double, bit for bit
}

// Whole numbers (a count, steps) are uint64, or int64 with a negative one, as Python's sweep gives
// them: one dtype per column across Python and the .npz (issue 51: float64 in the .npz); a null among
// them makes the column float64, as a missing value does in Python.
TEST(NpzWriter, WholeNumbersAreUint64OrInt64) {
  const std::vector<std::uint8_t> counts =
      npy_bytes({ordered_json(3u), ordered_json(0u), ordered_json(9007199254740993u)});
  EXPECT_EQ(header_of(counts).rfind("{'descr': '<u8'", 0), 0u) << header_of(counts);
  std::uint64_t u[3];
  std::memcpy(u, counts.data() + 10 + header_of(counts).size(), sizeof u);
  EXPECT_EQ(u[2], 9007199254740993u);  // past 2⁵³: exact, as no float64 is
  const std::vector<std::uint8_t> signs = npy_bytes({ordered_json(-2), ordered_json(5u)});
  EXPECT_EQ(header_of(signs).rfind("{'descr': '<i8'", 0), 0u) << header_of(signs);
  std::int64_t i[2];
  std::memcpy(i, signs.data() + 10 + header_of(signs).size(), sizeof i);
  EXPECT_EQ(i[0], -2);
  EXPECT_EQ(i[1], 5);
  EXPECT_EQ(header_of(npy_bytes({ordered_json(1u), nullptr})).rfind("{'descr': '<f8'", 0), 0u);
  EXPECT_EQ(header_of(npy_bytes({ordered_json(1u), ordered_json(1.5)})).rfind("{'descr': '<f8'", 0), 0u);
}

TEST(NpzWriter, TextIsFixedWidthUtf32) {
  const std::vector<std::uint8_t> npy = npy_bytes({"ok", "s = \u03BB", nullptr});
  const std::string header = header_of(npy);
  EXPECT_NE(header.find("'descr': '<U5'"), std::string::npos) << header;
  const std::size_t data = 10 + header.size();
  ASSERT_EQ(npy.size(), data + 3 * 5 * 4);
  std::uint32_t second[5];
  std::memcpy(second, npy.data() + data + 5 * 4, sizeof second);
  EXPECT_EQ(second[0], U's');
  EXPECT_EQ(second[4], 0x03BBu);  // λ, one code point from two UTF-8 bytes
  std::uint32_t third[5];
  std::memcpy(third, npy.data() + data + 10 * 4, sizeof third);
  EXPECT_EQ(third[0], 0u);  // null: empty
}

TEST(NpzWriter, AnUnwritablePathIsNamed) {
  try {
    write_npz("/nonexistent-dir/x.npz", {{"t", {0.0}}});
    FAIL() << "written";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.npz"), std::string::npos) << e.what();
  }
}

// No clock in the bytes: each entry's DOS time and date (local header bytes 10–13, central
// directory bytes 12–15) are 00:00 and 1980-01-01, so the same table is the same file at any hour.
TEST(NpzWriter, EntriesCarryNoClock) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("spinfold_npz_clock_" + std::to_string(getpid()) + ".npz"))
          .string();
  write_npz(path, {{"t", {0.0, 1.0}}, {"status", {"ok", "ok"}}});
  std::ifstream in(path, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::filesystem::remove(path);
  const auto u16 = [&](std::size_t at) {
    return static_cast<unsigned>(static_cast<unsigned char>(bytes[at])) |
           static_cast<unsigned>(static_cast<unsigned char>(bytes[at + 1])) << 8;
  };
  int local = 0, central = 0;
  for (std::size_t at = 0; at + 16 < bytes.size(); ++at) {
    if (bytes.compare(at, 4, "PK\x03\x04") == 0) {
      ++local;
      EXPECT_EQ(u16(at + 10), 0u);
      EXPECT_EQ(u16(at + 12), (1u << 5) | 1u);
    } else if (bytes.compare(at, 4, "PK\x01\x02") == 0) {
      ++central;
      EXPECT_EQ(u16(at + 12), 0u);
      EXPECT_EQ(u16(at + 14), (1u << 5) | 1u);
    }
  }
  EXPECT_EQ(local, 2);
  EXPECT_EQ(central, 2);
}

}  // namespace
}  // namespace spinfold
