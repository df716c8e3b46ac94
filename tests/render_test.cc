// Pictures of 2D mesh animations (render/): the texture warp, PNG and GIF files.
#include <gtest/gtest.h>
#include <gif_lib.h>

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
