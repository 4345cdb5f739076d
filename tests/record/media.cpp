#include "media.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}
#include <gif_lib.h>
#include <zip.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>

namespace spinfold::record::testing {

GifInfo read_gif(const std::string& path) {
  int error = 0;
  GifFileType* gif = DGifOpenFileName(path.c_str(), &error);
  if (!gif) throw std::runtime_error("giflib cannot open " + path);
  if (DGifSlurp(gif) != GIF_OK) {
    DGifCloseFile(gif, &error);
    throw std::runtime_error("giflib cannot read " + path);
  }
  GifInfo info;
  info.width = gif->SWidth;
  info.height = gif->SHeight;
  info.images = gif->ImageCount;
  info.colors = gif->SColorMap ? gif->SColorMap->ColorCount : 0;
  const auto scan = [&](int count, const ExtensionBlock* blocks) {
    for (int i = 0; i + 1 < count; ++i)
      if (blocks[i].Function == APPLICATION_EXT_FUNC_CODE && blocks[i].ByteCount == 11 &&
          std::memcmp(blocks[i].Bytes, "NETSCAPE2.0", 11) == 0 && blocks[i + 1].ByteCount == 3)
        info.loops_forever =
            blocks[i + 1].Bytes[0] == 1 && blocks[i + 1].Bytes[1] == 0 && blocks[i + 1].Bytes[2] == 0;
  };
  scan(gif->ExtensionBlockCount, gif->ExtensionBlocks);
  for (int i = 0; i < gif->ImageCount; ++i) {
    scan(gif->SavedImages[i].ExtensionBlockCount, gif->SavedImages[i].ExtensionBlocks);
    GraphicsControlBlock gcb{};
    info.delays.push_back(DGifSavedExtensionToGCB(gif, i, &gcb) == GIF_OK ? gcb.DelayTime : -1);
  }
  if (gif->SColorMap) {
    std::vector<std::uint8_t> screen(static_cast<std::size_t>(info.width) * info.height * 4, 0);
    for (int i = 0; i < gif->ImageCount; ++i) {
      const SavedImage& image = gif->SavedImages[i];
      GraphicsControlBlock gcb{};
      gcb.TransparentColor = NO_TRANSPARENT_COLOR;
      DGifSavedExtensionToGCB(gif, i, &gcb);
      long stored = 0;
      for (int y = 0; y < image.ImageDesc.Height; ++y)
        for (int x = 0; x < image.ImageDesc.Width; ++x) {
          const int index = image.RasterBits[y * image.ImageDesc.Width + x];
          if (index == gcb.TransparentColor) continue;
          ++stored;
          const GifColorType c = gif->SColorMap->Colors[index];
          std::uint8_t* p = &screen[4 * ((y + image.ImageDesc.Top) * static_cast<std::size_t>(info.width) +
                                         x + image.ImageDesc.Left)];
          p[0] = c.Red, p[1] = c.Green, p[2] = c.Blue, p[3] = 255;
        }
      info.shown.push_back(screen);
      info.stored.push_back(stored);
    }
    if (!info.shown.empty()) info.first_rgba = info.shown.front();
  }
  DGifCloseFile(gif, &error);
  return info;
}

VideoInfo read_video(const std::string& path, int keep) {
  AVFormatContext* input = nullptr;
  if (avformat_open_input(&input, path.c_str(), nullptr, nullptr) < 0)
    throw std::runtime_error("libavformat cannot open " + path);
  if (avformat_find_stream_info(input, nullptr) < 0) throw std::runtime_error("no stream info in " + path);
  const int index = av_find_best_stream(input, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  if (index < 0) throw std::runtime_error("no video stream in " + path);
  AVStream* stream = input->streams[index];
  const AVCodec* codec = avcodec_find_decoder(stream->codecpar->codec_id);
  AVCodecContext* decoder = avcodec_alloc_context3(codec);
  avcodec_parameters_to_context(decoder, stream->codecpar);
  decoder->thread_count = 1;
  if (avcodec_open2(decoder, codec, nullptr) < 0) throw std::runtime_error("cannot open the decoder");
  VideoInfo info;
  info.codec = avcodec_get_name(stream->codecpar->codec_id);
  info.width = stream->codecpar->width;
  info.height = stream->codecpar->height;
  info.duration =
      input->duration == AV_NOPTS_VALUE ? 0.0 : static_cast<double>(input->duration) / AV_TIME_BASE;
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  const auto receive = [&] {
    while (avcodec_receive_frame(decoder, frame) == 0) {
      if (static_cast<int>(info.pts.size()) == keep) {
        info.rgba.assign(static_cast<std::size_t>(info.width) * info.height * 4, 0);
        SwsContext* sws = sws_getContext(
            frame->width, frame->height, static_cast<AVPixelFormat>(frame->format), info.width, info.height,
            AV_PIX_FMT_RGBA, SWS_BILINEAR | SWS_ACCURATE_RND | SWS_BITEXACT, nullptr, nullptr, nullptr);
        std::uint8_t* out[1] = {info.rgba.data()};
        const int stride[1] = {4 * info.width};
        sws_scale(sws, frame->data, frame->linesize, 0, frame->height, out, stride);
        sws_freeContext(sws);
      }
      info.pts.push_back(static_cast<double>(frame->best_effort_timestamp) * av_q2d(stream->time_base));
    }
  };
  while (av_read_frame(input, packet) == 0) {
    if (packet->stream_index == index) {
      ++info.packets;
      avcodec_send_packet(decoder, packet);
      receive();
    }
    av_packet_unref(packet);
  }
  avcodec_send_packet(decoder, nullptr);
  receive();
  av_frame_free(&frame);
  av_packet_free(&packet);
  avcodec_free_context(&decoder);
  avformat_close_input(&input);
  return info;
}

std::vector<std::string> zip_names(const std::string& path) {
  int error = 0;
  zip_t* zip = zip_open(path.c_str(), ZIP_RDONLY, &error);
  if (!zip) throw std::runtime_error("libzip cannot open " + path);
  std::vector<std::string> names;
  const zip_int64_t n = zip_get_num_entries(zip, 0);
  for (zip_int64_t i = 0; i < n; ++i) names.emplace_back(zip_get_name(zip, static_cast<zip_uint64_t>(i), 0));
  zip_discard(zip);
  return names;
}

std::vector<std::uint8_t> zip_entry(const std::string& path, const std::string& name) {
  int error = 0;
  zip_t* zip = zip_open(path.c_str(), ZIP_RDONLY, &error);
  if (!zip) throw std::runtime_error("libzip cannot open " + path);
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat(zip, name.c_str(), 0, &st) != 0) throw std::runtime_error("no entry " + name);
  std::vector<std::uint8_t> bytes(st.size);
  zip_file_t* file = zip_fopen(zip, name.c_str(), 0);
  zip_fread(file, bytes.data(), bytes.size());
  zip_fclose(file);
  zip_discard(zip);
  return bytes;
}

std::vector<std::uint8_t> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

double psnr_rgb(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  if (a.size() != b.size() || a.empty()) return 0.0;
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = static_cast<double>(a[i]) - b[i];
    sum += d * d;
    ++n;
  }
  if (sum == 0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(255.0 * 255.0 / (sum / static_cast<double>(n)));
}

}  // namespace spinfold::record::testing
