#include "render/image.h"

#include <algorithm>
#include <cmath>

#include <gif_lib.h>
#include <png.h>

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

void write_png(const Image& image, const std::string& path) {
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
  write_file_atomically(path, bytes);
}

Image read_png(const std::string& path) {
  const std::vector<uint8_t> bytes = read_file(path);
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&png, bytes.data(), bytes.size())) throw image_error(path, std::string("not a PNG: ") + png.message);
  if (png.width == 0 || png.height == 0 || png.width > 16384 || png.height > 16384) {
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
};

namespace {

int write_to_file(GifFileType* gif, const GifByteType* data, int length) {
  static_cast<AtomicFile*>(gif->UserData)->write(std::string_view(reinterpret_cast<const char*>(data), static_cast<size_t>(length)));
  return length;
}

}  // namespace

GifWriter::GifWriter(const std::string& path, uint32_t width, uint32_t height, uint32_t delay_centiseconds)
    : state_(new State{AtomicFile(path), nullptr, width, height, delay_centiseconds, path}) {
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
  // The frame's own 256 colours (giflib's median cut), so that shading and colour maps keep their steps.
  const size_t pixels = size_t{frame.width} * frame.height;
  std::vector<GifByteType> red(pixels), green(pixels), blue(pixels), indices(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    red[i] = frame.pixels[i].r;
    green[i] = frame.pixels[i].g;
    blue[i] = frame.pixels[i].b;
  }
  int colours = 256;
  GifColorType palette[256];
  if (GifQuantizeBuffer(frame.width, frame.height, &colours, red.data(), green.data(), blue.data(), indices.data(), palette) == GIF_ERROR)
    throw image_error(state_->path, "GIF: cannot choose the frame's colours");
  const std::unique_ptr<ColorMapObject, void (*)(ColorMapObject*)> map(GifMakeMapObject(256, palette), GifFreeMapObject);
  GraphicsControlBlock control{DISPOSAL_UNSPECIFIED, false, static_cast<int>(state_->delay), NO_TRANSPARENT_COLOR};
  GifByteType extension[4];
  EGifGCBToExtension(&control, extension);
  if (!map || EGifPutExtension(gif, GRAPHICS_EXT_FUNC_CODE, 4, extension) == GIF_ERROR ||
      EGifPutImageDesc(gif, 0, 0, static_cast<int>(frame.width), static_cast<int>(frame.height), false, map.get()) == GIF_ERROR)
    throw image_error(state_->path, std::string("GIF: ") + GifErrorString(gif->Error));
  for (uint32_t y = 0; y < frame.height; ++y)
    if (EGifPutLine(gif, indices.data() + size_t{y} * frame.width, static_cast<int>(frame.width)) == GIF_ERROR)
      throw image_error(state_->path, std::string("GIF: ") + GifErrorString(gif->Error));
}

void GifWriter::finish() {
  int error = 0;
  const int status = EGifCloseFile(state_->gif, &error);
  state_->gif = nullptr;
  if (status == GIF_ERROR) throw image_error(state_->path, std::string("GIF: ") + GifErrorString(error));
  state_->file.commit();
}

}  // namespace m4mesh
