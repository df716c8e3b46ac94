#include "video/track.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "common/error.h"
#include "decoder/mesh_object_decoder.h"
#include "encoder/mesh_object_encoder.h"
#include "render/texture_warp.h"
#include "video/block_matching.h"

namespace m4mesh {

namespace {

[[noreturn]] void refuse(ErrorKind kind, const std::string& message) { throw Error(kind, "", kNoPlane, kNoOffset, message); }

// Blocks of side × side pixels holding a covered pixel.
uint32_t blocks_over(uint32_t side, const std::vector<uint8_t>& covered, uint32_t width, uint32_t height) {
  uint32_t count = 0;
  for (uint32_t by = 0; by < height; by += side)
    for (uint32_t bx = 0; bx < width; bx += side) {
      bool any = false;
      for (uint32_t y = by; y < std::min(by + side, height) && !any; ++y)
        for (uint32_t x = bx; x < std::min(bx + side, width) && !any; ++x) any = covered[size_t{y} * width + x] != 0;
      count += any;
    }
  return count;
}

// The block side (4 … 64) whose blocks over the covered pixels come nearest to `vectors`.
uint32_t matching_block(uint32_t vectors, const std::vector<uint8_t>& covered, uint32_t width, uint32_t height) {
  uint32_t best = 4;
  int64_t best_gap = std::numeric_limits<int64_t>::max();
  for (uint32_t side = 4; side <= 64; ++side)
    if (const int64_t gap = std::abs(int64_t{blocks_over(side, covered, width, height)} - vectors); gap < best_gap) best_gap = gap, best = side;
  return best;
}

}  // namespace

Mask mask_from_image(const Image& picture, uint32_t width, uint32_t height) {
  const Image sized = picture.width == width && picture.height == height ? picture : resized(picture, width, height);
  Mask mask{width, height, std::vector<uint8_t>(size_t{width} * height)};
  for (size_t i = 0; i < sized.pixels.size(); ++i) {
    const Rgb& p = sized.pixels[i];
    mask.inside[i] = p.r + p.g + p.b > 3 * 127;
  }
  return mask;
}

TrackResult track_video(const std::string& path, const TrackSettings& settings) {
  if (settings.first_frame < 0 || (settings.end_frame >= 0 && settings.end_frame <= settings.first_frame))
    refuse(ErrorKind::kUsage, "--frames A:B: 0 ≤ A < B");
  if (settings.mask && settings.nodes == 0) refuse(ErrorKind::kUsage, "--mask outlines a content-based Delaunay mesh: give --nodes N");
  VideoReader reader(path, kMaxMeshFrameSide);
  TrackResult result;
  result.video = reader.info();
  const uint32_t w = result.video.width, h = result.video.height;
  Image frame, previous;
  Luma previous_luma;
  while (reader.frames_read() <= settings.first_frame)
    if (!reader.next(frame))
      refuse(ErrorKind::kInput, reader.frames_read() == 0 ? path + ": no frame could be read"
                                                          : path + ": " + std::to_string(reader.frames_read()) + " frames; --frames starts at frame " +
                                                                std::to_string(settings.first_frame));

  // The mesh on the first frame (the mask's object there), and again on a later frame when the tracked one degrades.
  Luma luma = luma_of(frame);
  std::optional<Mask> mask;
  if (settings.mask) {
    const Image& m = *settings.mask;
    const bool coded_size = m.width == result.video.coded_width && m.height == result.video.coded_height;
    if (!coded_size && (m.width != w || m.height != h))
      refuse(ErrorKind::kUsage, "the mask is " + std::to_string(m.width) + " × " + std::to_string(m.height) + " pixels, the video " +
                                    std::to_string(result.video.coded_width) + " × " + std::to_string(result.video.coded_height));
    mask = mask_from_image(m, w, h);
  }
  auto design = [&](const Luma& on, const Mask* object) {
    return settings.nodes > 0 ? content_frame_mesh(on, settings.nodes, object) : uniform_frame_mesh(w, h, settings.cell_width, settings.cell_height);
  };
  result.mesh = design(luma, mask ? &*mask : nullptr);
  result.texture = frame;
  const bool remeshing = settings.remesh_stretch > 0 && !mask;

  // The mesh in force, its texture (the frame it was laid on, one texel a
  // pixel: the mesh reaches one pixel past the last pixel's centre, and
  // render lays such a texture so too) and its triangles' areas there.
  const Canvas frame_canvas{0, 0, w, h};
  const FrameMesh* mesh = &result.mesh;
  Image texture = frame;
  std::optional<TextureWarp> texture_warp;
  std::vector<int64_t> design_area;
  std::optional<NodeTracker> tracker;
  auto lay_out = [&](const FrameMesh& laid) {
    mesh = &laid;
    texture_warp.emplace(laid.tracking.nodes, laid.tracking.triangles, texture, frame_canvas, frame_canvas);
    design_area.clear();
    for (const Triangle& t : laid.tracking.triangles) design_area.push_back(orient(laid.tracking.nodes[t.v[0]], laid.tracking.nodes[t.v[1]], laid.tracking.nodes[t.v[2]]));
    tracker.emplace(laid.tracking, luma, settings.tracker);
  };
  lay_out(result.mesh);
  result.levels = tracker->levels();

  std::vector<uint8_t> covered;
  // Frame `result.positions.size()` with the nodes at `at`: its rendering, and its motion compensation from the frame before unless `intra`.
  auto measure = [&](const std::vector<Point>& at, bool intra) {
    TrackedFrame report;
    report.frame = settings.first_frame + static_cast<int64_t>(result.positions.size());
    report.intra = intra;
    const Image rendered = texture_warp->render(at, false, &covered);
    report.coverage = static_cast<double>(std::count(covered.begin(), covered.end(), 1)) / static_cast<double>(covered.size());
    report.render_psnr = psnr(luma, luma_of(rendered), covered);
    for (size_t t = 0; t < design_area.size(); ++t) {
      const Triangle& tri = mesh->tracking.triangles[t];
      const double ratio = static_cast<double>(orient(at[tri.v[0]], at[tri.v[1]], at[tri.v[2]])) / static_cast<double>(design_area[t]);
      report.stretch = std::max({report.stretch, ratio, 1 / ratio});
      report.strained += std::max(ratio, 1 / ratio) > settings.remesh_stretch;
    }
    report.strained /= static_cast<double>(std::max<size_t>(1, design_area.size()));
    report.mesh_psnr = report.block_psnr = std::numeric_limits<double>::quiet_NaN();
    if (!intra) {
      const std::vector<Point>& before = result.positions.back();
      const TextureWarp motion(before, mesh->tracking.triangles, previous, frame_canvas, frame_canvas);
      std::vector<uint8_t> moved_over;
      report.mesh_psnr = psnr(luma, luma_of(motion.render(at, false, &moved_over)), moved_over);
      const BlockPrediction blocks = block_prediction(previous, previous_luma, luma, result.block, settings.tracker.search);
      report.block_psnr = psnr(luma, luma_of(blocks.picture), moved_over);
    }
    return report;
  };
  result.frames.push_back(measure(result.mesh.tracking.nodes, true));
  result.positions.push_back(result.mesh.tracking.nodes);
  result.block = settings.block != 0 ? settings.block : matching_block(static_cast<uint32_t>(result.mesh.tracking.nodes.size()), covered, w, h);
  result.blocks = blocks_over(result.block, covered, w, h);

  // Every later frame; a new I-plane where the tracked mesh degrades.
  const int64_t stated_end = result.video.frames > 0 ? result.video.frames : -1;
  const int64_t end = settings.end_frame >= 0 && stated_end >= 0 ? std::min(settings.end_frame, stated_end) : std::max(settings.end_frame, stated_end);
  const int64_t total = end >= 0 ? std::max<int64_t>(1, end - settings.first_frame) : 0;
  if (settings.progress) settings.progress(1, total);
  bool out_of_room = false, too_soon = false;
  size_t mesh_laid_at = 0;  // the plane of the mesh in force
  while (settings.end_frame < 0 || reader.frames_read() < settings.end_frame) {
    previous = std::move(frame);
    previous_luma = std::move(luma);
    if (!reader.next(frame)) break;
    luma = luma_of(frame);
    const std::vector<Point>& at = tracker->track(luma);
    TrackedFrame report = measure(at, false);
    const bool degraded = remeshing && (report.strained > kMostStrained || report.coverage < kLeastCoverage);
    const bool due = degraded && result.positions.size() - mesh_laid_at >= kFewestPlanesPerMesh;
    if (degraded && !due && !too_soon) {
      too_soon = true;
      result.warnings.push_back("the mesh laid out on frame " + std::to_string(result.frames[mesh_laid_at].frame) + " degrades by frame " +
                                std::to_string(report.frame) + ", within " + std::to_string(kFewestPlanesPerMesh) +
                                " frames: tracking this content strains it, and no new I-plane comes sooner (--remesh 0: none; --nodes N: a mesh laid "
                                "on the content)");
    }
    // Every I-plane's texture goes into one PNG of at most kMostPictureSide on either side.
    const bool room = tile_grid(result.remeshes.size() + 2, w, h).has_value();
    if (due && !room && !out_of_room) {
      out_of_room = true;
      result.warnings.push_back("no more I-planes from frame " + std::to_string(report.frame) + ": their textures would pass " +
                                std::to_string(kMostPictureSide) + " × " + std::to_string(kMostPictureSide) + " pixels in one PNG");
    }
    if (due && room) {
      mesh_laid_at = result.positions.size();
      result.remeshes.push_back({result.positions.size(), design(luma, nullptr), frame});
      texture = frame;
      lay_out(result.remeshes.back().mesh);  // `mesh` points into result.remeshes until the next push_back
      report = measure(mesh->tracking.nodes, true);
      result.positions.push_back(mesh->tracking.nodes);
    } else {
      result.positions.push_back(at);
    }
    result.frames.push_back(report);
    if (settings.progress) settings.progress(static_cast<int64_t>(result.positions.size()), total);
  }
  if (result.video.frames > 0 && reader.frames_read() < result.video.frames && (settings.end_frame < 0 || settings.end_frame > reader.frames_read()))
    result.warnings.push_back(path + " states " + std::to_string(result.video.frames) + " frames; it ends after " + std::to_string(reader.frames_read()));
  if (settings.end_frame >= 0 && reader.frames_read() < settings.end_frame)
    refuse(ErrorKind::kInput, path + ": " + std::to_string(reader.frames_read()) + " frames; --frames ends at frame " + std::to_string(settings.end_frame - 1));

  // The stream, and each plane's bits as the decoder reads it back.
  std::vector<MeshPlane> planes;
  auto remesh = result.remeshes.begin();
  for (size_t f = 0; f < result.positions.size(); ++f) {
    if (f == 0) {
      planes.push_back(result.mesh.plane);
    } else if (remesh != result.remeshes.end() && remesh->plane == f) {
      planes.push_back(remesh++->mesh.plane);
    } else {
      planes.push_back(inter_plane(result.positions[f]));
    }
  }
  result.stream = encode(planes).stream;
  Decoder decoder(result.stream);
  uint64_t start = decoder.bit_position();  // each plane from its start code, as `info` counts it
  for (size_t f = 0; f < result.frames.size(); ++f) {
    if (!decoder.next() || decoder.info().intra != planes[f].info.intra)
      throw std::logic_error("track: the stream does not read back plane by plane");
    const std::vector<Point>& expected = result.positions[f];
    if (!std::equal(expected.begin(), expected.end(), decoder.nodes().begin(), decoder.nodes().end()))
      throw std::logic_error("track: a decoded plane differs from the tracked nodes");
    result.frames[f].bits = decoder.bit_position() - start;
    start = decoder.bit_position();
  }
  return result;
}

const FrameMesh& mesh_at(const TrackResult& result, size_t plane) {
  const FrameMesh* in_force = &result.mesh;
  for (const Remesh& r : result.remeshes)
    if (r.plane <= plane) in_force = &r.mesh;
  return *in_force;
}

}  // namespace m4mesh
