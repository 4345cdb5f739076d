// GIF (giflib 5.2): one palette for the whole recording, chosen by median cut (GifQuantizeBuffer)
// over sample frames spread across the clip, then refined at full precision by a few rounds of
// k-means over the samples' colours (the median cut works on 5 bits a channel, which bands and
// tints the shaded surface). A colour at a palette entry is that entry (a flat colour stays one
// index in every frame); a colour between entries is an ordered (8x8 Bayer) mix of its two nearest,
// in the proportion that keeps the local mean, so a gradient does not band. The dither is fixed to
// the pixel's place, so a still pixel keeps its index from frame to frame (no crawling noise).
// Each frame after the first stores only the rectangle that changed, and in it every pixel that did
// not change as the transparent index (long runs LZW packs small; disposal: leave in place).
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
constexpr int kColors = 256;               // the colour table's size
constexpr int kTransparent = kColors - 1;  // its last entry: "as in the previous frame"
constexpr int kShades = kColors - 1;       // the entries that are colours
// A colour within this squared RGB distance of its nearest entry is that entry, undithered: a
// flat colour the k-means moved its entry a level or two away from stays flat.
constexpr int kSnap = 12;

// The 8x8 Bayer matrix: thresholds (b + 0.5) / 64 laid out so that any mix is spread evenly.
constexpr std::array<std::uint8_t, 64> kBayer = {
    0,  32, 8,  40, 2,  34, 10, 42, 48, 16, 56, 24, 50, 18, 58, 26, 12, 44, 4,  36, 14, 46,
    6,  38, 60, 28, 52, 20, 62, 30, 54, 22, 3,  35, 11, 43, 1,  33, 9,  41, 51, 19, 59, 27,
    49, 17, 57, 25, 15, 47, 7,  39, 13, 45, 5,  37, 63, 31, 55, 23, 61, 29, 53, 21};

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
    Mix mix{};
    for (int y = 0; y < spec_.height; ++y)
      for (int x = 0; x < spec_.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * spec_.width + x;
        const std::uint32_t color = static_cast<std::uint32_t>(rgba[4 * i]) << 16 |
                                    static_cast<std::uint32_t>(rgba[4 * i + 1]) << 8 | rgba[4 * i + 2];
        if (color != last_color) {
          last_color = color;
          mix = mix_of(color);
        }
        index[i] = kBayer[(y & 7) * 8 + (x & 7)] < mix.share ? mix.second : mix.first;
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
    gcb.TransparentColor = frames_ > 0 ? kTransparent : NO_TRANSPARENT_COLOR;
    GifByteType extension[4];
    const std::size_t length = EGifGCBToExtension(&gcb, extension);
    check(EGifPutExtension(gif_, GRAPHICS_EXT_FUNC_CODE, static_cast<int>(length), extension));
    const int width = right - left + 1, height = bottom - top + 1;
    check(EGifPutImageDesc(gif_, left, top, width, height, false, nullptr));
    std::vector<GifByteType> line(static_cast<std::size_t>(width));
    for (int y = top; y <= bottom; ++y) {
      const std::size_t row = static_cast<std::size_t>(y) * spec_.width + left;
      for (int x = 0; x < width; ++x)
        line[x] = frames_ > 0 && index[row + x] == previous_[row + x] ? kTransparent : index[row + x];
      check(EGifPutLine(gif_, line.data(), width));
    }
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
    int count = kShades;
    if (GifQuantizeBuffer(static_cast<unsigned>(red_.size()), 1, &count, red_.data(), green_.data(),
                          blue_.data(), discarded.data(), colors.data()) != GIF_OK)
      throw RecordError("giflib: the palette could not be chosen");
    palette_.assign(colors.begin(), colors.begin() + kShades);
    refine_palette();
    red_ = {}, green_ = {}, blue_ = {};
    for (int i = 0; i < kShades; ++i) colors[i] = palette_[i];
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
      std::vector<std::array<std::uint64_t, 4>> sums(kShades, {0, 0, 0, 0});
      for (const auto& [color, count] : colors) {
        auto& sum = sums[nearest(color)];
        sum[0] += static_cast<std::uint64_t>(color >> 16) * count;
        sum[1] += static_cast<std::uint64_t>(color >> 8 & 0xff) * count;
        sum[2] += static_cast<std::uint64_t>(color & 0xff) * count;
        sum[3] += count;
      }
      for (int i = 0; i < kShades; ++i) {
        if (sums[i][3] == 0) continue;
        const auto mean = [&](int c) {
          return static_cast<GifByteType>((sums[i][c] + sums[i][3] / 2) / sums[i][3]);
        };
        palette_[i] = GifColorType{mean(0), mean(1), mean(2)};
      }
    }
  }

  static int distance2(std::uint32_t color, const GifColorType& entry) {
    const int dr = static_cast<int>(color >> 16) - entry.Red;
    const int dg = static_cast<int>(color >> 8 & 0xff) - entry.Green;
    const int db = static_cast<int>(color & 0xff) - entry.Blue;
    return dr * dr + dg * dg + db * db;
  }

  // The palette index nearest to a colour (squared RGB distance; ties to the lower index).
  GifByteType nearest(std::uint32_t color) const {
    int best = 0, best_distance = 1 << 30;
    for (int i = 0; i < kShades; ++i)
      if (const int d = distance2(color, palette_[i]); d < best_distance) best = i, best_distance = d;
    return static_cast<GifByteType>(best);
  }

  // How a colour is drawn: its nearest entry, or a mix of two entries near it, the second on the
  // pixels whose Bayer threshold is below its share (64ths). The pair and share are the ones whose
  // mean is nearest the colour, counting the mix's own noise (the variance t(1-t)|a-b|^2, weighted
  // by kNoise) against it, among the kNear entries nearest the colour: two entries across a cell
  // of the palette, not only its two nearest, so a colour is reached from any side. Cached.
  struct Mix {
    GifByteType first = 0, second = 0;
    int share = 0;  // of 64 pixels, how many take the second
  };
  Mix mix_of(std::uint32_t color) {
    if (const auto it = cache_.find(color); it != cache_.end()) return it->second;
    constexpr int kNear = 8;
    constexpr double kNoise = 0.1;
    std::array<std::pair<int, int>, kNear> near;  // (squared distance, entry), nearest first
    near.fill({1 << 30, 0});
    for (int i = 0; i < kShades; ++i) {
      const int d = distance2(color, palette_[i]);
      if (d >= near.back().first) continue;
      int j = kNear - 1;
      for (; j > 0 && near[j - 1].first > d; --j) near[j] = near[j - 1];
      near[j] = {d, i};
    }
    Mix mix{static_cast<GifByteType>(near[0].second), static_cast<GifByteType>(near[0].second), 0};
    if (near[0].first > kSnap) {
      const double x[3] = {static_cast<double>(color >> 16), static_cast<double>(color >> 8 & 0xff),
                           static_cast<double>(color & 0xff)};
      double best = near[0].first;
      for (int i = 0; i < kNear; ++i)
        for (int j = i + 1; j < kNear; ++j) {
          if (near[j].first >= (1 << 30)) continue;
          const GifColorType &a = palette_[near[i].second], &b = palette_[near[j].second];
          const double e[3] = {static_cast<double>(b.Red - a.Red), static_cast<double>(b.Green - a.Green),
                               static_cast<double>(b.Blue - a.Blue)};
          const double p[3] = {x[0] - a.Red, x[1] - a.Green, x[2] - a.Blue};
          const double length2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
          if (length2 == 0) continue;
          const double along = (p[0] * e[0] + p[1] * e[1] + p[2] * e[2]) / length2;
          const int share = static_cast<int>(std::lround(64.0 * std::clamp(along, 0.0, 1.0)));
          const double t = share / 64.0;
          double miss = 0;
          for (int c = 0; c < 3; ++c) miss += (p[c] - t * e[c]) * (p[c] - t * e[c]);
          const double cost = miss + kNoise * t * (1 - t) * length2;
          if (cost < best)
            best = cost, mix = Mix{static_cast<GifByteType>(near[i].second),
                                   static_cast<GifByteType>(near[j].second), share};
        }
    }
    cache_.emplace(color, mix);
    return mix;
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
  std::unordered_map<std::uint32_t, Mix> cache_;
  std::vector<GifByteType> previous_;
};

}  // namespace

std::unique_ptr<ClipWriter> open_gif(const std::string& path, const ClipWriterSpec& spec) {
  return std::make_unique<GifWriter>(path, spec);
}

}  // namespace spinfold::record
