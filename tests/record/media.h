// Reads recordings back for the tests, through the libraries' decoders: a GIF's images and delays
// (giflib's DGifSlurp), a video's frames, times and duration (libavformat demuxing, libavcodec
// decoding), a zip's entries (libzip).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace spinfold::record::testing {

struct GifInfo {
  int width = 0, height = 0;             // the logical screen [pixels]
  int images = 0;                        // image descriptors
  std::vector<int> delays;               // per image [1/100 s]
  bool loops_forever = false;            // NETSCAPE2.0 with loop count 0
  int colors = 0;                        // global colour table size
  std::vector<std::uint8_t> first_rgba;  // the first image, composed on the screen (RGBA)
  // Every image composed on the screen as a viewer shows it (each over the last: disposal "leave
  // in place", its transparent pixels showing the one before), RGBA.
  std::vector<std::vector<std::uint8_t>> shown;
  std::vector<long> stored;  // per image: the pixels it stores that are not transparent
};
GifInfo read_gif(const std::string& path);

struct VideoInfo {
  std::string codec;               // "vp9", "h264"
  int width = 0, height = 0;       // [pixels]
  long long packets = 0;           // video packets demuxed
  std::vector<double> pts;         // presentation times of the decoded frames, in order [s]
  double duration = 0;             // the container's duration [s]
  std::vector<std::uint8_t> rgba;  // decoded frame `keep`, converted to RGBA
};
VideoInfo read_video(const std::string& path, int keep = 0);

std::vector<std::string> zip_names(const std::string& path);
std::vector<std::uint8_t> zip_entry(const std::string& path, const std::string& name);

std::vector<std::uint8_t> file_bytes(const std::string& path);
// Peak signal-to-noise ratio of the RGB channels [dB] (infinity when equal).
double psnr_rgb(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b);

}  // namespace spinfold::record::testing
