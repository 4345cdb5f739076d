// WebM/VP9 and MP4/H.264 through FFmpeg's libavformat (the muxer) and libavcodec (libvpx-vp9,
// libx264): one well-kept library for both containers and both encoders (docs/recording.md).
// Single-threaded encoders and the bit-exact flags, so that a rerun gives the same bytes as far as
// the encoder allows. RGBA is converted to 4:2:0 (BT.601, limited range, tagged so) by libswscale.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/dict.h>
#include <libavutil/error.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <string>

#include "record/recorder.h"

namespace spinfold::record {

namespace {

std::string av_message(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

class VideoWriter final : public ClipWriter {
 public:
  VideoWriter(Format format, const std::string& path, const ClipWriterSpec& spec) : spec_(spec), path_(path) {
    const bool webm = format == Format::webm;
    const char* muxer = webm ? "webm" : "mp4";
    const char* encoder = webm ? "libvpx-vp9" : "libx264";
    av_log_set_level(AV_LOG_ERROR);  // libx264's statistics and the muxers' notes are not ours to print
    try {
      check(avformat_alloc_output_context2(&output_, nullptr, muxer, path.c_str()), "the muxer");
      const AVCodec* codec = avcodec_find_encoder_by_name(encoder);
      if (!codec) throw RecordError(std::string("FFmpeg has no encoder ") + encoder);
      stream_ = avformat_new_stream(output_, nullptr);
      codec_ = avcodec_alloc_context3(codec);
      frame_ = av_frame_alloc();
      packet_ = av_packet_alloc();
      if (!stream_ || !codec_ || !frame_ || !packet_) throw RecordError("FFmpeg: out of memory");
      const AVRational rate = av_d2q(spec.fps, 100000);
      codec_->width = spec.width;
      codec_->height = spec.height;
      codec_->pix_fmt = AV_PIX_FMT_YUV420P;
      codec_->framerate = rate;
      codec_->time_base = av_inv_q(rate);
      codec_->gop_size = static_cast<int>(spec.fps * 2 + 0.5);  // a key frame every 2 s: seekable
      codec_->thread_count = 1;                                 // deterministic output
      codec_->flags |= AV_CODEC_FLAG_BITEXACT;
      codec_->colorspace = AVCOL_SPC_SMPTE170M;
      codec_->color_primaries = AVCOL_PRI_SMPTE170M;
      codec_->color_trc = AVCOL_TRC_SMPTE170M;
      codec_->color_range = AVCOL_RANGE_MPEG;
      if (output_->oformat->flags & AVFMT_GLOBALHEADER) codec_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
      AVDictionary* options = nullptr;
      if (webm) {
        // Realtime mode at the fastest speed: a 10 s 640×480 clip well under 10 s on one core;
        // constant quality (crf with no bit-rate target).
        codec_->bit_rate = 0;
        av_dict_set(&options, "deadline", "realtime", 0);
        av_dict_set(&options, "cpu-used", "8", 0);
        av_dict_set(&options, "crf", "30", 0);
        av_dict_set(&options, "row-mt", "0", 0);
        // No look-ahead (libvpx keeps 25 frames by default): 100 MiB less at 1920×1080, the same
        // file size here (bench/limit_memory.py webm: 412 → 309 MiB at its peak).
        av_dict_set(&options, "lag-in-frames", "0", 0);
      } else {
        av_dict_set(&options, "preset", "veryfast", 0);
        av_dict_set(&options, "crf", "20", 0);
      }
      const int opened = avcodec_open2(codec_, codec, &options);
      av_dict_free(&options);
      check(opened, encoder);
      check(avcodec_parameters_from_context(stream_->codecpar, codec_), "the stream parameters");
      stream_->time_base = codec_->time_base;
      stream_->avg_frame_rate = rate;
      output_->flags |= AVFMT_FLAG_BITEXACT;
      check(avio_open(&output_->pb, path.c_str(), AVIO_FLAG_WRITE), "opening the file");
      if (!spec.provenance.empty()) av_dict_set(&output_->metadata, "comment", spec.provenance.c_str(), 0);
      AVDictionary* mux_options = nullptr;
      if (!webm) av_dict_set(&mux_options, "movflags", "+faststart", 0);  // playable while loading
      const int header = avformat_write_header(output_, &mux_options);
      av_dict_free(&mux_options);
      check(header, "the container header");
      frame_->format = AV_PIX_FMT_YUV420P;
      frame_->width = spec.width;
      frame_->height = spec.height;
      check(av_frame_get_buffer(frame_, 0), "the frame buffer");
      scaler_ = sws_getContext(spec.width, spec.height, AV_PIX_FMT_RGBA, spec.width, spec.height,
                               AV_PIX_FMT_YUV420P, SWS_BILINEAR | SWS_ACCURATE_RND | SWS_BITEXACT, nullptr,
                               nullptr, nullptr);
      if (!scaler_) throw RecordError("libswscale cannot convert RGBA to YUV 4:2:0");
    } catch (const RecordError& e) {
      release();
      throw RecordError("cannot write '" + path + "': " + e.what());
    } catch (...) {
      release();
      throw;
    }
  }
  ~VideoWriter() override { release(); }

  void add(const std::uint8_t* rgba) override {
    try {
      encode(rgba);
    } catch (const RecordError& e) {
      throw RecordError("cannot write '" + path_ + "': " + e.what());
    }
  }

  void finish() override {
    if (frames_ == 0) throw RecordError("a video needs at least one frame");
    try {
      flush_and_close();
    } catch (const RecordError& e) {
      throw RecordError("cannot write '" + path_ + "': " + e.what());
    }
  }

  std::uint64_t bytes() const override {
    return output_ && output_->pb ? static_cast<std::uint64_t>(avio_tell(output_->pb)) : written_;
  }

 private:
  void encode(const std::uint8_t* rgba) {
    check(av_frame_make_writable(frame_), "the frame buffer");
    const std::uint8_t* source[1] = {rgba};
    const int stride[1] = {4 * spec_.width};
    sws_scale(scaler_, source, stride, 0, spec_.height, frame_->data, frame_->linesize);
    frame_->pts = frames_++;
    check(avcodec_send_frame(codec_, frame_), "the encoder");
    drain();
  }

  void flush_and_close() {
    check(avcodec_send_frame(codec_, nullptr), "the encoder");
    drain();
    check(av_write_trailer(output_), "the container trailer");
    // avio buffers: a write the system refused shows in its error flag, and at the flush.
    avio_flush(output_->pb);
    check(output_->pb->error, "writing the file");
    written_ = static_cast<std::uint64_t>(avio_tell(output_->pb));
    check(avio_closep(&output_->pb), "closing the file");
  }

  static void check(int code, const char* what) {
    if (code < 0) throw RecordError(std::string("FFmpeg: ") + what + ": " + av_message(code));
  }

  // Writes every packet the encoder has ready.
  void drain() {
    for (;;) {
      const int got = avcodec_receive_packet(codec_, packet_);
      if (got == AVERROR(EAGAIN) || got == AVERROR_EOF) return;
      check(got, "the encoder");
      if (packet_->duration == 0) packet_->duration = 1;  // one frame [codec time base]
      av_packet_rescale_ts(packet_, codec_->time_base, stream_->time_base);
      packet_->stream_index = stream_->index;
      check(av_interleaved_write_frame(output_, packet_), "the muxer");
    }
  }

  void release() {
    sws_freeContext(scaler_);
    scaler_ = nullptr;
    av_packet_free(&packet_);
    av_frame_free(&frame_);
    avcodec_free_context(&codec_);
    if (output_ && output_->pb) avio_closep(&output_->pb);
    avformat_free_context(output_);
    output_ = nullptr;
  }

  ClipWriterSpec spec_;
  std::string path_;
  AVFormatContext* output_ = nullptr;
  AVStream* stream_ = nullptr;
  AVCodecContext* codec_ = nullptr;
  AVFrame* frame_ = nullptr;
  AVPacket* packet_ = nullptr;
  SwsContext* scaler_ = nullptr;
  std::int64_t frames_ = 0;
  std::uint64_t written_ = 0;  // the file's size, once finished
};

}  // namespace

std::unique_ptr<ClipWriter> open_video(Format format, const std::string& path, const ClipWriterSpec& spec) {
  return std::make_unique<VideoWriter>(format, path, spec);
}

}  // namespace spinfold::record
