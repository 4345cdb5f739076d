// GIF (giflib 5.2): one palette for the whole recording, chosen by median cut (GifQuantizeBuffer)
// over sample frames spread across the clip, then refined at full precision by a few rounds of
// k-means over the samples' colours (the median cut works on 5 bits a channel, which bands and
// tints the shaded surface), and every pixel mapped to its nearest palette colour
// without dithering, so a flat colour stays one index in every frame (no crawling dither noise).
// Each frame after the first stores only the rectangle that changed (disposal: leave in place).
// Loops forever (the NETSCAPE2.0 application extension). Byte-identical for identical frames.
#include <gif_lib.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include "record/recorder.h"

namespace spinfold::record {

namespace {

constexpr int kPaletteSamples = 8;
constexpr int kColors = 256;

class GifWriter final : public ClipWriter {
 public:
  GifWriter(const std::string& path, const ClipWriterSpec& spec) : spec_(spec), path_(path) {
    file_ = std::fopen(path.c_str(), "wb");
    if (!file_) throw RecordError("cannot write '" + path + "': " + std::strerror(errno));
    int error = 0;
    gif_ = EGifOpen(this, &GifWriter::write, &error);
    if (!gif_) {
      std::fclose(file_);
      throw RecordError(std::string("giflib: ") + GifErrorString(error));
    }
    pixels_ = static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height);
  }
  ~GifWriter() override {
    if (gif_) EGifCloseFile(gif_, nullptr);
    if (file_) std::fclose(file_);
  }

  int palette_samples() const override { return kPaletteSamples; }

  void add_palette_sample(const std::uint8_t* rgba) override {
    for (std::size_t i = 0; i < pixels_; ++i) {
      red_.push_back(rgba[4 * i]);
      green_.push_back(rgba[4 * i + 1]);
      blue_.push_back(rgba[4 * i + 2]);
    }
  }

  void add(const std::uint8_t* rgba) override {
    if (frames_ == 0) start(rgba);
    std::vector<GifByteType> index(pixels_);
    std::uint32_t last_color = 0xffffffffu;
    GifByteType last_index = 0;
    for (std::size_t i = 0; i < pixels_; ++i) {
      const std::uint32_t color = static_cast<std::uint32_t>(rgba[4 * i]) << 16 |
                                  static_cast<std::uint32_t>(rgba[4 * i + 1]) << 8 | rgba[4 * i + 2];
      if (color != last_color) {
        last_color = color;
        last_index = nearest(color);
      }
      index[i] = last_index;
    }
    // The rectangle that differs from the previous frame (all of the first).
    int left = 0, top = 0, right = spec_.width - 1, bottom = spec_.height - 1;
    if (frames_ > 0) {
      left = spec_.width, top = spec_.height, right = -1, bottom = -1;
      for (int y = 0; y < spec_.height; ++y)
        for (int x = 0; x < spec_.width; ++x) {
          const std::size_t i = static_cast<std::size_t>(y) * spec_.width + x;
          if (index[i] == previous_[i]) continue;
          left = std::min(left, x), right = std::max(right, x);
          top = std::min(top, y), bottom = std::max(bottom, y);
        }
      if (right < 0) left = top = right = bottom = 0;  // unchanged: one pixel, redrawn as it was
    }
    // Delays in hundredths of a second, rounded so that frame k starts at round(100·k / fps).
    const auto start_cs = [&](long long k) {
      return std::llround(100.0 * static_cast<double>(k) / spec_.fps);
    };
    GraphicsControlBlock gcb{};
    gcb.DisposalMode = DISPOSE_DO_NOT;
    gcb.UserInputFlag = false;
    gcb.DelayTime = static_cast<int>(start_cs(frames_ + 1) - start_cs(frames_));
    gcb.TransparentColor = NO_TRANSPARENT_COLOR;
    GifByteType extension[4];
    const std::size_t length = EGifGCBToExtension(&gcb, extension);
    check(EGifPutExtension(gif_, GRAPHICS_EXT_FUNC_CODE, static_cast<int>(length), extension));
    const int width = right - left + 1, height = bottom - top + 1;
    check(EGifPutImageDesc(gif_, left, top, width, height, false, nullptr));
    for (int y = top; y <= bottom; ++y)
      check(EGifPutLine(gif_, index.data() + static_cast<std::size_t>(y) * spec_.width + left, width));
    previous_ = std::move(index);
    ++frames_;
  }

  void finish() override {
    if (frames_ == 0) throw RecordError("a GIF needs at least one frame");
    int error = 0;
    const int closed = EGifCloseFile(gif_, &error);
    gif_ = nullptr;
    const bool flushed = std::fclose(file_) == 0;
    file_ = nullptr;
    if (closed != GIF_OK) throw RecordError(where() + "giflib: " + GifErrorString(error));
    if (!flushed) throw RecordError(where() + std::strerror(write_errno_ ? write_errno_ : errno));
  }

  std::uint64_t bytes() const override { return written_; }

 private:
  static int write(GifFileType* gif, const GifByteType* data, int length) {
    auto* self = static_cast<GifWriter*>(gif->UserData);
    errno = 0;
    const std::size_t n = std::fwrite(data, 1, static_cast<std::size_t>(length), self->file_);
    if (n != static_cast<std::size_t>(length) && self->write_errno_ == 0) self->write_errno_ = errno;
    self->written_ += n;
    return static_cast<int>(n);
  }

  // Every error names the file; a write the system refused, its reason (errno).
  std::string where() const { return "cannot write '" + path_ + "': "; }
  void check(int status) {
    if (status == GIF_OK) return;
    if (write_errno_ != 0) throw RecordError(where() + std::strerror(write_errno_));
    throw RecordError(where() + "giflib: " + GifErrorString(gif_->Error));
  }

  // The palette (from the samples, or from the first frame when none were given), the screen
  // descriptor and the loop extension.
  void start(const std::uint8_t* first) {
    if (red_.empty()) add_palette_sample(first);
    std::vector<GifColorType> colors(kColors, GifColorType{0, 0, 0});
    std::vector<GifByteType> discarded(red_.size());
    int count = kColors;
    if (GifQuantizeBuffer(static_cast<unsigned>(red_.size()), 1, &count, red_.data(), green_.data(),
                          blue_.data(), discarded.data(), colors.data()) != GIF_OK)
      throw RecordError("giflib: the palette could not be chosen");
    palette_.assign(colors.begin(), colors.end());
    refine_palette();
    red_ = {}, green_ = {}, blue_ = {};
    for (int i = 0; i < kColors; ++i) colors[i] = palette_[i];
    ColorMapObject* map = GifMakeMapObject(kColors, colors.data());
    if (!map) throw RecordError("giflib: out of memory");
    EGifSetGifVersion(gif_, true);
    const int status = EGifPutScreenDesc(gif_, spec_.width, spec_.height, 8, 0, map);
    GifFreeMapObject(map);
    check(status);
    // NETSCAPE2.0: sub-block 1 holds the loop count, 0 = forever.
    check(EGifPutExtensionLeader(gif_, APPLICATION_EXT_FUNC_CODE));
    check(EGifPutExtensionBlock(gif_, 11, "NETSCAPE2.0"));
    const GifByteType loop[3] = {1, 0, 0};
    check(EGifPutExtensionBlock(gif_, 3, loop));
    check(EGifPutExtensionTrailer(gif_));
    if (!spec_.provenance.empty()) check(EGifPutComment(gif_, spec_.provenance.c_str()));
  }

  // Lloyd's k-means over the samples' distinct colours (weighted by their counts), seeded by the
  // median cut: each entry moves to the mean of the colours nearest to it. Deterministic (colours
  // visited in sorted order, integer sums); entries nobody is nearest to stay where they are.
  void refine_palette() {
    std::unordered_map<std::uint32_t, std::uint32_t> counts;
    for (std::size_t i = 0; i < red_.size(); ++i)
      ++counts[static_cast<std::uint32_t>(red_[i]) << 16 | static_cast<std::uint32_t>(green_[i]) << 8 |
               blue_[i]];
    std::vector<std::pair<std::uint32_t, std::uint32_t>> colors(counts.begin(), counts.end());
    std::sort(colors.begin(), colors.end());
    constexpr int kRounds = 6;
    for (int round = 0; round < kRounds; ++round) {
      cache_.clear();
      std::vector<std::array<std::uint64_t, 4>> sums(kColors, {0, 0, 0, 0});
      for (const auto& [color, count] : colors) {
        auto& sum = sums[nearest(color)];
        sum[0] += static_cast<std::uint64_t>(color >> 16) * count;
        sum[1] += static_cast<std::uint64_t>(color >> 8 & 0xff) * count;
        sum[2] += static_cast<std::uint64_t>(color & 0xff) * count;
        sum[3] += count;
      }
      for (int i = 0; i < kColors; ++i) {
        if (sums[i][3] == 0) continue;
        const auto mean = [&](int c) {
          return static_cast<GifByteType>((sums[i][c] + sums[i][3] / 2) / sums[i][3]);
        };
        palette_[i] = GifColorType{mean(0), mean(1), mean(2)};
      }
    }
    cache_.clear();
  }

  // The palette index nearest to a colour (squared RGB distance; ties to the lower index), cached.
  GifByteType nearest(std::uint32_t color) {
    if (const auto it = cache_.find(color); it != cache_.end()) return it->second;
    const int r = static_cast<int>(color >> 16), g = static_cast<int>(color >> 8 & 0xff),
              b = static_cast<int>(color & 0xff);
    int best = 0, best_distance = 1 << 30;
    for (int i = 0; i < kColors; ++i) {
      const int dr = r - palette_[i].Red, dg = g - palette_[i].Green, db = b - palette_[i].Blue;
      const int distance = dr * dr + dg * dg + db * db;
      if (distance < best_distance) best = i, best_distance = distance;
    }
    cache_.emplace(color, static_cast<GifByteType>(best));
    return static_cast<GifByteType>(best);
  }

  ClipWriterSpec spec_;
  std::string path_;
  int write_errno_ = 0;  // the first write the system refused
  std::FILE* file_ = nullptr;
  GifFileType* gif_ = nullptr;
  std::size_t pixels_ = 0;
  long long frames_ = 0;
  std::uint64_t written_ = 0;
  std::vector<GifByteType> red_, green_, blue_;  // palette samples, one plane each
  std::vector<GifColorType> palette_;
  std::unordered_map<std::uint32_t, GifByteType> cache_;
  std::vector<GifByteType> previous_;
};

}  // namespace

std::unique_ptr<ClipWriter> open_gif(const std::string& path, const ClipWriterSpec& spec) {
  return std::make_unique<GifWriter>(path, spec);
}

}  // namespace spinfold::record
