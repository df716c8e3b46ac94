// RGB pictures and their files: PNG through libpng, animated GIF through
// giflib (a palette of 256 colours per frame, chosen by libimagequant).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace m4mesh {

struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

struct Image {
  uint32_t width = 0, height = 0;
  std::vector<Rgb> pixels;  // row by row from the top

  Image() = default;
  Image(uint32_t w, uint32_t h, Rgb fill = {}) : width(w), height(h), pixels(size_t{w} * h, fill) {}
  Rgb& at(uint32_t x, uint32_t y) { return pixels[size_t{y} * width + x]; }
  const Rgb& at(uint32_t x, uint32_t y) const { return pixels[size_t{y} * width + x]; }
};

// The picture at texel coordinates (u, v) (texel centres at integers),
// bilinear, the edge texels repeated outside; channels rounded.
Rgb bilinear(const Image& image, double u, double v);

// The picture scaled to width × height: each pixel the mean of the pixels
// it covers (the nearest one when enlarging).
Image resized(const Image& image, uint32_t width, uint32_t height);

// Errors are kIo errors that name the file. A PNG may carry text
// (tEXt chunks: keyword, text), as `track` gives its texture the video's
// frame rate.
void write_png(const Image& image, const std::string& path, const std::vector<std::pair<std::string, std::string>>& text = {});
Image read_png(const std::string& path);
// The text of `keyword` in a PNG's tEXt chunks, empty when it has none.
std::string png_text(const std::string& path, const std::string& keyword);
// The keyword of a texture's frames per second (a decimal number): `track`
// writes the video's, `render` plays at it.
inline constexpr const char* kFrameRateText = "Frame rate";
// The keyword of a texture for several I-planes: their plane numbers
// ("0 42 87"); the picture holds their textures, of equal height, one
// above the other in that order. `track` writes it, `render` lays each
// I-plane's own.
inline constexpr const char* kIntraPlanesText = "I-planes";
// The largest side of a PNG read.
inline constexpr uint32_t kMostPictureSide = 16384;

// An animated GIF written frame by frame (memory: one frame), looping.
class GifWriter {
 public:
  GifWriter(const std::string& path, uint32_t width, uint32_t height, uint32_t delay_centiseconds);
  ~GifWriter();
  GifWriter(const GifWriter&) = delete;
  GifWriter& operator=(const GifWriter&) = delete;
  void add(const Image& frame);
  // Completes the file (atomically, like every output).
  void finish();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace m4mesh
