#include "record/recorder.h"

#include "record/clip.h"

namespace spinfold::record {

std::optional<Format> parse_format(std::string_view name) {
  if (name == "gif") return Format::gif;
  if (name == "webm") return Format::webm;
  if (name == "mp4") return Format::mp4;
  if (name == "png-zip") return Format::png_zip;
  return std::nullopt;
}

std::string_view format_name(Format format) {
  switch (format) {
    case Format::gif: return "gif";
    case Format::webm: return "webm";
    case Format::mp4: return "mp4";
    case Format::png_zip: return "png-zip";
  }
  return "gif";
}

std::string_view content_type(Format format) {
  switch (format) {
    case Format::gif: return "image/gif";
    case Format::webm: return "video/webm";
    case Format::mp4: return "video/mp4";
    case Format::png_zip: return "application/zip";
  }
  return "application/octet-stream";
}

std::string_view file_extension(Format format) {
  switch (format) {
    case Format::gif: return "gif";
    case Format::webm: return "webm";
    case Format::mp4: return "mp4";
    case Format::png_zip: return "zip";
  }
  return "bin";
}

std::optional<std::string> size_unsupported_reason(Format format, int width, int height) {
  if ((format == Format::webm || format == Format::mp4) && (width % 2 != 0 || height % 2 != 0))
    return std::string(format_name(format)) +
           " video is 4:2:0 (chroma at half resolution): width and height must be even";
  return std::nullopt;
}

std::unique_ptr<Recorder> open_recorder(Format format, const std::string& path, const RecordingSpec& spec) {
  // Before the file exists: the writers turn fps into integer delays and time bases.
  if (!(spec.fps >= kMinFps && spec.fps <= kMaxFps))
    throw RecordError("fps must be a number from 0.01 to 120 [frames/s]");
  switch (format) {
    case Format::gif: return open_gif(path, spec);
    case Format::webm:
    case Format::mp4: return open_video(format, path, spec);
    case Format::png_zip: return open_png_zip(path, spec);
  }
  throw RecordError("unknown format");
}

}  // namespace spinfold::record
