// The writers, fed synthetic frames (no GL): each file parsed back through its library's decoder —
// frame counts, timing, looping, the palette, byte-identical reruns, a decoded frame against its
// source.
#include "record/recorder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numeric>

#include "media.h"
#include "render/png_encoder.h"

namespace spinfold::record {
namespace {

using namespace testing;
namespace fs = std::filesystem;

constexpr int kW = 64, kH = 48;

// Frame k: a flat background, a flat square moving right, a smooth ramp along the bottom.
std::vector<std::uint8_t> frame(int k) {
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(kW) * kH * 4);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      std::uint8_t* p = &rgba[4 * (static_cast<std::size_t>(y) * kW + x)];
      p[0] = 235, p[1] = 240, p[2] = 245, p[3] = 255;  // background
      if (x >= 4 + 3 * k && x < 16 + 3 * k && y >= 10 && y < 22) p[0] = 245, p[1] = 140, p[2] = 30;
      if (y >= 40)
        p[0] = static_cast<std::uint8_t>(4 * x), p[1] = 60, p[2] = static_cast<std::uint8_t>(255 - 4 * x);
    }
  return rgba;
}

fs::path temp_file(const std::string& name) {
  // One directory per process, removed with its files when the process ends.
  static const struct Dir {
    fs::path path = fs::temp_directory_path() / ("spinfold-record-test-" + std::to_string(::getpid()));
    Dir() { fs::create_directories(path); }
    ~Dir() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  } dir;
  return dir.path / name;
}

void write(Format format, const fs::path& path, int frames, double fps, bool samples = true) {
  auto recorder = open_clip_writer(format, path, {kW, kH, fps});
  if (samples)
    for (int j = 0; j < recorder->palette_samples(); ++j)
      recorder->add_palette_sample(
          frame(j * (frames - 1) / std::max(1, recorder->palette_samples() - 1)).data());
  for (int k = 0; k < frames; ++k) recorder->add(frame(k).data());
  recorder->finish();
  EXPECT_GT(recorder->bytes(), 0u);
}

TEST(RecorderGif, ImagesDelaysLoopAndOnePalette) {
  const fs::path path = temp_file("clip.gif");
  write(Format::gif, path, 10, 15.0);
  const GifInfo gif = read_gif(path);
  EXPECT_EQ(gif.width, kW);
  EXPECT_EQ(gif.height, kH);
  EXPECT_EQ(gif.images, 10);
  EXPECT_TRUE(gif.loops_forever);
  EXPECT_EQ(gif.colors, 256);
  // 15 frames/s: frame k starts at round(100·k/15) hundredths, so the delays are 7, 6, 7, … and
  // they add up to the clip's 0.67 s.
  ASSERT_EQ(gif.delays.size(), 10u);
  for (int k = 0; k < 10; ++k)
    EXPECT_EQ(gif.delays[k], std::lround(100.0 * (k + 1) / 15) - std::lround(100.0 * k / 15)) << k;
  EXPECT_EQ(std::accumulate(gif.delays.begin(), gif.delays.end(), 0), 67);
  // A flat colour is one colour everywhere (never dithered), close to the source's.
  const std::vector<std::uint8_t> source = frame(0);
  const std::uint8_t* corner = &gif.first_rgba[0];
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < kW; ++x) {
      const std::size_t i = 4 * (static_cast<std::size_t>(y) * kW + x);
      if (source[i] != 235) continue;  // the square
      ASSERT_EQ(std::memcmp(&gif.first_rgba[i], corner, 3), 0) << x << "," << y;
    }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(corner[c], source[c], 8);
  EXPECT_GT(psnr_rgb(gif.first_rgba, source), 30.0);
}

TEST(RecorderGif, EveryFrameShowsItsSourceAndStoresOnlyWhatChanged) {
  const fs::path path = temp_file("changes.gif");
  write(Format::gif, path, 10, 15.0);
  const GifInfo gif = read_gif(path);
  ASSERT_EQ(gif.shown.size(), 10u);
  ASSERT_EQ(gif.stored.size(), 10u);
  EXPECT_EQ(gif.stored[0], static_cast<long>(kW) * kH);  // the first frame whole
  for (int k = 0; k < 10; ++k) {
    const std::vector<std::uint8_t> source = frame(k);
    EXPECT_GT(psnr_rgb(gif.shown[k], source), 30.0) << k;
    // The square, where it is in this frame, one colour near its own.
    const std::uint8_t* square = &gif.shown[k][4 * (10 * static_cast<std::size_t>(kW) + 4 + 3 * k)];
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(square[c], source[4 * (10 * kW + 4 + 3 * k) + c], 8) << k;
    for (int y = 10; y < 22; ++y)
      for (int x = 4 + 3 * k; x < 16 + 3 * k; ++x)
        ASSERT_EQ(std::memcmp(&gif.shown[k][4 * (static_cast<std::size_t>(y) * kW + x)], square, 3), 0)
            << k << ": " << x << "," << y;
    // The square moves 3 pixels right: a 3x12 strip becomes background and another becomes square;
    // every other pixel is stored as "as before".
    if (k > 0) {
      EXPECT_EQ(gif.stored[k], 2 * 3 * 12) << k;
    }
  }
}

// A smooth gradient of more colours than the palette has: the ordered dither keeps each small
// block's mean colour where the source's is (the nearest colour alone bands: blocks off by up to
// half the palette's spacing; measured 2.1 levels with the dither, 5.5 without).
TEST(RecorderGif, AGradientKeepsItsLocalMeanWithoutBands) {
  constexpr int w = 128, h = 128, block = 8;
  std::vector<std::uint8_t> ramp(static_cast<std::size_t>(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = &ramp[4 * (static_cast<std::size_t>(y) * w + x)];
      p[0] = static_cast<std::uint8_t>(2 * x), p[1] = static_cast<std::uint8_t>(2 * y), p[2] = 128,
      p[3] = 255;
    }
  const fs::path path = temp_file("ramp.gif");
  auto recorder = open_clip_writer(Format::gif, path, {w, h, 10.0});
  recorder->add_palette_sample(ramp.data());
  recorder->add(ramp.data());
  recorder->add(ramp.data());
  recorder->finish();
  const GifInfo gif = read_gif(path);
  ASSERT_EQ(gif.shown.size(), 2u);
  EXPECT_EQ(gif.stored[1], 0);  // nothing changed: the dither is fixed to the pixel's place
  double worst = 0;
  // Inside the palette's reach: the blocks on the frame's edge hold the ramp's extremes, which the
  // k-means' means (centroids of their cells) fall a few levels short of.
  for (int by = block; by < h - block; by += block)
    for (int bx = block; bx < w - block; bx += block)
      for (int c = 0; c < 3; ++c) {
        double error = 0;
        for (int y = by; y < by + block; ++y)
          for (int x = bx; x < bx + block; ++x) {
            const std::size_t i = 4 * (static_cast<std::size_t>(y) * w + x) + c;
            error += static_cast<double>(gif.shown[0][i]) - ramp[i];
          }
        worst = std::max(worst, std::abs(error) / (block * block));
      }
  RecordProperty("worst_block_mean_error", std::to_string(worst));
  EXPECT_LT(worst, 3.0);
}

TEST(RecorderGif, RerunIsByteIdentical) {
  write(Format::gif, temp_file("a.gif"), 6, 30.0);
  write(Format::gif, temp_file("b.gif"), 6, 30.0);
  EXPECT_EQ(file_bytes(temp_file("a.gif")), file_bytes(temp_file("b.gif")));
  write(Format::gif, temp_file("c.gif"), 7, 30.0);  // and a different clip differs
  EXPECT_NE(file_bytes(temp_file("a.gif")), file_bytes(temp_file("c.gif")));
}

TEST(RecorderPngZip, EntriesInOrderEachThePngOfItsFrame) {
  const fs::path path = temp_file("clip.zip");
  write(Format::png_zip, path, 5, 30.0);
  const auto names = zip_names(path);
  ASSERT_EQ(names.size(), 5u);
  for (int k = 0; k < 5; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame-%06d.png", k);
    EXPECT_EQ(names[k], name);
    const std::vector<std::uint8_t> source = frame(k);
    EXPECT_EQ(zip_entry(path, name), render::encode_png(source.data(), kW, kH)) << k;
  }
}

TEST(RecorderPngZip, RerunIsByteIdentical) {
  write(Format::png_zip, temp_file("a.zip"), 4, 30.0);
  write(Format::png_zip, temp_file("b.zip"), 4, 30.0);
  EXPECT_EQ(file_bytes(temp_file("a.zip")), file_bytes(temp_file("b.zip")));
}

// VmRSS of this process [KiB].
long rss_kib() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  long kib = -1;
  char line[256];
  while (f && std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "VmRSS: %ld", &kib) == 1) break;
  if (f) std::fclose(f);
  return kib;
}

// A recording's largest frames (server::Limits: 1920×1080) that do not compress (noise: each PNG
// ~6.2 MB of RGB): 32 of them held until finish() would be ~200 MB; the writer holds one. The
// archive still has every frame's own PNG.
TEST(RecorderPngZip, HoldsOneFrameNotTheClip) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the sanitizers keep freed blocks (ASan's quarantine), so RSS does not follow what is held";
#endif
  constexpr int w = 1920, h = 1080, frames = 32;
  const auto noise = [&](int k) {
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(w) * h * 4);
    std::uint64_t x = 0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(k + 1);
    for (std::size_t i = 0; i < rgba.size(); i += 8) {
      x ^= x << 13, x ^= x >> 7, x ^= x << 17;  // xorshift64
      std::memcpy(&rgba[i], &x, 8);
    }
    for (std::size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
    return rgba;
  };
  const fs::path path = temp_file("large.zip");
  auto recorder = open_clip_writer(Format::png_zip, path, {w, h, 30.0});
  recorder->add(noise(0).data());  // the first frame's buffers, libzip's and the encoder's
  const long before = rss_kib();
  for (int k = 1; k < frames; ++k) recorder->add(noise(k).data());
  const long grown = rss_kib() - before;
  EXPECT_GT(recorder->bytes(), 32ull * 6'000'000) << "the frames do not compress, as meant";
  EXPECT_LT(grown, 64 * 1024) << "KiB grown over 31 frames of ~6 MB: the PNGs are held in memory";
  recorder->finish();
  ASSERT_EQ(zip_names(path).size(), static_cast<std::size_t>(frames));
  const std::vector<std::uint8_t> last = noise(frames - 1);
  EXPECT_EQ(zip_entry(path, "frame-000031.png"), render::encode_png(last.data(), w, h));
  EXPECT_FALSE(fs::exists(path.string() + ".frames")) << "the spill file is removed";
}

class RecorderVideo : public ::testing::TestWithParam<Format> {};

TEST_P(RecorderVideo, FramesTimesDurationAndPicture) {
  const Format format = GetParam();
  const fs::path path = temp_file(std::string("clip.") + std::string(file_extension(format)));
  constexpr int kFrames = 12;
  constexpr double kFps = 24.0;
  write(format, path, kFrames, kFps);
  const VideoInfo video = read_video(path, 5);
  EXPECT_EQ(video.codec, format == Format::webm ? "vp9" : "h264");
  EXPECT_EQ(video.width, kW);
  EXPECT_EQ(video.height, kH);
  EXPECT_EQ(video.packets, kFrames);
  ASSERT_EQ(video.pts.size(), static_cast<std::size_t>(kFrames));
  for (int k = 0; k < kFrames; ++k) EXPECT_NEAR(video.pts[k], k / kFps, 0.002) << k;
  EXPECT_NEAR(video.duration, kFrames / kFps, 1.0 / kFps + 0.002);
  // 4:2:0 halves the chroma resolution: on a 64×48 frame of hard colour edges that alone costs
  // ~29 dB. Frame 5 is closer to its source than to its neighbours' (the square moved 3 pixels).
  const double psnr = psnr_rgb(video.rgba, frame(5));
  EXPECT_GT(psnr, 26.0);
  EXPECT_GT(psnr, psnr_rgb(video.rgba, frame(4)) + 2.0);
  EXPECT_GT(psnr, psnr_rgb(video.rgba, frame(6)) + 2.0);
}

INSTANTIATE_TEST_SUITE_P(WebmAndMp4, RecorderVideo, ::testing::Values(Format::webm, Format::mp4),
                         [](const auto& p) { return std::string(format_name(p.param)); });

TEST(ClipWriter, FormatsNamesAndSizes) {
  for (const Format f : {Format::gif, Format::webm, Format::mp4, Format::png_zip})
    EXPECT_EQ(parse_format(format_name(f)), f);
  EXPECT_FALSE(parse_format("avi"));
  EXPECT_EQ(content_type(Format::mp4), "video/mp4");
  EXPECT_TRUE(size_unsupported_reason(Format::webm, 65, 48));
  EXPECT_TRUE(size_unsupported_reason(Format::mp4, 64, 47));
  EXPECT_FALSE(size_unsupported_reason(Format::gif, 65, 47));
  EXPECT_THROW(open_clip_writer(Format::gif, "/nonexistent-dir/x.gif", {kW, kH, 30}), RecordError);
}

}  // namespace
}  // namespace spinfold::record
