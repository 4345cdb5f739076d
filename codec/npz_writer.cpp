#include "codec/npz_writer.h"

#include <zip.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>

namespace spinfold {

namespace {

static_assert(std::endian::native == std::endian::little, "the .npy data is written as the machine holds it");

// The code points of UTF-8 text (an invalid byte stands for itself: the text is ours, never invalid).
std::u32string code_points(const std::string& text) {
  std::u32string out;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const int extra = c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : c >= 0xC0 ? 1 : 0;
    char32_t cp = extra == 0 ? c : c & (0x3F >> extra);
    std::size_t k = 1;
    for (; k <= static_cast<std::size_t>(extra) && i + k < text.size(); ++k)
      cp = (cp << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
    out.push_back(cp);
    i += k;
  }
  return out;
}

// The .npy header: magic, version 1.0, the dict's length, the dict padded with spaces and ended by
// a newline so that the data starts at a multiple of 64 bytes.
std::vector<std::uint8_t> npy_header(const std::string& descr, std::size_t rows) {
  std::string dict =
      "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ",), }";
  const std::size_t unpadded = 10 + dict.size() + 1;
  dict.append((64 - unpadded % 64) % 64, ' ');
  dict += '\n';
  std::vector<std::uint8_t> out = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0};
  out.push_back(static_cast<std::uint8_t>(dict.size() & 0xFF));
  out.push_back(static_cast<std::uint8_t>(dict.size() >> 8));
  out.insert(out.end(), dict.begin(), dict.end());
  return out;
}

template <class T>
void append(std::vector<std::uint8_t>& out, const T& value) {
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(&value);
  out.insert(out.end(), bytes, bytes + sizeof value);
}

}  // namespace

std::vector<std::uint8_t> npy_bytes(const std::vector<nlohmann::ordered_json>& cells) {
  bool numeric = true, whole = !cells.empty(), negative = false;
  for (const auto& c : cells) {
    numeric = numeric && (c.is_number() || c.is_null());
    whole = whole && c.is_number_integer();
    negative = negative || (c.is_number_integer() && !c.is_number_unsigned() && c.get<std::int64_t>() < 0);
  }
  // Whole numbers (counts, steps, occurrences) as Python's sweep gives them: uint64, or int64 with a
  // negative one; a column with a null in it is float64 with NaN there.
  if (whole) {
    std::vector<std::uint8_t> out = npy_header(negative ? "<i8" : "<u8", cells.size());
    for (const auto& c : cells)
      if (negative)
        append(out, c.get<std::int64_t>());
      else
        append(out, c.get<std::uint64_t>());
    return out;
  }
  if (numeric) {
    std::vector<std::uint8_t> out = npy_header("<f8", cells.size());
    for (const auto& c : cells) append(out, c.is_null() ? std::nan("") : c.get<double>());
    return out;
  }
  std::vector<std::u32string> texts;
  std::size_t width = 1;
  for (const auto& c : cells) {
    texts.push_back(code_points(c.is_string() ? c.get<std::string>() : c.is_null() ? "" : c.dump()));
    width = std::max(width, texts.back().size());
  }
  std::vector<std::uint8_t> out = npy_header("<U" + std::to_string(width), cells.size());
  for (const std::u32string& t : texts)
    for (std::size_t k = 0; k < width; ++k) append(out, static_cast<std::uint32_t>(k < t.size() ? t[k] : 0));
  return out;
}

void write_npz(const std::string& path, const std::vector<NpzColumn>& columns) {
  int error = 0;
  zip_t* archive = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (!archive)
    throw std::runtime_error("cannot write '" + path + "' (libzip error " + std::to_string(error) + ")");
  // libzip reads each array when the archive is closed: they are kept until then.
  std::vector<std::vector<std::uint8_t>> arrays;
  arrays.reserve(columns.size());
  bool ok = true;
  for (const NpzColumn& column : columns) {
    arrays.push_back(npy_bytes(column.cells));
    zip_source_t* source = zip_source_buffer(archive, arrays.back().data(), arrays.back().size(), 0);
    const zip_int64_t index = source ? zip_file_add(archive, (column.name + ".npy").c_str(), source,
                                                    ZIP_FL_OVERWRITE | ZIP_FL_ENC_UTF_8)
                                     : -1;
    if (index < 0) {
      if (source) zip_source_free(source);
      ok = false;
      break;
    }
    // no clock in the bytes: every entry dated 1980-01-01 00:00 (the zip's first day), as the
    // recorder's png-zip is, so the same table is the same file
    if (zip_set_file_compression(archive, static_cast<zip_uint64_t>(index), ZIP_CM_STORE, 0) != 0 ||
        zip_file_set_dostime(archive, static_cast<zip_uint64_t>(index), 0, (0 << 9) | (1 << 5) | 1, 0) != 0) {
      ok = false;
      break;
    }
  }
  if (!ok || zip_close(archive) != 0) {
    const std::string why = zip_strerror(archive);
    zip_discard(archive);
    throw std::runtime_error("cannot write '" + path + "': " + why);
  }
}

}  // namespace spinfold
