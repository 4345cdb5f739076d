#include "codec/provenance_reader.h"

#include <zip.h>

#include <cctype>
#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

namespace spinfold {
namespace {

using json = nlohmann::json;

std::string whole_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ProvenanceError("cannot read '" + path + "'");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

std::optional<json> parsed(std::string_view text) {
  json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return std::nullopt;
  return j;
}

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

// A PNG's tEXt or iTXt chunk with the keyword "Source" (render/png_encoder.cpp writes it).
std::optional<std::string> png_source(const std::string& bytes) {
  std::size_t at = 8;
  while (at + 12 <= bytes.size()) {
    const auto b = [&](std::size_t k) {
      return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[k]));
    };
    const std::uint32_t length = b(at) << 24 | b(at + 1) << 16 | b(at + 2) << 8 | b(at + 3);
    const std::string type = bytes.substr(at + 4, 4);
    if (at + 12 + static_cast<std::size_t>(length) > bytes.size()) break;
    const std::string data = bytes.substr(at + 8, length);
    const std::size_t nul = data.find('\0');
    if ((type == "tEXt" || type == "iTXt") && nul != std::string::npos && data.substr(0, nul) == "Source") {
      if (type == "tEXt") return data.substr(nul + 1);
      // iTXt: compression flag and method, language tag, NUL, translated keyword, NUL, text
      const std::size_t language_end = data.find('\0', nul + 3);
      const std::size_t translated_end =
          language_end == std::string::npos ? std::string::npos : data.find('\0', language_end + 1);
      if (translated_end != std::string::npos && data[nul + 1] == '\0')
        return data.substr(translated_end + 1);
    }
    if (type == "IEND") break;
    at += 12 + length;
  }
  return std::nullopt;
}

// The text between <metadata> and </metadata>, unescaped (render/figure_page.cpp escapes &, <, >, ").
std::optional<std::string> svg_metadata(const std::string& bytes) {
  const std::size_t open = bytes.find("<metadata>");
  const std::size_t close = open == std::string::npos ? open : bytes.find("</metadata>", open);
  if (close == std::string::npos) return std::nullopt;
  const std::string escaped = bytes.substr(open + 10, close - open - 10);
  std::string text;
  for (std::size_t i = 0; i < escaped.size(); ++i) {
    if (escaped[i] != '&') {
      text += escaped[i];
      continue;
    }
    const std::size_t semi = escaped.find(';', i);
    const std::string entity = escaped.substr(i, semi == std::string::npos ? 1 : semi - i + 1);
    if (entity == "&amp;")
      text += '&';
    else if (entity == "&lt;")
      text += '<';
    else if (entity == "&gt;")
      text += '>';
    else if (entity == "&quot;")
      text += '"';
    else if (entity == "&apos;")
      text += '\'';
    else
      return std::nullopt;
    i += entity.size() - 1;
  }
  return text;
}

// The PDF's /Subject string (cairo writes it in the document's Info dictionary): a literal string
// (…) with backslash escapes, or <FEFF…> hex in UTF-16BE where the text is not plain ASCII.
std::optional<std::string> pdf_subject(const std::string& bytes) {
  const std::size_t key = bytes.find("/Subject");
  if (key == std::string::npos) return std::nullopt;
  std::size_t at = bytes.find_first_not_of(" \r\n\t", key + 8);
  if (at == std::string::npos) return std::nullopt;
  std::string text;
  if (bytes[at] == '(') {
    int depth = 1;
    for (++at; at < bytes.size(); ++at) {
      const char c = bytes[at];
      if (c == '\\' && at + 1 < bytes.size()) {
        const char e = bytes[++at];
        if (e >= '0' && e <= '7') {
          int value = 0;
          for (int k = 0; k < 3 && at < bytes.size() && bytes[at] >= '0' && bytes[at] <= '7'; ++k, ++at)
            value = value * 8 + (bytes[at] - '0');
          --at;
          text += static_cast<char>(value);
        } else {
          text += e == 'n' ? '\n' : e == 'r' ? '\r' : e == 't' ? '\t' : e == 'b' ? '\b' : e == 'f' ? '\f' : e;
        }
      } else if (c == '(') {
        ++depth;
        text += c;
      } else if (c == ')') {
        if (--depth == 0) return text;
        text += c;
      } else {
        text += c;
      }
    }
    return std::nullopt;
  }
  if (bytes[at] != '<') return std::nullopt;
  const std::size_t close = bytes.find('>', at);
  if (close == std::string::npos) return std::nullopt;
  std::string hex;
  for (std::size_t k = at + 1; k < close; ++k)
    if (std::isxdigit(static_cast<unsigned char>(bytes[k]))) hex += bytes[k];
  std::vector<std::uint32_t> units;
  for (std::size_t k = 0; k + 4 <= hex.size(); k += 4)
    units.push_back(std::stoul(hex.substr(k, 4), nullptr, 16));
  std::size_t k = !units.empty() && units[0] == 0xFEFF ? 1 : 0;
  for (; k < units.size(); ++k) {
    std::uint32_t cp = units[k];
    if (cp >= 0xD800 && cp < 0xDC00 && k + 1 < units.size())
      cp = 0x10000 + ((cp - 0xD800) << 10) + (units[++k] - 0xDC00);
    append_utf8(text, cp);
  }
  return text;
}

// An .npz's provenance.npy ('<U' text, UTF-32LE; codec/npz_writer.cpp), its first cell.
std::optional<std::string> npz_provenance(const std::string& path) {
  int error = 0;
  std::unique_ptr<zip_t, decltype(&zip_discard)> archive(zip_open(path.c_str(), ZIP_RDONLY, &error),
                                                         zip_discard);
  if (!archive) return std::nullopt;
  zip_stat_t stat;
  if (zip_stat(archive.get(), "provenance.npy", 0, &stat) != 0 || !(stat.valid & ZIP_STAT_SIZE))
    return std::nullopt;
  std::unique_ptr<zip_file_t, decltype(&zip_fclose)> file(zip_fopen(archive.get(), "provenance.npy", 0),
                                                          zip_fclose);
  if (!file) return std::nullopt;
  std::string npy(stat.size, '\0');
  if (zip_fread(file.get(), npy.data(), stat.size) != static_cast<zip_int64_t>(stat.size))
    return std::nullopt;
  if (npy.size() < 10 || npy.compare(1, 5, "NUMPY") != 0) return std::nullopt;
  const std::size_t header = 10 + (static_cast<unsigned char>(npy[8]) |
                                   static_cast<std::size_t>(static_cast<unsigned char>(npy[9])) << 8);
  const std::size_t descr = npy.find("'<U", 10);
  if (descr == std::string::npos || descr > header) return std::nullopt;
  const std::size_t width = std::stoul(npy.substr(descr + 3));
  std::string text;
  for (std::size_t k = 0; k < width && header + 4 * k + 4 <= npy.size(); ++k) {
    const auto b = [&](std::size_t i) {
      return static_cast<std::uint32_t>(static_cast<unsigned char>(npy[header + 4 * k + i]));
    };
    const std::uint32_t cp = b(0) | b(1) << 8 | b(2) << 16 | b(3) << 24;
    if (cp == 0) break;
    append_utf8(text, cp);
  }
  return text;
}

// A text output's lines: JSON Lines' first record, or CSV (and summary.md) comment lines.
std::optional<json> text_provenance(const std::string& bytes) {
  std::istringstream lines(bytes);
  std::string line;
  std::optional<json> sweep_base;
  std::string sweep_command;
  for (int n = 0; std::getline(lines, line) && n < 64; ++n) {
    if (n == 0 && line.starts_with('{')) {
      if (auto first = parsed(line)) {
        if (first->contains("provenance")) return (*first)["provenance"];
        if (first->contains("sweep")) return (*first)["sweep"];
      }
    }
    if (line.starts_with("# provenance: ")) return parsed(std::string_view(line).substr(14));
    if (line.starts_with("# command: ")) sweep_command = line.substr(11);
    if (line.starts_with("# base: ")) sweep_base = parsed(std::string_view(line).substr(8));
  }
  if (sweep_base && !sweep_command.empty()) return json{{"command", sweep_command}, {"base", *sweep_base}};
  return std::nullopt;
}

}  // namespace

RecordedRun recorded_run(const std::string& path) {
  const std::string bytes = whole_file(path);
  RecordedRun run;
  std::optional<json> provenance;
  if (bytes.starts_with("\x89PNG\r\n\x1a\n")) {
    run.format = "png";
    if (const auto text = png_source(bytes)) provenance = parsed(*text);
  } else if (bytes.starts_with("%PDF")) {
    run.format = "pdf";
    if (const auto text = pdf_subject(bytes)) provenance = parsed(*text);
  } else if (bytes.starts_with("PK")) {
    run.format = "npz";
    if (const auto text = npz_provenance(path)) {
      provenance = parsed(*text);  // simulate's record, or a sweep's JSON Lines header
      if (provenance && provenance->contains("sweep")) provenance = (*provenance)["sweep"];
    }
  } else if (bytes.find("<svg") != std::string::npos && bytes.find("<metadata>") != std::string::npos) {
    run.format = "svg";
    if (const auto text = svg_metadata(bytes)) provenance = parsed(*text);
  } else {
    run.format = bytes.starts_with('{') ? "jsonl" : bytes.starts_with("<!--") ? "markdown" : "csv";
    provenance = text_provenance(bytes);
  }
  if (!provenance || !provenance->is_object())
    throw ProvenanceError("'" + path + "' carries no spinfold provenance (a " + run.format +
                          " file without its record of the run)");
  const json& p = *provenance;
  run.version = p.value("version", "");
  run.commit = p.value("commit", "");
  run.command = p.value("command", "");
  // a sweep's header: its base scene as given; any other output: the scene as run
  if (p.contains("base") && p["base"].is_object() && p["base"].contains("scene"))
    run.scene = p["base"]["scene"];
  else if (p.contains("scene"))
    run.scene = p["scene"];
  if (run.command.empty() || !run.scene.is_object())
    throw ProvenanceError("'" + path + "' records no command and scene to re-run (" +
                          (run.command.empty() ? "no command: made by the HTTP API or a library call"
                                               : "no scene: made by a version before 0.3.0") +
                          ")");
  return run;
}

}  // namespace spinfold
