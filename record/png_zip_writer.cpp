// A zip of PNGs (libzip): frame-000000.png, frame-000001.png, … in order, stored (the PNGs are
// already compressed), every entry dated 1980-01-01 00:00 so that a rerun gives the same bytes.
// libzip writes the archive at finish(), reading each entry's bytes then: each PNG is appended to a
// spill file beside the archive as it is made and its entry reads its piece of that file, so the
// writer holds one frame however long the clip (3600 PNGs of 1920×1080 were ~4 GB held in memory).
#include <zip.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "record/recorder.h"
#include "render/png_encoder.h"

namespace spinfold::record {

namespace {

class PngZipWriter final : public ClipWriter {
 public:
  PngZipWriter(const std::string& path, const ClipWriterSpec& spec)
      : spec_(spec), path_(path), spill_path_(path + ".frames") {
    spill_ = std::fopen(spill_path_.c_str(), "wb");
    if (!spill_)
      throw RecordError("cannot write '" + spill_path_ +
                        "' (the frames until the zip is written): " + std::strerror(errno));
    int error = 0;
    zip_ = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    if (!zip_) {
      zip_error_t e;
      zip_error_init_with_code(&e, error);
      const std::string why = zip_error_strerror(&e);
      zip_error_fini(&e);
      drop_spill();
      throw RecordError("libzip: cannot write '" + path + "': " + why);
    }
  }
  ~PngZipWriter() override {
    if (zip_) zip_discard(zip_);
    drop_spill();
  }

  void add(const std::uint8_t* rgba) override {
    std::vector<render::PngText> texts;
    if (!spec_.provenance.empty()) texts.emplace_back("Source", spec_.provenance);
    const std::vector<std::uint8_t> png = render::encode_png(rgba, spec_.width, spec_.height, texts);
    // Flushed at once: libzip checks the piece against the file's size when the entry is added.
    if (std::fwrite(png.data(), 1, png.size(), spill_) != png.size() || std::fflush(spill_) != 0)
      throw RecordError("cannot write '" + spill_path_ + "': " + std::strerror(errno));
    zip_source_t* source =
        zip_source_file(zip_, spill_path_.c_str(), held_, static_cast<zip_int64_t>(png.size()));
    if (!source) fail();
    char name[32];
    std::snprintf(name, sizeof name, "frame-%06lld.png", frames_);
    const zip_int64_t index = zip_file_add(zip_, name, source, ZIP_FL_ENC_UTF_8);
    if (index < 0) {
      zip_source_free(source);
      fail();
    }
    const auto entry = static_cast<zip_uint64_t>(index);
    if (zip_set_file_compression(zip_, entry, ZIP_CM_STORE, 0) != 0) fail();
    if (zip_file_set_dostime(zip_, entry, 0, (0 << 9) | (1 << 5) | 1, 0) != 0) fail();  // 1980-01-01
    held_ += png.size();
    ++frames_;
  }

  void finish() override {
    if (frames_ == 0) throw RecordError("a zip of PNGs needs at least one frame");
    if (!spec_.provenance.empty() && zip_set_archive_comment(zip_, spec_.provenance.c_str(),
                                                             static_cast<zip_uint16_t>(std::min<std::size_t>(
                                                                 spec_.provenance.size(), 65535))) != 0)
      fail();
    if (zip_close(zip_) != 0) fail();
    zip_ = nullptr;
    drop_spill();
  }

  std::uint64_t bytes() const override { return held_; }

 private:
  [[noreturn]] void fail() {
    throw RecordError("cannot write '" + path_ + "': libzip: " + zip_strerror(zip_));
  }
  void drop_spill() {
    if (spill_) std::fclose(spill_), std::remove(spill_path_.c_str());
    spill_ = nullptr;
  }

  ClipWriterSpec spec_;
  std::string path_;
  std::string spill_path_;
  std::FILE* spill_ = nullptr;
  zip_t* zip_ = nullptr;
  long long frames_ = 0;
  std::uint64_t held_ = 0;  // the spill file's length: the PNGs so far
};

}  // namespace

std::unique_ptr<ClipWriter> open_png_zip(const std::string& path, const ClipWriterSpec& spec) {
  return std::make_unique<PngZipWriter>(path, spec);
}

}  // namespace spinfold::record
