// The provenance read back from an output's bytes (codec/provenance_reader.h), each container built
// here by hand as its writer lays it out: PNG iTXt, PDF strings (literal with escapes, UTF-16 hex
// with a character beyond the BMP), SVG entities, CSV and JSON Lines headers, a sweep's lines; and
// the refusals (no provenance, no command).
#include "codec/provenance_reader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace spinfold {
namespace {

using nlohmann::json;

// A provenance with text a writer must escape: quotes, parentheses, a backslash, é and 😀.
const json kRecord = {{"software", "spinfold"},
                      {"version", "0.3.0"},
                      {"commit", "abc"},
                      {"command", "spinfold simulate 'my (first) scene.json' --out a\\b.csv"},
                      {"scene", {{"description", "é 😀 <&>"}, {"surface", {{"kind", "sphere"}}}}}};

std::string file_with(const std::string& name, const std::string& bytes) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("spinfold_reader_" + std::to_string(getpid()) + "_" + name))
          .string();
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

void expect_the_record(const RecordedRun& run, const std::string& format) {
  EXPECT_EQ(run.format, format);
  EXPECT_EQ(run.version, "0.3.0");
  EXPECT_EQ(run.commit, "abc");
  EXPECT_EQ(run.command, kRecord["command"]);
  EXPECT_EQ(run.scene, kRecord["scene"]);
}

std::string chunk(const std::string& type, const std::string& data) {
  std::string c;
  for (int shift : {24, 16, 8, 0}) c += static_cast<char>((data.size() >> shift) & 0xFF);
  return c + type + data + std::string(4, '\0');  // the CRC is not read
}

TEST(ProvenanceReader, ReadsAPngsSourceTextAsITXt) {
  const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", std::string(13, '\0')) +
                          chunk("tEXt", std::string("Software\0spinfold", 17)) +
                          chunk("iTXt", std::string("Source\0\0\0\0\0", 11) + kRecord.dump()) +
                          chunk("IEND", "");
  expect_the_record(recorded_run(file_with("a.png", png)), "png");
}

TEST(ProvenanceReader, ReadsAPdfsSubjectLiteralOrUtf16Hex) {
  std::string literal;  // ( ) \ escaped, é as an octal escape of its UTF-8 bytes
  for (const char c : kRecord.dump()) {
    if (c == '(' || c == ')' || c == '\\') literal += '\\';
    if (static_cast<unsigned char>(c) >= 0x80) {
      char octal[8];
      std::snprintf(octal, sizeof octal, "\\%03o", static_cast<unsigned char>(c));
      literal += octal;
    } else {
      literal += c;
    }
  }
  expect_the_record(recorded_run(file_with("a.pdf", "%PDF-1.7\n1 0 obj\n<< /Title (t)\n   /Subject (" +
                                                        literal + ")\n>>\nendobj\n")),
                    "pdf");
  // UTF-16BE with its byte-order mark, 😀 as a surrogate pair
  std::string hex = "FEFF";
  const std::string text = kRecord.dump();
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const int extra = c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : c >= 0xC0 ? 1 : 0;
    std::uint32_t cp = extra ? c & (0x3F >> extra) : c;
    for (int k = 1; k <= extra; ++k) cp = cp << 6 | (static_cast<unsigned char>(text[i + k]) & 0x3F);
    i += 1 + extra;
    char unit[16];
    if (cp >= 0x10000)
      std::snprintf(unit, sizeof unit, "%04X%04X", 0xD800 + ((cp - 0x10000) >> 10),
                    0xDC00 + ((cp - 0x10000) & 0x3FF));
    else
      std::snprintf(unit, sizeof unit, "%04X", cp);
    hex += unit;
  }
  expect_the_record(recorded_run(file_with("b.pdf", "%PDF-1.7\n<< /Subject <" + hex + "> >>\n")), "pdf");
}

TEST(ProvenanceReader, ReadsAnSvgsMetadataUnescaped) {
  std::string escaped;
  for (const char c : kRecord.dump())
    escaped += c == '&'   ? "&amp;"
               : c == '<' ? "&lt;"
               : c == '>' ? "&gt;"
               : c == '"' ? "&quot;"
                          : std::string(1, c);
  expect_the_record(
      recorded_run(file_with("a.svg", "<?xml version=\"1.0\"?>\n<svg>\n<title>t</title>\n<metadata>" +
                                          escaped + "</metadata>\n</svg>\n")),
      "svg");
}

TEST(ProvenanceReader, ReadsTablesAndASweepsHeader) {
  expect_the_record(
      recorded_run(file_with("a.jsonl", json{{"provenance", kRecord}}.dump() + "\n{\"t\": 0}\n")), "jsonl");
  expect_the_record(recorded_run(file_with("a.csv", "t,r\n# spinfold simulate 0.3.0\n# provenance: " +
                                                        kRecord.dump() + "\n0,1\n")),
                    "csv");
  // a sweep: its command and its base scene as given
  json base = {{"scene_hash", "0"}, {"scene", kRecord["scene"]}};
  json sweep = {{"version", "0.3.0"}, {"commit", "abc"}, {"command", kRecord["command"]}, {"base", base}};
  expect_the_record(recorded_run(file_with("s.jsonl", json{{"sweep", sweep}}.dump() + "\n")), "jsonl");
  const RecordedRun csv = recorded_run(file_with(
      "s.csv", "index,t\n# spinfold sweep 0.3.0\n# command: " + kRecord["command"].get<std::string>() +
                   "\n# runs: 2\n# base: " + base.dump() + "\n0,1\n"));
  EXPECT_EQ(csv.command, kRecord["command"]);
  EXPECT_EQ(csv.scene, kRecord["scene"]);
}

TEST(ProvenanceReader, SaysWhyAFileCannotBeRerun) {
  const auto message = [](const std::string& path) {
    try {
      recorded_run(path);
    } catch (const ProvenanceError& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  const std::string plain = file_with("plain.csv", "a,b\n1,2\n");
  EXPECT_EQ(message(plain),
            "'" + plain + "' carries no spinfold provenance (a csv file without its record of the run)");
  json api = kRecord;  // the HTTP API's: no command, no scene
  api.erase("command");
  api.erase("scene");
  const std::string served = file_with("served.jsonl", json{{"provenance", api}}.dump() + "\n");
  EXPECT_NE(message(served).find("no command: made by the HTTP API"), std::string::npos) << message(served);
  json old = kRecord;  // before 0.3.0: a command, no scene
  old.erase("scene");
  const std::string before = file_with("old.jsonl", json{{"provenance", old}}.dump() + "\n");
  EXPECT_NE(message(before).find("no scene: made by a version before 0.3.0"), std::string::npos);
  EXPECT_NE(message("/nonexistent/x.png").find("cannot read '/nonexistent/x.png'"), std::string::npos);
}

}  // namespace
}  // namespace spinfold
