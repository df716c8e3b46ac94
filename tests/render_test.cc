// Pictures of 2D mesh animations (render/): the texture warp, PNG and GIF files.
#include <gtest/gtest.h>
#include <gif_lib.h>

#include <cmath>
#include <filesystem>

#include "mesh/uniform.h"
#include "render/texture_warp.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

struct Grid {
  UniformParams params{9, 7, 16, 16, 0};
  std::vector<Point> nodes = uniform_nodes(params);
  std::vector<Triangle> triangles = uniform_triangles(params);
};

// A plane with zero motion shows the texture unwarped: every pixel the mesh
// covers is the texel under it.
TEST(TextureWarp, ZeroMotionShowsTheTexture) {
  const Grid grid;
  const Canvas canvas = canvas_over(grid.nodes);
  ASSERT_EQ(canvas.width, 65u);  // 128 half pixels: pixels 0 … 64
  const Image texture = checkerboard(canvas.width, canvas.height, 5);
  const TextureWarp warp(grid.nodes, grid.triangles, texture, canvas);
  const Image picture = warp.render(grid.nodes, false);
  // The mesh ends at pixel 64.0: the last column's centres lie outside it.
  for (uint32_t y = 0; y + 1 < canvas.height; ++y)
    for (uint32_t x = 0; x + 1 < canvas.width; ++x) ASSERT_EQ(picture.at(x, y), texture.at(x, y)) << x << ", " << y;
}

TEST(TextureWarp, MotionMovesTheTextureWithTheNodes) {
  const Grid grid;
  std::vector<Point> moved = grid.nodes;
  for (Point& p : moved) p.x += 8;  // 4 pixels right
  const Canvas canvas = united(canvas_over(grid.nodes), canvas_over(moved));
  const Image texture = checkerboard(65, 49, 5);
  const TextureWarp warp(grid.nodes, grid.triangles, texture, canvas);
  const Image before = warp.render(grid.nodes, false), after = warp.render(moved, false);
  for (uint32_t y = 0; y + 1 < 49; ++y)
    for (uint32_t x = 0; x + 1 < 65; ++x) ASSERT_EQ(after.at(x + 4, y), before.at(x, y)) << x << ", " << y;
  EXPECT_NE(after.at(1, 10), before.at(1, 10));  // uncovered now: the background
}

TEST(Pictures, PngRoundTrips) {
  const fs::path path = fs::temp_directory_path() / ("m4mesh-render-" + std::to_string(::getpid()) + ".png");
  const Image board = checkerboard(37, 23, 4);
  write_png(board, path.string());
  const Image back = read_png(path.string());
  fs::remove(path);
  EXPECT_EQ(back.width, 37u);
  EXPECT_EQ(back.height, 23u);
  EXPECT_EQ(back.pixels, board.pixels);
}

TEST(Pictures, GifHoldsEveryFrameAtItsSize) {
  const fs::path path = fs::temp_directory_path() / ("m4mesh-render-" + std::to_string(::getpid()) + ".gif");
  {
    GifWriter gif(path.string(), 40, 30, 4);
    for (uint32_t k = 1; k <= 3; ++k) gif.add(checkerboard(40, 30, k));
    gif.finish();
  }
  int error = 0;
  GifFileType* gif = DGifOpenFileName(path.string().c_str(), &error);
  ASSERT_NE(gif, nullptr);
  ASSERT_EQ(DGifSlurp(gif), GIF_OK);
  EXPECT_EQ(gif->SWidth, 40);
  EXPECT_EQ(gif->SHeight, 30);
  EXPECT_EQ(gif->ImageCount, 3);
  DGifCloseFile(gif, &error);
  fs::remove(path);
}

// The frames a GIF shows: each image over the one before, its transparent
// pixels letting that one through.
std::vector<Image> shown_frames(const fs::path& path) {
  int error = 0;
  GifFileType* gif = DGifOpenFileName(path.string().c_str(), &error);
  EXPECT_NE(gif, nullptr);
  if (!gif) return {};
  EXPECT_EQ(DGifSlurp(gif), GIF_OK);
  std::vector<Image> frames;
  Image shown(static_cast<uint32_t>(gif->SWidth), static_cast<uint32_t>(gif->SHeight));
  for (int k = 0; k < gif->ImageCount; ++k) {
    const SavedImage& image = gif->SavedImages[k];
    const ColorMapObject* map = image.ImageDesc.ColorMap ? image.ImageDesc.ColorMap : gif->SColorMap;
    GraphicsControlBlock control{};
    DGifSavedExtensionToGCB(gif, k, &control);
    for (size_t i = 0; i < shown.pixels.size(); ++i) {
      const int index = image.RasterBits[i];
      if (index != control.TransparentColor) shown.pixels[i] = {map->Colors[index].Red, map->Colors[index].Green, map->Colors[index].Blue};
    }
    frames.push_back(shown);
  }
  DGifCloseFile(gif, &error);
  return frames;
}

double rgb_psnr(const Image& a, const Image& b) {
  double sum = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (auto channel : {&Rgb::r, &Rgb::g, &Rgb::b}) sum += std::pow(static_cast<double>(a.pixels[i].*channel) - static_cast<double>(b.pixels[i].*channel), 2);
  return 10 * std::log10(255.0 * 255.0 * 3 * static_cast<double>(a.pixels.size()) / sum);
}

// Colours of a busy picture (many hues, a checker of two lightnesses): a
// GIF keeps them within 33 dB (giflib's own median cut of 5-bit colours
// gave 27.7 dB here, and turned video's grey road cyan); pixels that did not
// change cost next to nothing.
TEST(Pictures, GifColoursComeCloseAndStillPixelsCostNothing) {
  Image busy(128, 96);
  for (uint32_t y = 0; y < 96; ++y)
    for (uint32_t x = 0; x < 128; ++x)
      busy.at(x, y) = {static_cast<uint8_t>(60 + (x * 97 + y * 13) % 61 + (x * y) % 17), static_cast<uint8_t>(80 + (x * 31 + y * 57) % 71),
                       static_cast<uint8_t>(20 + (x * 7 + y * 11) % 41 + ((x / 16 + y / 16) % 2) * 90)};
  Image changed = busy;  // the right half brighter
  for (uint32_t y = 0; y < 96; ++y)
    for (uint32_t x = 64; x < 128; ++x) changed.at(x, y).g = static_cast<uint8_t>(changed.at(x, y).g + 40);
  const fs::path base = fs::temp_directory_path() / ("m4mesh-colours-" + std::to_string(::getpid()));
  auto write = [&](const std::vector<const Image*>& frames) {
    const fs::path path = base.string() + std::to_string(frames.size()) + ".gif";
    GifWriter gif(path.string(), 128, 96, 10);
    for (const Image* frame : frames) gif.add(*frame);
    gif.finish();
    return path;
  };
  const fs::path two = write({&busy, &changed}), three = write({&busy, &changed, &changed});
  const std::vector<Image> shown = shown_frames(three);
  ASSERT_EQ(shown.size(), 3u);
  EXPECT_GE(rgb_psnr(shown[0], busy), 33.0);
  EXPECT_GE(rgb_psnr(shown[1], changed), 33.0);
  EXPECT_EQ(shown[2].pixels, shown[1].pixels);
  EXPECT_LT(fs::file_size(three), fs::file_size(two) + 1000);  // the third frame: all transparent
  fs::remove(two);
  fs::remove(three);
}

// A PNG's text: written after IHDR, found by its keyword.
TEST(Pictures, PngCarriesItsText) {
  const fs::path path = fs::temp_directory_path() / ("m4mesh-text-" + std::to_string(::getpid()) + ".png");
  write_png(checkerboard(9, 7, 2), path.string(), {{kFrameRateText, "29.97002997"}, {"Comment", "m4mesh"}});
  EXPECT_EQ(png_text(path.string(), kFrameRateText), "29.97002997");
  EXPECT_EQ(png_text(path.string(), "Comment"), "m4mesh");
  EXPECT_EQ(png_text(path.string(), "Title"), "");
  EXPECT_EQ(read_png(path.string()).pixels, checkerboard(9, 7, 2).pixels);
  fs::remove(path);
}

// I-plane textures stay in one column while it fits (28 of 576 rows),
// then take the fewest columns, rows balanced; none past 16384 × 16384.
TEST(Pictures, TileGridsGrowColumnsOnlyWhenOneIsFull) {
  auto grid = [](size_t count, uint32_t width, uint32_t height) {
    const std::optional<TileGrid> g = tile_grid(count, width, height);
    return g ? std::pair{g->columns, g->rows} : std::pair{0u, 0u};
  };
  EXPECT_EQ(grid(1, 768, 576), std::pair(1u, 1u));
  EXPECT_EQ(grid(28, 768, 576), std::pair(1u, 28u));
  EXPECT_EQ(grid(29, 768, 576), std::pair(2u, 15u));
  EXPECT_EQ(grid(21 * 28, 768, 576), std::pair(21u, 28u));
  EXPECT_EQ(grid(21 * 28 + 1, 768, 576), std::pair(0u, 0u));
  EXPECT_EQ(grid(1, 16384, 16384), std::pair(1u, 1u));
  EXPECT_EQ(grid(2, 16384, 16384), std::pair(0u, 0u));
  EXPECT_EQ(grid(1, 16385, 1), std::pair(0u, 0u));
  EXPECT_EQ(grid(0, 8, 8), std::pair(0u, 0u));
  // Three tiles in 2 columns, row by row, cut back out as they were.
  const Image a = checkerboard(5, 3, 1), b(5, 3, Rgb{1, 2, 3}), c(5, 3, Rgb{4, 5, 6});
  const Image picture = tiled({&a, &b, &c}, TileGrid{2, 2});
  EXPECT_EQ(picture.width, 10u);
  EXPECT_EQ(picture.height, 6u);
  EXPECT_EQ(picture.at(5, 0), (Rgb{1, 2, 3}));
  EXPECT_EQ(picture.at(0, 3), (Rgb{4, 5, 6}));
  EXPECT_EQ(picture.at(9, 5), Rgb{});
  const std::vector<Image> back = untiled(picture, TileGrid{2, 2}, 3);
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[0].pixels, a.pixels);
  EXPECT_EQ(back[1].pixels, b.pixels);
  EXPECT_EQ(back[2].pixels, c.pixels);
}

TEST(Pictures, AGifNotFinishedLeavesNoFile) {
  const fs::path path = fs::temp_directory_path() / ("m4mesh-render-cut-" + std::to_string(::getpid()) + ".gif");
  {
    GifWriter gif(path.string(), 8, 8, 4);
    gif.add(checkerboard(8, 8, 2));
  }
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace m4mesh
