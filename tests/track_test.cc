// m4mesh track (video/track.h, video/tracking/): videos made here, with
// known motion, compressed by FFmpeg; the tracked nodes against the truth.
#include <gif_lib.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "cli/app.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/random.h"
#include "decoder/mesh_object_decoder.h"
#include "render/texture_warp.h"
#include "video/block_matching.h"
#include "video/track.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

// A folder for one test's files; kept under $M4MESH_TRACK_KEEP when set
// (scripts/track_figures.py measures the same videos).
class Workspace {
 public:
  explicit Workspace(const std::string& name) {
    const char* keep = std::getenv("M4MESH_TRACK_KEEP");
    keep_ = keep && *keep;
    path_ = fs::path(keep_ ? keep : testing::TempDir()) / ("track-" + name);
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~Workspace() {
    std::error_code ignored;
    if (!keep_) fs::remove_all(path_, ignored);
  }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
  bool keep_ = false;
};

// A colourful picture with structure at every scale: random soft blobs and edges.
Image pattern(uint32_t width, uint32_t height, uint64_t seed) {
  SplitMix64 random(seed);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * static_cast<double>(random.next() >> 11) / 9007199254740992.0; };
  struct Blob {
    double x, y, radius, r, g, b;
  };
  std::vector<Blob> blobs;
  const int count = static_cast<int>(width * height / 60);
  for (int i = 0; i < count; ++i)
    blobs.push_back({uniform(0, width), uniform(0, height), uniform(2, 8), uniform(-90, 90), uniform(-90, 90), uniform(-90, 90)});
  Image picture(width, height);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      double r = 128, g = 128, b = 128;
      for (const Blob& blob : blobs) {
        const double d2 = ((x - blob.x) * (x - blob.x) + (y - blob.y) * (y - blob.y)) / (blob.radius * blob.radius);
        const double weight = d2 < 1 ? 1 - d2 * d2 * 0.6 : std::exp(-(d2 - 1) * 3) * 0.4;
        r += blob.r * weight, g += blob.g * weight, b += blob.b * weight;
      }
      auto channel = [](double v) { return static_cast<uint8_t>(std::clamp(std::lround(v), 0L, 255L)); };
      picture.at(x, y) = {channel(r), channel(g), channel(b)};
    }
  return picture;
}

// A colour picture of sums of 24 sinusoids with periods of 6 to 40 pixels:
// fine, repeating structure that a polygon can match a period off.
Image waves(uint32_t width, uint32_t height, uint64_t seed) {
  SplitMix64 random(seed);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * static_cast<double>(random.next() >> 11) / 9007199254740992.0; };
  struct Wave {
    double fx, fy, phase[3], weight[3];
  };
  std::vector<Wave> waves(24);
  for (Wave& wave : waves) {
    const double period = std::exp(uniform(std::log(6.0), std::log(40.0))), angle = uniform(0, std::numbers::pi);
    wave.fx = std::cos(angle) / period, wave.fy = std::sin(angle) / period;
    for (int c = 0; c < 3; ++c) wave.phase[c] = uniform(0, 2 * std::numbers::pi), wave.weight[c] = uniform(0.3, 1.0) * 4;
  }
  Image picture(width, height);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      double rgb[3] = {128, 128, 128};
      for (const Wave& wave : waves)
        for (int c = 0; c < 3; ++c) rgb[c] += wave.weight[c] * std::sin(2 * std::numbers::pi * (x * wave.fx + y * wave.fy) + wave.phase[c]);
      auto channel = [](double v) { return static_cast<uint8_t>(std::clamp(std::lround(v), 0L, 255L)); };
      picture.at(x, y) = {channel(rgb[0]), channel(rgb[1]), channel(rgb[2])};
    }
  return picture;
}

void write_frames(const Workspace& folder, const std::vector<Image>& frames) {
  for (size_t t = 0; t < frames.size(); ++t) {
    char name[32];
    std::snprintf(name, sizeof name, "%03zu.png", t);
    write_png(frames[t], folder / name);
  }
}

// The frames as H.264 (yuv420p), as a camera's video would come.
std::string h264_video(const Workspace& folder, const std::vector<Image>& frames, int fps = 25, int crf = 12) {
  write_frames(folder, frames);
  const std::string video = folder / "video.mp4";
  const std::string command = "ffmpeg -nostdin -v error -y -framerate " + std::to_string(fps) + " -i '" + folder / "%03d.png" +
                              "' -c:v libx264 -preset fast -crf " + std::to_string(crf) + " -pix_fmt yuv420p -movflags +faststart '" + video + "'";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return video;
}

// A smooth motion that vanishes on the frame's border: pixels, at frame t.
struct SmoothMotion {
  double width, height;
  double amplitude = 1;
  std::pair<double, double> at(double x, double y, int t) const {
    const double fx = std::clamp(x / width, 0.0, 1.0), fy = std::clamp(y / height, 0.0, 1.0);
    const double bump = std::sin(std::numbers::pi * fx) * std::sin(std::numbers::pi * fy);
    const double phase = 2 * std::numbers::pi * t / 24.0;
    return {amplitude * 5.0 * std::sin(phase) * bump, amplitude * 3.5 * std::sin(phase * 0.7) * bump * std::cos(std::numbers::pi * (fx - 0.3))};
  }
};

// Frames warped from a texture by a fine mesh (4-pixel cells) moved by
// `motion`: the truth of any point is that mesh's piecewise-affine map.
struct WarpedVideo {
  FrameMesh truth_mesh;
  std::vector<std::vector<Point>> truth;  // the fine mesh's nodes per frame
  std::vector<Image> frames;

  WarpedVideo(uint32_t width, uint32_t height, int count, const SmoothMotion& motion) : truth_mesh(uniform_frame_mesh(width, height, 4, 4)) {
    const std::vector<Point>& nodes = truth_mesh.tracking.nodes;
    const Canvas box = canvas_over(nodes);
    const Image texture = pattern(box.width, box.height, 7);
    const TextureWarp warp(nodes, truth_mesh.tracking.triangles, texture, Canvas{0, 0, width, height});
    for (int t = 0; t < count; ++t) {
      std::vector<Point> moved;
      for (const Point& p : nodes) {
        const auto [dx, dy] = motion.at(p.x / 2.0, p.y / 2.0, t);
        moved.push_back({p.x + static_cast<int32_t>(std::lround(2 * dx)), p.y + static_cast<int32_t>(std::lround(2 * dy))});
      }
      frames.push_back(warp.render(moved, false));
      truth.push_back(std::move(moved));
    }
  }

  // Where the point at q (half pixels, frame 0) lies in frame t, in pixels.
  std::pair<double, double> truth_at(const Point& q, size_t t) const {
    const std::vector<Point>& p0 = truth_mesh.tracking.nodes;
    for (const Triangle& tri : truth_mesh.tracking.triangles) {
      const Point &a = p0[tri.v[0]], &b = p0[tri.v[1]], &c = p0[tri.v[2]];
      const double area = static_cast<double>(orient(a, b, c));
      const double wb = static_cast<double>(orient(a, q, c)) / area, wc = static_cast<double>(orient(a, b, q)) / area, wa = 1 - wb - wc;
      if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9) continue;
      const Point &at = truth[t][tri.v[0]], &bt = truth[t][tri.v[1]], &ct = truth[t][tri.v[2]];
      return {(wa * at.x + wb * bt.x + wc * ct.x) / 2, (wa * at.y + wb * bt.y + wc * ct.y) / 2};
    }
    ADD_FAILURE() << "node " << q.x << ", " << q.y << " outside the truth mesh";
    return {0, 0};
  }
};

double mean_error(const TrackResult& result, const std::function<std::pair<double, double>(const Point&, size_t)>& truth) {
  double sum = 0;
  size_t count = 0;
  for (size_t t = 1; t < result.positions.size(); ++t)
    for (size_t n = 0; n < result.positions[t].size(); ++n) {
      const auto [x, y] = truth(result.positions[0][n], t);
      sum += std::hypot(result.positions[t][n].x / 2.0 - x, result.positions[t][n].y / 2.0 - y);
      ++count;
    }
  return sum / static_cast<double>(count);
}

// No triangle folded, none grown or shrunk past kMaxStretch since its I-plane.
void expect_no_fold(const TrackResult& result) {
  for (size_t t = 0; t < result.positions.size(); ++t) {
    const TrackingMesh& mesh = mesh_at(result, t).tracking;
    for (const Triangle& tri : mesh.triangles) {
      const int64_t area = orient(result.positions[t][tri.v[0]], result.positions[t][tri.v[1]], result.positions[t][tri.v[2]]);
      const int64_t design = orient(mesh.nodes[tri.v[0]], mesh.nodes[tri.v[1]], mesh.nodes[tri.v[2]]);
      ASSERT_GT(area, 0) << "frame " << t;
      ASSERT_LE(static_cast<double>(std::max(area, design)) / static_cast<double>(std::min(area, design)), kMaxStretch + 1e-9) << "frame " << t;
    }
  }
}

TEST(Track, UniformNodesFollowASmoothWarpThroughH264) {
  const Workspace folder("smooth");
  const WarpedVideo video(160, 128, 16, SmoothMotion{160, 128});
  TrackSettings settings;
  const TrackResult result = track_video(h264_video(folder, video.frames), settings);
  ASSERT_EQ(result.positions.size(), 16u);
  EXPECT_EQ(result.mesh.plane.info.kind, MeshKind::kUniform);
  expect_no_fold(result);
  const double error = mean_error(result, [&](const Point& q, size_t t) { return video.truth_at(q, t); });
  std::printf("uniform 16x16 on a smooth warp, H.264: mean node error %.3f px\n", error);
  EXPECT_LE(error, 0.5);
  // The texture warped by the tracked mesh comes close to the video.
  for (size_t t = 1; t < result.frames.size(); ++t) EXPECT_GT(result.frames[t].render_psnr, 30) << "frame " << t;
}

TEST(Track, ContentBasedNodesFollowASmoothWarpThroughH264) {
  const Workspace folder("smooth-delaunay");
  const WarpedVideo video(160, 128, 16, SmoothMotion{160, 128});
  TrackSettings settings;
  settings.nodes = 80;
  const TrackResult result = track_video(h264_video(folder, video.frames), settings);
  EXPECT_EQ(result.mesh.plane.info.kind, MeshKind::kDelaunay);
  EXPECT_NEAR(static_cast<double>(result.mesh.tracking.nodes.size()), 80, 4);
  expect_no_fold(result);
  const double error = mean_error(result, [&](const Point& q, size_t t) { return video.truth_at(q, t); });
  std::printf("content-based Delaunay (80 nodes) on a smooth warp, H.264: mean node error %.3f px\n", error);
  EXPECT_LE(error, 0.5);
}

// A warp strong enough to stretch and turn the content under a node by
// about a fifth across its window: each node's window takes the shape of
// its ring's motion.
TEST(Track, NodesMatchTheirContentAsTheWarpShapesIt) {
  const Workspace folder("strong-warp");
  const WarpedVideo video(160, 128, 16, SmoothMotion{160, 128, 2.5});
  TrackSettings settings;
  const TrackResult result = track_video(h264_video(folder, video.frames), settings);
  expect_no_fold(result);
  const double error = mean_error(result, [&](const Point& q, size_t t) { return video.truth_at(q, t); });
  std::printf("uniform 16x16 on a strong warp, H.264: mean node error %.3f px\n", error);
  EXPECT_LE(error, 0.3);
}

// The stream decodes to the tracked nodes, and `m4mesh render` of it with
// the written texture draws the frames the measurement compared, at the
// video's size and, as a GIF, at its frame rate (10 a second here).
TEST(Track, RenderOfTheStreamIsWhatWasMeasured) {
  const Workspace folder("render");
  const WarpedVideo video(96, 80, 6, SmoothMotion{96, 80});
  const std::string input = h264_video(folder, video.frames, 10);
  const std::string stream = folder / "out.m4m", texture = folder / "first.png", picture = folder / "plane5.png";
  // Border nodes held on the frame: the mesh covers it whole, so the picture compares pixel for pixel.
  std::vector<const char*> track{"m4mesh", "-q", "track", input.c_str(), "-o", stream.c_str(), "--texture", texture.c_str(), "--nodes", "40", "--border", "frame"};
  ASSERT_EQ(run_m4mesh(static_cast<int>(track.size()), track.data()), 0);
  std::vector<const char*> render{"m4mesh", "-q", "render", stream.c_str(), "-o", picture.c_str(), "--texture", texture.c_str(), "--plane", "5"};
  ASSERT_EQ(run_m4mesh(static_cast<int>(render.size()), render.data()), 0);

  TrackSettings settings;
  settings.nodes = 40;
  settings.tracker.border_on_frame = true;
  const TrackResult result = track_video(input, settings);
  EXPECT_EQ(result.stream, read_file(stream));
  const Image drawn = read_png(picture);
  ASSERT_EQ(drawn.width, 96u);
  ASSERT_EQ(drawn.height, 80u);
  // The texture is the first frame at the video's size, with the video's frame rate.
  const Image first = read_png(texture);
  EXPECT_EQ(first.width, 96u);
  EXPECT_EQ(first.height, 80u);
  EXPECT_EQ(png_text(texture, kFrameRateText), "10");
  const std::string animation = folder / "all.gif";
  std::vector<const char*> gif{"m4mesh", "-q", "render", stream.c_str(), "-o", animation.c_str(), "--texture", texture.c_str()};
  ASSERT_EQ(run_m4mesh(static_cast<int>(gif.size()), gif.data()), 0);
  int error = 0;
  GifFileType* file = DGifOpenFileName(animation.c_str(), &error);
  ASSERT_NE(file, nullptr);
  ASSERT_EQ(DGifSlurp(file), GIF_OK);
  GraphicsControlBlock control{};
  DGifSavedExtensionToGCB(file, 0, &control);
  EXPECT_EQ(control.DelayTime, 10);  // centiseconds
  EXPECT_EQ(file->SWidth, 96);
  EXPECT_EQ(file->SHeight, 80);
  DGifCloseFile(file, &error);
  VideoReader reader(input);
  Image frame;
  for (int t = 0; t <= 5; ++t) ASSERT_TRUE(reader.next(frame));
  EXPECT_EQ(result.frames[5].coverage, 1.0);
  EXPECT_NEAR(psnr(luma_of(frame), luma_of(drawn)), result.frames[5].render_psnr, 1e-9);
}

// An object moving over a still background, outlined by a mask: an image
// sequence read by FFmpeg's pattern.
TEST(Track, MaskedObjectMovesOverAStillBackground) {
  const Workspace folder("object");
  const uint32_t w = 144, h = 112;
  const double cx = 56, cy = 60, radius = 30, vx = 1.5, vy = -0.75;
  const Image background = pattern(w, h, 11), object = pattern(w, h, 23);
  std::vector<Image> frames;
  for (int t = 0; t < 12; ++t) {
    Image frame = background;
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        const double u = x + 0.5 - vx * t, v = y + 0.5 - vy * t;  // the point of frame 0 seen here
        if ((u - cx) * (u - cx) + (v - cy) * (v - cy) <= radius * radius) frame.at(x, y) = bilinear(object, u - 0.5, v - 0.5);
      }
    frames.push_back(std::move(frame));
  }
  write_frames(folder, frames);
  Image mask(w, h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      if ((x + 0.5 - cx) * (x + 0.5 - cx) + (y + 0.5 - cy) * (y + 0.5 - cy) <= radius * radius) mask.at(x, y) = {255, 255, 255};
  write_png(mask, folder / "mask.png");
  TrackSettings settings;
  settings.nodes = 50;
  settings.mask = &mask;
  const TrackResult result = track_video(folder / "%03d.png", settings);
  ASSERT_EQ(result.positions.size(), 12u);
  expect_no_fold(result);
  // Every node inside the disc.
  for (const Point& p : result.mesh.tracking.nodes) EXPECT_LE(std::hypot(p.x / 2.0 - cx, p.y / 2.0 - cy), radius);
  const double error = mean_error(result, [&](const Point& q, size_t t) {
    return std::pair<double, double>{q.x / 2.0 + vx * static_cast<double>(t), q.y / 2.0 + vy * static_cast<double>(t)};
  });
  std::printf("masked object (50 nodes), PNG sequence: mean node error %.3f px\n", error);
  EXPECT_LE(error, 0.5);
  EXPECT_LT(result.frames[1].coverage, 0.25);
}

// A textured disc moving over a still textured background, no mask, through
// H.264 at `crf`, tracked with 60 content-based nodes: the mean error of the
// nodes at least 3 pixels inside the disc's edge in the first frame, and of
// those outside it while the disc has not reached them.
std::pair<double, double> disc_errors(const std::string& name, int crf) {
  const Workspace folder(name);
  const uint32_t w = 320, h = 240;
  const int frames = 14;
  const double cx = 112, cy = 120, radius = 42, vx = 1.6, vy = -0.5;
  const Image background = waves(w, h, 41), object = waves(w, h, 43);
  auto on_disc = [&](double x, double y, int t) { return std::hypot(x - vx * t - cx, y - vy * t - cy) <= radius; };
  std::vector<Image> video;
  for (int t = 0; t < frames; ++t) {
    Image frame = background;
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x)
        if (on_disc(x + 0.5, y + 0.5, t)) frame.at(x, y) = bilinear(object, x - vx * t, y - vy * t);
    video.push_back(std::move(frame));
  }
  const std::string clip = h264_video(folder, video, 25, crf);
  TrackSettings settings;
  settings.nodes = 60;
  settings.remesh_stretch = 0;  // one mesh throughout
  const TrackResult result = track_video(clip, settings);
  if (result.positions.size() != static_cast<size_t>(frames)) {
    ADD_FAILURE() << "tracked " << result.positions.size() << " frames of " << frames;
    return {HUGE_VAL, HUGE_VAL};
  }
  expect_no_fold(result);
  // Nodes at least 3 pixels from the disc's edge in the first frame, while their content is in view.
  double disc_sum = 0, background_sum = 0;
  size_t disc_count = 0, background_count = 0;
  for (size_t n = 0; n < result.mesh.tracking.nodes.size(); ++n) {
    const double x0 = result.mesh.tracking.nodes[n].x / 2.0, y0 = result.mesh.tracking.nodes[n].y / 2.0;
    const double edge = std::hypot(x0 - cx, y0 - cy) - radius;
    if (std::abs(edge) < 3) continue;
    for (int t = 1; t < frames; ++t) {
      const Point& p = result.positions[static_cast<size_t>(t)][n];
      if (edge < 0) {
        disc_sum += std::hypot(p.x / 2.0 - x0 - vx * t, p.y / 2.0 - y0 - vy * t), ++disc_count;
      } else if (!on_disc(x0, y0, t)) {
        background_sum += std::hypot(p.x / 2.0 - x0, p.y / 2.0 - y0), ++background_count;
      }
    }
  }
  EXPECT_GT(disc_count, 0u);
  EXPECT_GT(background_count, 0u);
  const double disc = disc_sum / static_cast<double>(disc_count), off = background_sum / static_cast<double>(background_count);
  std::printf("disc over a still background (60 nodes), H.264 CRF %d: mean node error %.3f px on the disc, %.3f px off it\n", crf, disc, off);
  return {disc, off};
}

// The mesh has polygons that straddle the disc's edge, whose warp fits the
// other side's motion a period of the texture off. Nodes on the disc follow
// the disc, nodes off it stay.
TEST(Track, NodesOnAMovingDiscFollowItNotTheBackground) {
  const auto [disc, off] = disc_errors("disc", 12);
  EXPECT_LE(disc, 0.5);
  EXPECT_LE(off, 0.5);
}

// The same through a coarse video (CRF 28): where the content moves as one,
// a node matches a larger window, whose more pixels average the coding
// noise (0.333 px on the disc with 17 × 17 windows only).
TEST(Track, NodesAverageCodingNoiseOverALargerWindow) {
  const auto [disc, off] = disc_errors("disc-coarse", 28);
  EXPECT_LE(disc, 0.32);
  EXPECT_LE(off, 0.1);
}

// A camera pan over a still scene, lossless: frame t is a window of a
// larger picture whose content moves kPanX right and kPanY down a frame.
constexpr uint32_t kPanWidth = 128, kPanHeight = 96;
constexpr int kPanX = 2, kPanY = 1;
std::vector<Image> panned_video(int frames, uint64_t seed) {
  const Image scene = pattern(kPanWidth + 64, kPanHeight + 32, seed);
  std::vector<Image> video;
  for (int t = 0; t < frames; ++t) {
    Image frame(kPanWidth, kPanHeight);
    const int left = kPanX * (frames - 1 - t), top = kPanY * (frames - 1 - t);
    for (uint32_t y = 0; y < kPanHeight; ++y)
      for (uint32_t x = 0; x < kPanWidth; ++x) frame.at(x, y) = scene.at(x + static_cast<uint32_t>(left), y + static_cast<uint32_t>(top));
    video.push_back(std::move(frame));
  }
  return video;
}

// A camera pan of 24 pixels over 12 frames (the content moves 2 pixels
// right and 1 down a frame), lossless: every node follows the content
// under it, those of the frame's border too; held on the frame, the left
// column stays on the frame's edge.
TEST(Track, BorderNodesFollowAPan) {
  const Workspace folder("pan");
  const uint32_t w = kPanWidth, h = kPanHeight;
  const int frames = 12, vx = kPanX, vy = kPanY;
  write_frames(folder, panned_video(frames, 31));
  for (const bool on_frame : {false, true}) {
    TrackSettings settings;
    settings.tracker.border_on_frame = on_frame;
    settings.remesh_stretch = 0;  // one mesh throughout, however little of the frame it covers
    const TrackResult result = track_video(folder / "%03d.png", settings);
    ASSERT_EQ(result.positions.size(), static_cast<size_t>(frames));
    expect_no_fold(result);
    double sum = 0, left_edge = 0;
    size_t count = 0, on_left = 0;
    for (size_t n = 0; n < result.mesh.tracking.nodes.size(); ++n) {
      const Point& p0 = result.mesh.tracking.nodes[n];
      const Point& p = result.positions.back()[n];
      const double tx = p0.x / 2.0 + vx * (frames - 1), ty = p0.y / 2.0 + vy * (frames - 1);
      if (p0.x == 0) left_edge += p.x / 2.0, ++on_left;
      if (tx > w || ty > h) continue;  // its content has left the frame
      sum += std::hypot(p.x / 2.0 - tx, p.y / 2.0 - ty), ++count;
    }
    left_edge /= static_cast<double>(on_left);
    std::printf("pan of (%d, %d) px a frame, border %s: mean node error %.3f px in the last frame, left column at x = %.1f\n", vx, vy,
                on_frame ? "on the frame" : "following", sum / static_cast<double>(count), left_edge);
    if (on_frame) {
      EXPECT_EQ(left_edge, 0.0);
    } else {
      EXPECT_LE(sum / static_cast<double>(count), 0.25);
      EXPECT_NEAR(left_edge, vx * (frames - 1), 0.5);
      EXPECT_LT(result.frames.back().coverage, 0.9);
    }
  }
}

// A zoom into a still scene, lossless: the content leaves the frame on
// every side, and the nodes near the frame's edge go with it as far as the
// frame shows it.
TEST(Track, BorderNodesFollowAZoom) {
  const Workspace folder("zoom");
  const uint32_t w = 160, h = 120;
  const int frames = 16;
  const double cx = w / 2.0, cy = h / 2.0, rate = 0.01;  // scale 1 + rate · t about the centre
  const Image scene = waves(w, h, 47);
  std::vector<Image> video;
  for (int t = 0; t < frames; ++t) {
    const double scale = 1 + rate * t;
    Image frame(w, h);
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) frame.at(x, y) = bilinear(scene, cx + (x + 0.5 - cx) / scale - 0.5, cy + (y + 0.5 - cy) / scale - 0.5);
    video.push_back(std::move(frame));
  }
  write_frames(folder, video);
  TrackSettings settings;
  settings.remesh_stretch = 0;  // one mesh throughout
  const TrackResult result = track_video(folder / "%03d.png", settings);
  ASSERT_EQ(result.positions.size(), static_cast<size_t>(frames));
  expect_no_fold(result);
  double sum = 0;
  size_t count = 0;
  for (size_t n = 0; n < result.mesh.tracking.nodes.size(); ++n) {
    const double x0 = result.mesh.tracking.nodes[n].x / 2.0, y0 = result.mesh.tracking.nodes[n].y / 2.0;
    if (x0 > 16.5 && y0 > 16.5 && x0 < w - 16.5 && y0 < h - 16.5) continue;  // not within a cell of the frame's edge
    for (int t = 1; t < frames; ++t) {
      const double scale = 1 + rate * t, tx = cx + (x0 - cx) * scale, ty = cy + (y0 - cy) * scale;
      if (tx < 0 || ty < 0 || tx > w || ty > h) continue;  // its content has left the frame
      const Point& p = result.positions[static_cast<size_t>(t)][n];
      sum += std::hypot(p.x / 2.0 - tx, p.y / 2.0 - ty), ++count;
    }
  }
  ASSERT_GT(count, 0u);
  std::printf("zoom to %.2f, lossless: mean error of the nodes within a cell of the edge, in view, %.3f px\n", 1 + rate * (frames - 1), sum / static_cast<double>(count));
  EXPECT_LE(sum / static_cast<double>(count), 0.25);
}

// The same pan over 24 frames with the defaults: once the mesh covers less
// than kLeastCoverage of the frame, a new I-plane lays a mesh on the frame,
// whose texture (below the first in the texture's PNG) render draws there.
TEST(Track, APanPastTheMeshGetsANewIPlane) {
  const Workspace folder("pan-remesh");
  const std::vector<Image> video = panned_video(24, 37);
  write_frames(folder, video);
  const TrackResult result = track_video(folder / "%03d.png", {});
  expect_no_fold(result);
  ASSERT_FALSE(result.remeshes.empty());
  for (const TrackedFrame& f : result.frames) EXPECT_GE(f.coverage, kLeastCoverage) << "frame " << f.frame;
  const size_t plane = result.remeshes.front().plane;
  const std::string frames_in = folder / "%03d.png", stream = folder / "out.m4m", texture = folder / "texture.png", picture = folder / "plane.png";
  std::vector<const char*> track{"m4mesh", "-q", "track", frames_in.c_str(), "-o", stream.c_str(), "--texture", texture.c_str()};
  ASSERT_EQ(run_m4mesh(static_cast<int>(track.size()), track.data()), 0);
  EXPECT_EQ(read_file(stream), result.stream);
  EXPECT_EQ(read_png(texture).height, kPanHeight * (1 + result.remeshes.size()));
  const std::string plane_text = std::to_string(plane);
  std::vector<const char*> render{"m4mesh", "-q", "render", stream.c_str(), "-o", picture.c_str(), "--texture", texture.c_str(), "--plane", plane_text.c_str()};
  ASSERT_EQ(run_m4mesh(static_cast<int>(render.size()), render.data()), 0);
  const Image drawn = read_png(picture);
  EXPECT_EQ(drawn.pixels, video[plane].pixels) << "plane " << plane << ": its I-plane draws its own texture, the frame";
}

// The global motion of a picture zoomed, turned and moved by a known
// affine map, with a patch that moves against it: found to a tenth of a
// pixel over the whole frame (the patch weighs little).
TEST(Track, GlobalMotionFindsAKnownAffineMap) {
  const uint32_t w = 192, h = 144;
  const Image scene = pattern(w, h, 41);
  Affine truth;
  const double zoom = 1.04, angle = 0.03;
  truth.a = {zoom * std::cos(angle), -zoom * std::sin(angle), zoom * std::sin(angle), zoom * std::cos(angle), 6.3, -4.6};
  const Affine back = truth.inverse();
  Image moved(w, h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const bool patch = x >= 20 && x < 50 && y >= 20 && y < 50;  // content moving its own way
      const auto [u, v] = back(x + 0.5 + (patch ? 9 : 0), y + 0.5);
      moved.at(x, y) = bilinear(scene, u - 0.5, v - 0.5);
    }
  const Affine found = global_motion(pyramid(luma_of(scene), 2), pyramid(luma_of(moved), 2), Affine{}, 16);
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {double(w), 0.0}, {0.0, double(h)}, {double(w), double(h)}, {w / 2.0, h / 2.0}}) {
    const auto [ex, ey] = truth(x, y);
    const auto [fx, fy] = found(x, y);
    EXPECT_NEAR(fx, ex, 0.1) << "at " << x << ", " << y;
    EXPECT_NEAR(fy, ey, 0.1) << "at " << x << ", " << y;
  }
}

// A window cut from a picture at a fractional point is found there, between
// the half pixels a descent compares; a flat picture or a point out of
// reach gives none.
TEST(Track, SubpixelFitFindsAWindowBetweenHalfPixels) {
  const Luma picture = luma_of(pattern(120, 100, 7));
  const std::array<double, 2> truth{60.3, 49.8};
  Window window;
  for (int j = -8; j <= 8; ++j)
    for (int i = -8; i <= 8; ++i) window.push_back({double(i), double(j), picture.sample(truth[0] + i, truth[1] + j)});
  const std::optional<std::array<double, 2>> fit = subpixel_fit(picture, window, {60.5, 50.0});
  ASSERT_TRUE(fit);
  EXPECT_NEAR((*fit)[0], truth[0], 0.02);
  EXPECT_NEAR((*fit)[1], truth[1], 0.02);
  EXPECT_FALSE(subpixel_fit(picture, window, {62.5, 50.0}));
  EXPECT_FALSE(subpixel_fit(Luma(120, 100, 128), window, {60.5, 50.0}));
}

TEST(Track, OneFrameIsAStillTexture) {
  const Workspace folder("one");
  write_frames(folder, {pattern(64, 48, 3)});
  const TrackResult result = track_video(folder / "%03d.png", {});
  ASSERT_EQ(result.frames.size(), 1u);
  Decoder decoder(result.stream);
  ASSERT_TRUE(decoder.next());
  EXPECT_TRUE(decoder.info().intra);
  EXPECT_FALSE(decoder.next());
}

// A blank video: nodes spread evenly (nothing has structure), and none moves.
TEST(Track, BlankVideoGivesAnEvenMeshThatStaysStill) {
  const Workspace folder("blank");
  write_frames(folder, std::vector<Image>(4, Image(64, 48, Rgb{90, 90, 90})));
  TrackSettings settings;
  settings.nodes = 30;
  const TrackResult result = track_video(folder / "%03d.png", settings);
  ASSERT_EQ(result.positions.size(), 4u);
  EXPECT_GE(result.mesh.tracking.nodes.size(), 25u);
  for (const std::vector<Point>& frame : result.positions) EXPECT_EQ(frame, result.mesh.tracking.nodes);
}

template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(Track, DegenerateInputsGiveClearErrors) {
  const Workspace folder("errors");
  write_frames(folder, std::vector<Image>(2, pattern(8, 8, 5)));
  EXPECT_NE(error_of([&] { track_video(folder / "%03d.png", {}); }).find("smaller than one 16 × 16 mesh cell"), std::string::npos);

  const std::string garbage = folder / "garbage.mp4";
  std::ofstream(garbage) << std::string(5000, 'x');
  EXPECT_NE(error_of([&] { track_video(garbage, {}); }).find(garbage + ": not a video FFmpeg can read"), std::string::npos);
  EXPECT_NE(error_of([&] { track_video(folder / "missing.mp4", {}); }).find("No such file"), std::string::npos);

  // A video cut short: fewer frames than it states, never a shorter object.
  const WarpedVideo video(64, 48, 8, SmoothMotion{64, 48});
  const std::vector<uint8_t> whole = read_file(h264_video(folder, video.frames));
  const std::string cut = folder / "cut.mp4";
  write_file_atomically(cut, std::string_view(reinterpret_cast<const char*>(whole.data()), whole.size() * 3 / 4));
  EXPECT_NE(error_of([&] { track_video(cut, {}); }), "no error");

  TrackSettings past_end;
  past_end.first_frame = 20;
  EXPECT_NE(error_of([&] { track_video(folder / "%03d.png", past_end); }).find("--frames starts at frame 20"), std::string::npos);
  TrackSettings ends_late;
  ends_late.end_frame = 12;  // --frames 0:11 of the 8 frames h264_video left there
  EXPECT_NE(error_of([&] { track_video(folder / "%03d.png", ends_late); }).find("8 frames; --frames ends at frame 11"), std::string::npos);
}

// A natural video: a tree in the wind (OpenCV's sample tree.avi, Debian's
// opencv-doc, Cinepak). The mesh's motion compensation keeps up with block
// matching at as many vectors.
TEST(Track, NaturalVideo) {
  const std::string tree = "/usr/share/doc/opencv-doc/examples/data/tree.avi";
  if (!fs::exists(tree)) GTEST_SKIP() << tree << " is absent (Debian's opencv-doc; scripts/install-deps.sh installs it)";
  TrackSettings settings;
  settings.end_frame = 12;
  const TrackResult result = track_video(tree, settings);
  ASSERT_EQ(result.positions.size(), 12u);
  expect_no_fold(result);
  double render = 0, mesh = 0, block = 0;
  for (size_t t = 1; t < result.frames.size(); ++t) render += result.frames[t].render_psnr, mesh += result.frames[t].mesh_psnr, block += result.frames[t].block_psnr;
  render /= 11, mesh /= 11, block /= 11;
  std::printf("tree.avi, frames 0 … 11: rendering %.2f dB, mesh MC %.2f dB, block MC %.2f dB\n", render, mesh, block);
  EXPECT_GT(render, 25);
  EXPECT_GT(mesh, block - 1);
}

}  // namespace
}  // namespace m4mesh
