// The golden comparison (frame_compare.h): passes llvmpipe's measured jitter across CPU code (pairs
// in tests/golden/jitter/: NAME.pinned.png, the golden frame as pinned on another machine, and
// NAME.sse4.1.png, rendered here with GALLIUM_OVERRIDE_CPU_CAPS=sse4.1), fails on
// anything with a shape: a line moved by a pixel, a missing body, a missing glyph, a shade changed
// everywhere.
#include "tests/render/frame_compare.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace spinfold::test {
namespace {

const std::filesystem::path kGolden = SPINFOLD_GOLDEN_DIR;

RgbImage golden(const std::string& name) {
  std::optional<RgbImage> image = read_png(kGolden / (name + ".png"));
  EXPECT_TRUE(image) << name;
  return image.value_or(RgbImage{});
}

void fill(RgbImage& image, int x0, int y0, int x1, int y1, std::array<std::uint8_t, 3> colour) {
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c)
        image.rgb[(static_cast<std::size_t>(y) * image.width + x) * 3 + c] = colour[c];
}

// A light background, a grey disc (a body) at (200, 150) and a dark 2-pixel line at row `line_y`.
RgbImage drawing(int line_y, bool with_body = true) {
  RgbImage image{320, 240, std::vector<std::uint8_t>(320 * 240 * 3, 245)};
  if (with_body)
    for (int y = 140; y < 160; ++y)
      for (int x = 190; x < 210; ++x)
        if ((x - 200) * (x - 200) + (y - 150) * (y - 150) <= 64)
          fill(image, x, y, x + 1, y + 1, {200, 120, 40});
  fill(image, 20, line_y, 300, line_y + 2, {40, 60, 160});
  return image;
}

bool matches(const RgbImage& a, const RgbImage& b) {
  return within(compare_frames(a, b, {}), {});
}

TEST(FrameCompare, AFrameMatchesItself) {
  const RgbImage image = golden("jitter/tractricoid.pinned");
  const FrameDifference d = compare_frames(image, image, {});
  EXPECT_EQ(d.differing, 0);
  EXPECT_TRUE(within(d, {}));
}

TEST(FrameCompare, TheMeasuredJitterOfAnotherCpusCodePasses) {
  // The three worst frames of the measurement: the most pixels moved (the thumbnail, 0.46%), the
  // largest level (43 in 4 edge pixels of the tractricoid) and 7 levels at the sphere's lines.
  for (const std::string name : {"tractricoid", "sphere_thumbnail", "spin_vs_geodesic_sphere"}) {
    const RgbImage pinned = golden("jitter/" + name + ".pinned"),
                   other = golden("jitter/" + name + ".sse4.1");
    const FrameDifference d = compare_frames(pinned, other, {});
    EXPECT_GT(d.differing, 0) << name << ": the pair shows no jitter, so it proves nothing";
    EXPECT_TRUE(within(d, {})) << name << ": " << describe(d, {});
  }
}

TEST(FrameCompare, ALineMovedByOnePixelFails) {
  const FrameDifference d = compare_frames(drawing(100), drawing(101), {});
  EXPECT_FALSE(within(d, {})) << describe(d, {});
  EXPECT_GT(d.worst_block, FrameTolerance{}.max_over_jitter_in_block);
}

TEST(FrameCompare, AMissingBodyFails) {
  const FrameDifference d = compare_frames(drawing(100), drawing(100, false), {});
  EXPECT_FALSE(within(d, {})) << describe(d, {});
  EXPECT_GT(d.worst_block, FrameTolerance{}.max_over_jitter_in_block);
  EXPECT_EQ(d.worst_block_x / 16, 192 / 16);  // where the body was
}

TEST(FrameCompare, AMissingGlyphFails) {
  // The "t" of "t = 6.000" in the HUD (its top-left corner) painted over with the HUD box's colour.
  const RgbImage pinned = golden("jitter/tractricoid.pinned");
  RgbImage edited = pinned;
  const std::size_t box = (static_cast<std::size_t>(14) * pinned.width + 300) * 3;  // inside the box, no text
  fill(edited, 10, 10, 19, 24, {pinned.rgb[box], pinned.rgb[box + 1], pinned.rgb[box + 2]});
  const FrameDifference d = compare_frames(pinned, edited, {});
  EXPECT_LT(d.fraction(), FrameTolerance{}.max_differing_fraction);  // a few pixels: caught by the blocks
  EXPECT_GT(d.worst_block, FrameTolerance{}.max_over_jitter_in_block) << describe(d, {});
  EXPECT_FALSE(within(d, {})) << describe(d, {});
}

TEST(FrameCompare, AFaintChangeEverywhereFails) {
  // One level on every pixel: within the jitter level, but not the scattered pixels of jitter.
  const RgbImage pinned = golden("jitter/sphere_thumbnail.pinned");
  RgbImage lighter = pinned;
  for (std::uint8_t& v : lighter.rgb) v = v == 255 ? 254 : v + 1;
  EXPECT_FALSE(matches(pinned, lighter));
}

TEST(FrameCompare, FramesOfAnotherSizeFail) {
  const RgbImage a = drawing(100);
  RgbImage b = a;
  b.height = 239;
  b.rgb.resize(320 * 239 * 3);
  EXPECT_FALSE(matches(a, b));
  EXPECT_EQ(describe(compare_frames(a, b, {}), {}), "the frames differ in size");
}

TEST(FrameCompare, AMismatchWritesTheFrameAndADifferenceImageAndSaysWhy) {
  const std::filesystem::path dir = std::filesystem::path(SPINFOLD_ACTUAL_DIR) / "frame_compare_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ASSERT_TRUE(write_png(dir / "expected.png", drawing(100)));
  ASSERT_TRUE(write_png(dir / "moved.png", drawing(104)));
  std::ifstream in(dir / "moved.png", std::ios::binary);
  const std::vector<std::uint8_t> moved{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};

  const std::string why = golden_mismatch(moved, dir / "expected.png", dir / "actual.png");
  EXPECT_NE(why.find("pixels differ"), std::string::npos) << why;
  EXPECT_NE(why.find("beyond 3 levels"), std::string::npos) << why;
  const std::optional<RgbImage> actual = read_png(dir / "actual.png"),
                                diff = read_png(dir / "actual.diff.png");
  ASSERT_TRUE(actual && diff);
  EXPECT_TRUE(matches(*actual, drawing(104)));
  // Red where the line was and where it is now, grey elsewhere.
  const auto at = [&](int x, int y, int c) {
    return diff->rgb[(static_cast<std::size_t>(y) * diff->width + x) * 3 + c];
  };
  EXPECT_EQ(at(150, 100, 0), 255);
  EXPECT_EQ(at(150, 104, 0), 255);
  EXPECT_EQ(at(150, 104, 1), 0);
  EXPECT_EQ(at(150, 50, 0), at(150, 50, 1));

  EXPECT_EQ(golden_mismatch(moved, dir / "moved.png", dir / "again.png"), "");
  EXPECT_FALSE(std::filesystem::exists(dir / "again.diff.png"));
  EXPECT_NE(golden_mismatch(moved, dir / "absent.png", dir / "new.png").find("no golden frame"),
            std::string::npos);
}

}  // namespace
}  // namespace spinfold::test
