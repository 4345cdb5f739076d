// Clip writers: RGBA frames in, one file out (GIF, WebM/VP9, MP4/H.264, a zip of PNGs). One writer
// per format behind this interface, each on a library that does the encoding and the container (giflib,
// FFmpeg's libavformat/libavcodec, libzip): docs/recording.md says why each. No GL, no physics.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace spinfold::record {

enum class Format { gif, webm, mp4, png_zip };

// The one table of recording formats: the name the API, the CLI and the UI use, the file's
// extension and content type, and one line for a reader.
struct FormatInfo {
  std::string_view name;  // "png-zip"
  Format format;
  std::string_view extension;     // "zip"
  std::string_view content_type;  // "application/zip"
  std::string_view help;          // one line
};
inline constexpr FormatInfo kFormats[] = {
    {"gif", Format::gif, "gif", "image/gif", "an animated GIF (giflib): one 256-colour palette for the clip"},
    {"webm", Format::webm, "webm", "video/webm",
     "WebM video, VP9 (libvpx through FFmpeg), 4:2:0: even sides"},
    {"mp4", Format::mp4, "mp4", "video/mp4", "MP4 video, H.264 (libx264 through FFmpeg), 4:2:0: even sides"},
    {"png-zip", Format::png_zip, "zip", "application/zip", "a zip of lossless PNG frames (libzip)"},
};
const FormatInfo& format_info(Format format);
// The names joined for a message or a help text: "gif, webm, mp4 or png-zip" with last = " or ".
std::string joined_format_names(std::string_view separator, std::string_view last);

std::optional<Format> parse_format(std::string_view name);  // "gif", "webm", "mp4", "png-zip"
std::string_view format_name(Format format);
std::string_view content_type(Format format);    // "image/gif", "video/webm", "video/mp4", "application/zip"
std::string_view file_extension(Format format);  // "gif", "webm", "mp4", "zip"
// Why a frame size cannot be recorded in this format, or nullopt (4:2:0 video needs even sides).
std::optional<std::string> size_unsupported_reason(Format format, int width, int height);

// An encoder or file error: what failed, in one sentence.
struct RecordError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What every writer is told before the first frame.
struct ClipWriterSpec {
  int width = 640;    // [pixels]
  int height = 480;   // [pixels]
  double fps = 30.0;  // frames per second of the file (the playback rate, not the simulated rate)
  // Where it came from (codec/provenance.h, one line of JSON): a GIF comment extension, the WebM
  // and MP4 container's "comment" tag, the zip's archive comment and each PNG's Source text.
  std::string provenance{};
};

class ClipWriter {
 public:
  virtual ~ClipWriter() = default;
  // Frames to show the writer before the first add() (GIF: its one palette is chosen from them);
  // 0 when it needs none. Give them in the order of the recording.
  virtual int palette_samples() const { return 0; }
  virtual void add_palette_sample(const std::uint8_t* /*rgba*/) {}
  // One frame: width·height·4 RGBA bytes, first row on top. RecordError on failure.
  virtual void add(const std::uint8_t* rgba) = 0;
  // Flushes and closes the file; no frame may follow. RecordError on failure.
  virtual void finish() = 0;
  // The bytes written so far, or held to be written (a bound on the file's size as it grows).
  virtual std::uint64_t bytes() const = 0;
};

// The writer of a format, writing `path` (created or truncated). RecordError when it cannot start.
std::unique_ptr<ClipWriter> open_clip_writer(Format format, const std::string& path,
                                             const ClipWriterSpec& spec);

// The writers (gif_writer.cpp, video_writer.cpp, png_zip_writer.cpp).
std::unique_ptr<ClipWriter> open_gif(const std::string& path, const ClipWriterSpec& spec);
std::unique_ptr<ClipWriter> open_video(Format format, const std::string& path, const ClipWriterSpec& spec);
std::unique_ptr<ClipWriter> open_png_zip(const std::string& path, const ClipWriterSpec& spec);

}  // namespace spinfold::record
