#include "record/recorder.h"

#include <iterator>

#include "record/clip.h"

namespace spinfold::record {

const FormatInfo& format_info(Format format) {
  for (const FormatInfo& f : kFormats)
    if (f.format == format) return f;
  return kFormats[0];
}

std::string joined_format_names(std::string_view separator, std::string_view last) {
  std::string names;
  for (std::size_t i = 0; i < std::size(kFormats); ++i) {
    if (i > 0) names += i + 1 == std::size(kFormats) ? last : separator;
    names += kFormats[i].name;
  }
  return names;
}

std::optional<Format> parse_format(std::string_view name) {
  for (const FormatInfo& f : kFormats)
    if (f.name == name) return f.format;
  return std::nullopt;
}

std::string_view format_name(Format format) {
  return format_info(format).name;
}

std::string_view content_type(Format format) {
  return format_info(format).content_type;
}

std::string_view file_extension(Format format) {
  return format_info(format).extension;
}

std::optional<std::string> size_unsupported_reason(Format format, int width, int height) {
  if ((format == Format::webm || format == Format::mp4) && (width % 2 != 0 || height % 2 != 0))
    return std::string(format_name(format)) +
           " video is 4:2:0 (chroma at half resolution): width and height must be even";
  return std::nullopt;
}

std::unique_ptr<ClipWriter> open_clip_writer(Format format, const std::string& path,
                                             const ClipWriterSpec& spec) {
  // Before the file exists: the writers turn fps into integer delays and time bases.
  if (const auto why = refusal(kFpsRule, spec.fps)) throw RecordError("fps " + *why);
  switch (format) {
    case Format::gif: return open_gif(path, spec);
    case Format::webm:
    case Format::mp4: return open_video(format, path, spec);
    case Format::png_zip: return open_png_zip(path, spec);
  }
  throw RecordError("unknown format");
}

}  // namespace spinfold::record
