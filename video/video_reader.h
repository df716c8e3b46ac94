// Video in: any container and codec Debian's FFmpeg libraries read, and
// image sequences by FFmpeg's pattern (frames/%04d.png), frame by frame as
// RGB pictures. Frames wider or taller than `max_side` are scaled down
// (aspect kept) by libswscale.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "render/image.h"

namespace m4mesh {

struct VideoInfo {
  uint32_t coded_width = 0, coded_height = 0;  // as stored
  uint32_t width = 0, height = 0;              // as delivered
  double fps = 0;                              // 0 when the file does not say
  int64_t frames = 0;                          // as the file states (0: not stated)
  std::string codec;                           // FFmpeg's decoder name
};

class VideoReader {
 public:
  // kIo / kInput errors name the file and give FFmpeg's reason.
  explicit VideoReader(const std::string& path, uint32_t max_side = 8192);
  ~VideoReader();
  VideoReader(const VideoReader&) = delete;
  VideoReader& operator=(const VideoReader&) = delete;

  const VideoInfo& info() const;
  // The next frame in display order; false at the end. A frame the decoder
  // finds damaged, or whose size changes, is a kInput error naming it. (A
  // file may end before the frame count it states, with no damaged packet:
  // FFmpeg reads such files as they are, and so does this.)
  bool next(Image& frame);
  int64_t frames_read() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace m4mesh
