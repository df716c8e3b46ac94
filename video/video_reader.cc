#include "video/video_reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libswscale/swscale.h>
}

#include "common/error.h"

namespace m4mesh {

static_assert(sizeof(Rgb) == 3, "Image rows are copied as packed RGB");

namespace {

// Sizes past this are refused before any picture is allocated.
constexpr int kMaxCodedSide = 8192;

std::string av_reason(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

}  // namespace

struct VideoReader::State {
  std::string path;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  SwsContext* scaler = nullptr;
  AVPacket* packet = nullptr;
  AVFrame* decoded = nullptr;
  AVFrame* rgb = nullptr;
  int stream = -1;
  bool flushing = false;
  int64_t frames = 0;
  VideoInfo info;

  ~State() {
    sws_freeContext(scaler);
    av_frame_free(&rgb);
    av_frame_free(&decoded);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
    avformat_close_input(&format);
  }

  [[noreturn]] void fail(ErrorKind kind, const std::string& what, int code) const {
    throw Error(kind, "", kNoPlane, kNoOffset, path + ": " + what + (code < 0 ? ": " + av_reason(code) : ""));
  }
  [[noreturn]] void damaged(int code) const { fail(ErrorKind::kInput, "frame " + std::to_string(frames) + " cannot be decoded", code); }
};

VideoReader::VideoReader(const std::string& path, uint32_t max_side) : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.path = path;
  av_log_set_level(AV_LOG_QUIET);
  if (int r = avformat_open_input(&s.format, path.c_str(), nullptr, nullptr); r < 0)
    s.fail(r == AVERROR(ENOENT) || r == AVERROR(EACCES) ? ErrorKind::kIo : ErrorKind::kInput, "not a video FFmpeg can read", r);
  if (int r = avformat_find_stream_info(s.format, nullptr); r < 0) s.fail(ErrorKind::kInput, "no stream information", r);
  const AVCodec* decoder = nullptr;
  s.stream = av_find_best_stream(s.format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (s.stream < 0) s.fail(ErrorKind::kInput, s.stream == AVERROR_DECODER_NOT_FOUND ? "no decoder for its video" : "no video stream", s.stream);
  const AVCodecParameters* parameters = s.format->streams[s.stream]->codecpar;
  if (parameters->width <= 0 || parameters->height <= 0 || parameters->width > kMaxCodedSide || parameters->height > kMaxCodedSide)
    s.fail(ErrorKind::kInput,
           "a " + std::to_string(parameters->width) + " × " + std::to_string(parameters->height) + " picture (1 … " +
               std::to_string(kMaxCodedSide) + " pixels a side)",
           0);
  s.codec = avcodec_alloc_context3(decoder);
  s.packet = av_packet_alloc();
  s.decoded = av_frame_alloc();
  s.rgb = av_frame_alloc();
  if (!s.codec || !s.packet || !s.decoded || !s.rgb) throw std::bad_alloc();
  if (int r = avcodec_parameters_to_context(s.codec, parameters); r < 0) s.fail(ErrorKind::kInput, "bad codec parameters", r);
  // A damaged packet is an error, not a concealed picture.
  s.codec->err_recognition |= AV_EF_EXPLODE;
  s.codec->thread_count = 1;
  if (int r = avcodec_open2(s.codec, decoder, nullptr); r < 0) s.fail(ErrorKind::kInput, "cannot open its decoder", r);

  VideoInfo& info = s.info;
  info.codec = decoder->name;
  info.coded_width = static_cast<uint32_t>(parameters->width);
  info.coded_height = static_cast<uint32_t>(parameters->height);
  const double scale = std::min(1.0, static_cast<double>(std::max<uint32_t>(max_side, 1)) / std::max(info.coded_width, info.coded_height));
  info.width = std::max<uint32_t>(1, static_cast<uint32_t>(std::lround(info.coded_width * scale)));
  info.height = std::max<uint32_t>(1, static_cast<uint32_t>(std::lround(info.coded_height * scale)));
  const AVRational rate = av_guess_frame_rate(s.format, s.format->streams[s.stream], nullptr);
  if (rate.num > 0 && rate.den > 0) info.fps = av_q2d(rate);
  info.frames = std::max<int64_t>(0, s.format->streams[s.stream]->nb_frames);
  s.rgb->format = AV_PIX_FMT_RGB24;
  s.rgb->width = static_cast<int>(info.width);
  s.rgb->height = static_cast<int>(info.height);
  if (av_frame_get_buffer(s.rgb, 0) < 0) throw std::bad_alloc();
}

VideoReader::~VideoReader() = default;

const VideoInfo& VideoReader::info() const { return state_->info; }
int64_t VideoReader::frames_read() const { return state_->frames; }

bool VideoReader::next(Image& frame) {
  State& s = *state_;
  for (;;) {
    const int received = avcodec_receive_frame(s.codec, s.decoded);
    if (received == AVERROR_EOF) return false;
    if (received == 0) break;
    if (received != AVERROR(EAGAIN)) s.damaged(received);
    if (s.flushing) return false;
    const int read = av_read_frame(s.format, s.packet);
    if (read == AVERROR_EOF) {
      s.flushing = true;
      if (int r = avcodec_send_packet(s.codec, nullptr); r < 0 && r != AVERROR_EOF) s.damaged(r);
      continue;
    }
    if (read < 0) s.fail(ErrorKind::kInput, "cannot read past frame " + std::to_string(s.frames), read);
    const bool ours = s.packet->stream_index == s.stream;
    const int sent = ours ? avcodec_send_packet(s.codec, s.packet) : 0;
    av_packet_unref(s.packet);
    if (sent < 0 && sent != AVERROR(EAGAIN)) s.damaged(sent);
  }
  const VideoInfo& info = s.info;
  if (s.decoded->width != static_cast<int>(info.coded_width) || s.decoded->height != static_cast<int>(info.coded_height) || s.decoded->format < 0)
    s.fail(ErrorKind::kInput,
           "frame " + std::to_string(s.frames) + " is " + std::to_string(s.decoded->width) + " × " + std::to_string(s.decoded->height) +
               ", the video " + std::to_string(info.coded_width) + " × " + std::to_string(info.coded_height) + " (a size change is not supported)",
           0);
  s.scaler = sws_getCachedContext(s.scaler, s.decoded->width, s.decoded->height, static_cast<AVPixelFormat>(s.decoded->format),
                                  static_cast<int>(info.width), static_cast<int>(info.height), AV_PIX_FMT_RGB24,
                                  SWS_AREA | SWS_ACCURATE_RND | SWS_BITEXACT, nullptr, nullptr, nullptr);
  if (!s.scaler) s.fail(ErrorKind::kInput, "frame " + std::to_string(s.frames) + ": no conversion to RGB from its pixel format", 0);
  if (int r = av_frame_make_writable(s.rgb); r < 0) throw std::bad_alloc();
  sws_scale(s.scaler, s.decoded->data, s.decoded->linesize, 0, s.decoded->height, s.rgb->data, s.rgb->linesize);
  av_frame_unref(s.decoded);
  frame = Image(info.width, info.height);
  for (uint32_t y = 0; y < info.height; ++y)
    std::memcpy(&frame.at(0, y), s.rgb->data[0] + static_cast<ptrdiff_t>(y) * s.rgb->linesize[0], size_t{info.width} * 3);
  ++s.frames;
  return true;
}

}  // namespace m4mesh
