// RGB pictures and their files: PNG through libpng, animated GIF through
// giflib (a palette of 256 colours per frame, chosen by libimagequant).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
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
// ("0 42 87"); the picture holds their textures, tiles of equal size, in
// that order row by row in kIntraColumnsText columns (1 when the text is
// absent: one above the other). `track` writes them, `render` and the web
// player lay each I-plane's own.
inline constexpr const char* kIntraPlanesText = "I-planes";
inline constexpr const char* kIntraColumnsText = "I-plane columns";
// The largest side of a PNG read.
inline constexpr uint32_t kMostPictureSide = 16384;

// Tiles of a texture for several I-planes: the k-th at column k mod
// `columns`, row k / `columns`.
struct TileGrid {
  uint32_t columns = 1, rows = 1;
};
// The grid of `count` tiles of width × height in a picture of at most
// kMostPictureSide on either side: one column while it fits, else the
// fewest columns that hold them; none when they cannot fit.
std::optional<TileGrid> tile_grid(size_t count, uint32_t width, uint32_t height);
// Pictures of one size laid in `grid`, and cut back out: `count` tiles of
// a picture whose sides `grid` divides.
Image tiled(const std::vector<const Image*>& tiles, TileGrid grid);
std::vector<Image> untiled(const Image& picture, TileGrid grid, size_t count);

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
