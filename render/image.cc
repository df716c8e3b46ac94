#include "render/image.h"

#include <algorithm>
#include <cmath>

#include <gif_lib.h>
#include <libimagequant.h>
#include <png.h>
#include <zlib.h>

#include <cstring>

#include "common/atomic_file.h"
#include "common/error.h"

namespace m4mesh {

namespace {

Error image_error(const std::string& path, const std::string& message) {
  return Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, path + ": " + message);
}

}  // namespace

Rgb bilinear(const Image& image, double u, double v) {
  u = std::clamp(u, 0.0, image.width - 1.0);
  v = std::clamp(v, 0.0, image.height - 1.0);
  const auto x = static_cast<uint32_t>(u), y = static_cast<uint32_t>(v);
  const uint32_t x1 = std::min(x + 1, image.width - 1), y1 = std::min(y + 1, image.height - 1);
  const double fx = u - x, fy = v - y;
  auto mix = [&](uint8_t Rgb::*c) {
    const double top = image.at(x, y).*c * (1 - fx) + image.at(x1, y).*c * fx;
    const double bottom = image.at(x, y1).*c * (1 - fx) + image.at(x1, y1).*c * fx;
    return static_cast<uint8_t>(std::lround(top * (1 - fy) + bottom * fy));
  };
  return {mix(&Rgb::r), mix(&Rgb::g), mix(&Rgb::b)};
}

Image resized(const Image& image, uint32_t width, uint32_t height) {
  Image out(width, height);
  for (uint32_t y = 0; y < height; ++y) {
    const uint32_t y0 = static_cast<uint32_t>(uint64_t{y} * image.height / height);
    const uint32_t y1 = std::max(y0 + 1, static_cast<uint32_t>((uint64_t{y} + 1) * image.height / height));
    for (uint32_t x = 0; x < width; ++x) {
      const uint32_t x0 = static_cast<uint32_t>(uint64_t{x} * image.width / width);
      const uint32_t x1 = std::max(x0 + 1, static_cast<uint32_t>((uint64_t{x} + 1) * image.width / width));
      uint64_t r = 0, g = 0, b = 0;
      for (uint32_t v = y0; v < y1; ++v)
        for (uint32_t u = x0; u < x1; ++u) {
          const Rgb& c = image.at(u, v);
          r += c.r;
          g += c.g;
          b += c.b;
        }
      const uint64_t n = uint64_t{x1 - x0} * (y1 - y0);
      out.at(x, y) = {static_cast<uint8_t>((r + n / 2) / n), static_cast<uint8_t>((g + n / 2) / n), static_cast<uint8_t>((b + n / 2) / n)};
    }
  }
  return out;
}

namespace {

constexpr size_t kPngSignature = 8;

uint32_t big_endian(const uint8_t* p) { return uint32_t{p[0]} << 24 | uint32_t{p[1]} << 16 | uint32_t{p[2]} << 8 | p[3]; }

// A tEXt chunk: length, type, keyword, a zero byte, the text, CRC-32 of type and data.
std::string text_chunk(const std::string& keyword, const std::string& text) {
  auto put32 = [](std::string& out, uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>(v >> shift);
  };
  const std::string chunk = "tEXt" + keyword + '\0' + text;
  std::string out;
  put32(out, static_cast<uint32_t>(chunk.size() - 4));
  out += chunk;
  put32(out, static_cast<uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(chunk.data()), static_cast<uInt>(chunk.size()))));
  return out;
}

}  // namespace

std::string png_text(const std::string& path, const std::string& keyword) {
  const std::vector<uint8_t> bytes = read_file(path);
  // Chunks until the image data: length, type, data, CRC.
  for (size_t at = kPngSignature; at + 12 <= bytes.size();) {
    const uint32_t length = big_endian(&bytes[at]);
    if (length > bytes.size() - at - 12) break;
    const std::string type(bytes.begin() + static_cast<std::ptrdiff_t>(at + 4), bytes.begin() + static_cast<std::ptrdiff_t>(at + 8));
    if (type == "IDAT") break;
    if (type == "tEXt") {
      const std::string data(bytes.begin() + static_cast<std::ptrdiff_t>(at + 8), bytes.begin() + static_cast<std::ptrdiff_t>(at + 8 + length));
      if (const size_t zero = data.find('\0'); zero != std::string::npos && data.substr(0, zero) == keyword) return data.substr(zero + 1);
    }
    at += 12 + length;
  }
  return "";
}

std::optional<TileGrid> tile_grid(size_t count, uint32_t width, uint32_t height) {
  if (count == 0 || width == 0 || height == 0 || width > kMostPictureSide || height > kMostPictureSide) return std::nullopt;
  const uint64_t per_column = kMostPictureSide / height;
  const uint64_t columns = (count + per_column - 1) / per_column;
  if (columns > kMostPictureSide / width) return std::nullopt;
  const uint64_t rows = (count + columns - 1) / columns;
  return TileGrid{static_cast<uint32_t>(columns), static_cast<uint32_t>(rows)};
}

Image tiled(const std::vector<const Image*>& tiles, TileGrid grid) {
  const uint32_t w = tiles.front()->width, h = tiles.front()->height;
  Image picture(grid.columns * w, grid.rows * h);
  for (size_t k = 0; k < tiles.size(); ++k) {
    const uint32_t x0 = static_cast<uint32_t>(k % grid.columns) * w, y0 = static_cast<uint32_t>(k / grid.columns) * h;
    for (uint32_t y = 0; y < h; ++y)
      std::copy_n(tiles[k]->pixels.begin() + static_cast<std::ptrdiff_t>(size_t{y} * w), w,
                  picture.pixels.begin() + static_cast<std::ptrdiff_t>(size_t{y0 + y} * picture.width + x0));
  }
  return picture;
}

std::vector<Image> untiled(const Image& picture, TileGrid grid, size_t count) {
  const uint32_t w = picture.width / grid.columns, h = picture.height / grid.rows;
  std::vector<Image> tiles;
  for (size_t k = 0; k < count; ++k) {
    const uint32_t x0 = static_cast<uint32_t>(k % grid.columns) * w, y0 = static_cast<uint32_t>(k / grid.columns) * h;
    Image& tile = tiles.emplace_back(w, h);
    for (uint32_t y = 0; y < h; ++y)
      std::copy_n(picture.pixels.begin() + static_cast<std::ptrdiff_t>(size_t{y0 + y} * picture.width + x0), w,
                  tile.pixels.begin() + static_cast<std::ptrdiff_t>(size_t{y} * w));
  }
  return tiles;
}

void write_png(const Image& image, const std::string& path, const std::vector<std::pair<std::string, std::string>>& text) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = image.width;
  png.height = image.height;
  png.format = PNG_FORMAT_RGB;
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, image.pixels.data(), 0, nullptr))
    throw image_error(path, std::string("PNG: ") + png.message);
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.pixels.data(), 0, nullptr))
    throw image_error(path, std::string("PNG: ") + png.message);
  bytes.resize(size);
  // The text after IHDR (the signature, then IHDR's 13 bytes in a chunk of 25).
  for (const auto& [keyword, value] : text) bytes.insert(kPngSignature + 25, text_chunk(keyword, value));
  write_file_atomically(path, bytes);
}

Image read_png(const std::string& path) {
  const std::vector<uint8_t> bytes = read_file(path);
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&png, bytes.data(), bytes.size())) throw image_error(path, std::string("not a PNG: ") + png.message);
  if (png.width == 0 || png.height == 0 || png.width > kMostPictureSide || png.height > kMostPictureSide) {
    png_image_free(&png);
    throw image_error(path, "a PNG of " + std::to_string(png.width) + " × " + std::to_string(png.height) + ": textures go to 16384 × 16384");
  }
  png.format = PNG_FORMAT_RGB;
  Image image(png.width, png.height);
  if (!png_image_finish_read(&png, nullptr, image.pixels.data(), 0, nullptr)) throw image_error(path, std::string("PNG: ") + png.message);
  return image;
}

struct GifWriter::State {
  AtomicFile file;
  GifFileType* gif = nullptr;
  uint32_t width, height, delay;
  std::string path;
  Image previous;  // the last frame given, empty before the first
};

namespace {

int write_to_file(GifFileType* gif, const GifByteType* data, int length) {
  static_cast<AtomicFile*>(gif->UserData)->write(std::string_view(reinterpret_cast<const char*>(data), static_cast<size_t>(length)));
  return length;
}

}  // namespace

GifWriter::GifWriter(const std::string& path, uint32_t width, uint32_t height, uint32_t delay_centiseconds)
    : state_(new State{AtomicFile(path), nullptr, width, height, delay_centiseconds, path, Image()}) {
  if (width == 0 || height == 0 || width > 65535 || height > 65535) throw image_error(path, "a GIF goes to 65535 × 65535 pixels");
  int error = 0;
  state_->gif = EGifOpen(&state_->file, write_to_file, &error);
  if (!state_->gif) throw image_error(path, std::string("GIF: ") + GifErrorString(error));
  EGifSetGifVersion(state_->gif, true);
  // No global palette: every frame brings its own (add()).
  const int status = EGifPutScreenDesc(state_->gif, static_cast<int>(width), static_cast<int>(height), 8, 0, nullptr);
  // Loop for ever: the NETSCAPE2.0 application extension.
  static const GifByteType kLoop[] = {1, 0, 0};
  if (status == GIF_ERROR || EGifPutExtensionLeader(state_->gif, APPLICATION_EXT_FUNC_CODE) == GIF_ERROR ||
      EGifPutExtensionBlock(state_->gif, 11, "NETSCAPE2.0") == GIF_ERROR || EGifPutExtensionBlock(state_->gif, 3, kLoop) == GIF_ERROR ||
      EGifPutExtensionTrailer(state_->gif) == GIF_ERROR)
    throw image_error(path, std::string("GIF: ") + GifErrorString(state_->gif->Error));
}

GifWriter::~GifWriter() {
  if (state_->gif) EGifCloseFile(state_->gif, nullptr);  // the file is not committed: it is removed
}

void GifWriter::add(const Image& frame) {
  GifFileType* gif = state_->gif;
  if (frame.width != state_->width || frame.height != state_->height) throw image_error(state_->path, "a GIF frame of another size");
  // The frame's own colours, chosen by libimagequant (giflib's median cut
  // of 5-bit colours lost 13 dB on video) for the pixels that changed since
  // the last frame, without dithering: frames stay compressible and do not
  // shimmer. Pixels that did not change are transparent: the last frame
  // shows through (index 255, so 255 colours after the first frame).
  const size_t pixels = size_t{frame.width} * frame.height;
  const bool first = state_->previous.pixels.empty();
  std::vector<uint8_t> rgba(4 * pixels), indices(pixels), changed(pixels, 255);
  for (size_t i = 0; i < pixels; ++i) {
    rgba[4 * i] = frame.pixels[i].r;
    rgba[4 * i + 1] = frame.pixels[i].g;
    rgba[4 * i + 2] = frame.pixels[i].b;
    rgba[4 * i + 3] = 255;
    if (!first && frame.pixels[i] == state_->previous.pixels[i]) changed[i] = 0;
  }
  constexpr int kTransparent = 255;
  const std::unique_ptr<liq_attr, void (*)(liq_attr*)> attr(liq_attr_create(), liq_attr_destroy);
  const std::unique_ptr<liq_image, void (*)(liq_image*)> image(
      attr ? liq_image_create_rgba(attr.get(), rgba.data(), static_cast<int>(frame.width), static_cast<int>(frame.height), 0) : nullptr,
      liq_image_destroy);
  liq_result* chosen = nullptr;
  if (!image || liq_set_max_colors(attr.get(), first ? 256 : kTransparent) != LIQ_OK || liq_set_speed(attr.get(), 8) != LIQ_OK ||
      (!first && liq_image_set_importance_map(image.get(), changed.data(), pixels, LIQ_COPY_PIXELS) != LIQ_OK) ||
      liq_image_quantize(image.get(), attr.get(), &chosen) != LIQ_OK)
    throw image_error(state_->path, "GIF: cannot choose the frame's colours");
  const std::unique_ptr<liq_result, void (*)(liq_result*)> result(chosen, liq_result_destroy);
  if (liq_set_dithering_level(result.get(), 0) != LIQ_OK || liq_write_remapped_image(result.get(), image.get(), indices.data(), pixels) != LIQ_OK)
    throw image_error(state_->path, "GIF: cannot map the frame to its colours");
  for (size_t i = 0; i < pixels; ++i)
    if (!changed[i]) indices[i] = kTransparent;
  const liq_palette* chosen_palette = liq_get_palette(result.get());
  GifColorType palette[256] = {};
  for (unsigned i = 0; i < chosen_palette->count; ++i) palette[i] = {chosen_palette->entries[i].r, chosen_palette->entries[i].g, chosen_palette->entries[i].b};
  const std::unique_ptr<ColorMapObject, void (*)(ColorMapObject*)> map(GifMakeMapObject(256, palette), GifFreeMapObject);
  GraphicsControlBlock control{DISPOSE_DO_NOT, false, static_cast<int>(state_->delay), first ? NO_TRANSPARENT_COLOR : kTransparent};
  GifByteType extension[4];
  EGifGCBToExtension(&control, extension);
  if (!map || EGifPutExtension(gif, GRAPHICS_EXT_FUNC_CODE, 4, extension) == GIF_ERROR ||
      EGifPutImageDesc(gif, 0, 0, static_cast<int>(frame.width), static_cast<int>(frame.height), false, map.get()) == GIF_ERROR)
    throw image_error(state_->path, std::string("GIF: ") + GifErrorString(gif->Error));
  for (uint32_t y = 0; y < frame.height; ++y)
    if (EGifPutLine(gif, indices.data() + size_t{y} * frame.width, static_cast<int>(frame.width)) == GIF_ERROR)
      throw image_error(state_->path, std::string("GIF: ") + GifErrorString(gif->Error));
  state_->previous = frame;
}

void GifWriter::finish() {
  int error = 0;
  const int status = EGifCloseFile(state_->gif, &error);
  state_->gif = nullptr;
  if (status == GIF_ERROR) throw image_error(state_->path, std::string("GIF: ") + GifErrorString(error));
  state_->file.commit();
}

}  // namespace m4mesh
