#include "cli/pictures.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>

#include "cli/console.h"
#include "cli/sequence_files.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "decoder/mesh3d/container_decoder.h"
#include "decoder/mesh_object_decoder.h"
#include "encoder/mesh3d/base_mesh.h"
#include "render/shaded.h"
#include "render/texture_warp.h"
#include "syntax/mesh3d/container.h"

namespace m4mesh {

namespace {

// The picture's form from its name: a GIF of every frame or a PNG of one.
bool gif_output(const std::string& output, const char* command) {
  const std::string extension = std::filesystem::path(output).extension().string();
  if (extension != ".gif" && extension != ".png")
    throw usage_error(output + ": " + command + " writes .gif (every frame) or .png (one frame)");
  return extension == ".gif";
}

uint32_t gif_delay(double fps) {
  if (!(fps > 0 && fps <= 100)) throw usage_error("--fps: 0 < fps ≤ 100");
  return static_cast<uint32_t>(std::lround(100.0 / fps));
}

// A stream's codec and rate ("bfs3d 2.350 BPVF"), empty for a sequence.
std::string stream_label(const StreamFacts& facts, const MeshSequence& decoded) {
  if (facts.codec.empty()) return "";
  char text[96];
  std::snprintf(text, sizeof text, "%s %.3f BPVF", facts.codec.c_str(),
                8.0 * static_cast<double>(facts.bytes) / (static_cast<double>(decoded.vertex_count) * static_cast<double>(decoded.frames.size())));
  return text;
}

// A file's size for people: "6.4 MB", "812 kB", "96 bytes".
std::string size_text(const std::string& path) {
  const double bytes = static_cast<double>(std::filesystem::file_size(path));
  char text[32];
  if (bytes >= 1e6)
    std::snprintf(text, sizeof text, "%.1f MB", bytes / 1e6);
  else if (bytes >= 1e3)
    std::snprintf(text, sizeof text, "%.0f kB", bytes / 1e3);
  else
    std::snprintf(text, sizeof text, "%.0f bytes", bytes);
  return text;
}

std::string fps_text(double fps) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", fps);
  return text;
}

// Where a texture lies: over the I-plane's pixels, one texel a pixel when
// they are the same size to a pixel (a mesh over a video frame reaches its
// far edge, one pixel past the last pixel's centre).
Canvas texture_box(const Canvas& plane, const Image& texture) {
  auto near = [](uint32_t a, uint32_t b) { return a <= b + 1 && b <= a + 1; };
  return near(plane.width, texture.width) && near(plane.height, texture.height) ? Canvas{plane.x0, plane.y0, texture.width, texture.height} : plane;
}

// Each I-plane's texture: a texture made for several (its kIntraPlanesText
// `list`, its kIntraColumnsText `columns`) cut into theirs, else the one
// texture for every I-plane.
std::map<uint32_t, Image> textures_by_plane(const std::string& path, const std::string& list, const std::string& columns, Image texture) {
  if (list.empty()) return {{0, std::move(texture)}};
  std::vector<uint32_t> planes;
  std::istringstream in(list);
  bool increasing = true;
  for (uint32_t plane = 0; in >> plane;) {
    increasing = increasing && (planes.empty() || plane > planes.back());
    planes.push_back(plane);
  }
  const unsigned long grid_columns = columns.empty() ? 1 : std::strtoul(columns.c_str(), nullptr, 10);
  const size_t grid_rows = grid_columns == 0 ? 0 : (planes.size() + grid_columns - 1) / grid_columns;
  if (grid_columns == 0 || grid_columns > texture.width || texture.width % grid_columns != 0 || std::to_string(grid_columns) != (columns.empty() ? "1" : columns))
    throw input_error(path, 0, "its '" + std::string(kIntraColumnsText) + "' text \"" + columns + "\" is not a number of equal columns of its width");
  if (!in.eof() || !increasing || planes.empty() || planes.front() != 0 || texture.height % grid_rows != 0)
    throw input_error(path, 0, "its '" + std::string(kIntraPlanesText) + "' text \"" + list + "\" does not list increasing planes from 0, one per equal part of its " +
                                   (grid_columns == 1 ? "height" : std::to_string(grid_columns) + " columns"));
  std::vector<Image> tiles = untiled(texture, TileGrid{static_cast<uint32_t>(grid_columns), static_cast<uint32_t>(grid_rows)}, planes.size());
  std::map<uint32_t, Image> out;
  for (size_t k = 0; k < planes.size(); ++k) out.emplace(planes[k], std::move(tiles[k]));
  return out;
}

}  // namespace

int run_render(const RenderArgs& args) {
  const bool to_gif = gif_output(args.output, "render");
  std::optional<Image> texture;
  std::map<uint32_t, Image> textures;
  std::string intra_planes;  // the texture's kIntraPlanesText: a texture for each I-plane
  double fps = args.fps.value_or(25);
  if (!args.texture.empty()) {
    intra_planes = png_text(args.texture, kIntraPlanesText);
    textures = textures_by_plane(args.texture, intra_planes, png_text(args.texture, kIntraColumnsText), read_png(args.texture));
    texture = textures.at(0);
    if (const std::string rate = png_text(args.texture, kFrameRateText); !args.fps && !rate.empty()) fps = std::strtod(rate.c_str(), nullptr);
  }
  const uint32_t delay = gif_delay(fps);
  refuse_overwriting(args.input, args.output);
  const std::vector<uint8_t> stream = read_file(args.input);
  if (is_mesh3d_stream(stream))
    throw usage_error(args.input + ": a mesh3d stream; render draws 2D mesh streams");
  // First pass: the rectangle every plane fits in (the texture's, at the
  // first I-plane's corner, when there is one: the video's frame), and the
  // plane count.
  Canvas canvas, first;
  uint32_t planes = 0;
  for (Decoder decoder(stream); decoder.next(); ++planes) {
    const Canvas plane = canvas_over(decoder.nodes());
    if (planes == 0) first = plane;
    canvas = united(canvas, plane);
  }
  if (texture) canvas = {first.x0, first.y0, texture->width, texture->height};
  if (!to_gif && args.plane >= planes)
    throw usage_error("--plane " + std::to_string(args.plane) + ": the stream has planes 0 … " + std::to_string(planes - 1));
  if (canvas.width > 8192 || canvas.height > 8192)
    throw usage_error(args.input + ": the planes span " + std::to_string(canvas.width) + " × " + std::to_string(canvas.height) +
                    " pixels; render draws up to 8192 × 8192");
  if (args.size != 0 && (args.size < 16 || args.size > 8192)) throw usage_error("--size: 16 … 8192 pixels");
  const double zoom = args.size == 0 ? 1.0 : static_cast<double>(args.size) / std::max(canvas.width, canvas.height);
  const uint32_t width = std::max<uint32_t>(1, static_cast<uint32_t>(std::lround(canvas.width * zoom)));
  const uint32_t height = std::max<uint32_t>(1, static_cast<uint32_t>(std::lround(canvas.height * zoom)));
  auto sized = [&](const Image& picture) { return args.size == 0 ? picture : resized(picture, width, height); };
  // Second pass: each plane drawn as it is decoded.
  std::optional<TextureWarp> warp;
  std::optional<GifWriter> gif;
  if (to_gif) gif.emplace(args.output, width, height, delay);
  console::Progress progress("rendering plane", planes);
  Decoder decoder(stream);
  for (uint32_t k = 0; decoder.next(); ++k) {
    progress.update(k + 1);
    if (decoder.info().intra) {
      if (!intra_planes.empty()) {
        const auto own = textures.find(k);
        if (own == textures.end())
          throw input_error(args.texture, 0, "holds no texture for the I-plane at plane " + std::to_string(k) + " (its '" + kIntraPlanesText + "': " +
                                                 intra_planes + ")");
        texture = own->second;
      }
      if (!texture) {
        const Canvas box = canvas_over(decoder.nodes());
        texture = checkerboard(box.width, box.height);
      }
      warp.emplace(decoder.nodes(), decoder.triangles(), *texture, texture_box(canvas_over(decoder.nodes()), *texture), canvas);
    }
    if (gif) {
      gif->add(sized(warp->render(decoder.nodes(), args.wireframe)));
    } else if (k == args.plane) {
      write_png(sized(warp->render(decoder.nodes(), args.wireframe)), args.output);
      break;
    }
  }
  if (gif) gif->finish();
  console::say("%s: %s, %u × %u pixels%s, %s", args.output.c_str(),
               gif ? console::counted(static_cast<uint64_t>(planes), "plane", "planes").c_str() : ("plane " + std::to_string(args.plane)).c_str(), width, height,
               gif ? (" at " + fps_text(fps) + " frames/s").c_str() : "", size_text(args.output).c_str());
  return 0;
}

int run_render3d(const Render3dArgs& args) {
  const bool gif = gif_output(args.output, "render3d");
  const uint32_t delay = gif_delay(args.fps);
  if (args.size < 16 || args.size > 4096) throw usage_error("--size: 16 … 4096 pixels");
  if (args.max_error && !(std::isfinite(*args.max_error) && *args.max_error > 0))
    throw usage_error("--max-error: a finite error above 0");
  if (args.max_error && args.compare.empty()) throw usage_error("--max-error colours the error: it needs --compare");
  refuse_overwriting(args.input, args.output);
  if (!args.compare.empty()) refuse_overwriting(args.compare, args.output);
  StreamFacts facts;
  const MeshSequence shown = load_sequence_or_stream(args.input, &facts);
  MeshSequence original;
  if (!args.compare.empty()) {
    original = original_as_decoded(load_sequence_or_stream(args.compare), shown, facts.coding_order, args.input);
    if (original.vertex_count != shown.vertex_count || original.frames.size() != shown.frames.size())
      throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                  args.compare + ": " + std::to_string(original.vertex_count) + " vertices, " + std::to_string(original.frames.size()) +
                      " frames; " + args.input + " has " + std::to_string(shown.vertex_count) + " and " + std::to_string(shown.frames.size()));
    // Vertex i of one must be vertex i of the other, or the error map is false.
    if (!same_faces(original.faces, shown.faces))
      throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                  args.compare + " and " + args.input + " have other faces (or the same faces numbered otherwise): not a sequence and its decoding");
  }
  if (!gif && args.frame >= shown.frames.size())
    throw usage_error("--frame " + std::to_string(args.frame) + ": the sequence has frames 0 … " + std::to_string(shown.frames.size() - 1));
  const bool compare = !args.compare.empty();
  const std::vector<std::pair<Vec3, Vec3>> boxes = view_boxes(compare ? original : shown, args.view);
  auto error_at = [&](size_t f, uint32_t i) {
    const Vec3& a = shown.frames[f][i];
    const Vec3& b = original.frames[f][i];
    return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
  };
  // The colour scale: --max-error (one scale across pictures), else the
  // largest error of the whole sequence, so that frames compare.
  double max_error = 0;
  if (compare)
    for (size_t f = 0; f < shown.frames.size(); ++f)
      for (uint32_t i = 0; i < shown.vertex_count; ++i) max_error = std::max(max_error, error_at(f, i));
  const double scale = args.max_error ? *args.max_error : max_error;
  const std::string label = stream_label(facts, shown);
  const uint32_t width = compare ? 2 * args.size + 80 : args.size;
  Image image(width, args.size);
  auto draw = [&](size_t f) {
    const Camera camera(boxes[f].first, boxes[f].second, args.azimuth, args.elevation, args.size);
    if (!compare) {
      draw_shaded(image, 0, camera, shown.frames[f], shown.faces);
    } else {
      std::vector<Rgb> colours(shown.vertex_count);
      for (uint32_t i = 0; i < shown.vertex_count; ++i) colours[i] = error_colour(scale > 0 ? error_at(f, i) / scale : 0);
      draw_shaded(image, 0, camera, original.frames[f], original.faces);
      draw_shaded(image, args.size, camera, shown.frames[f], shown.faces, colours);
      draw_legend(image, 2 * args.size, scale);
      draw_text(image, 8, 8, "ORIGINAL", 2);
    }
    const uint32_t right = compare ? args.size : 0;
    if (compare) draw_text(image, right + 8, 8, "DECODED", 2);
    if (!label.empty()) draw_text(image, right + 8, compare ? 22 : 8, label, 2);
    draw_text(image, 8, args.size - 18, "FRAME " + std::to_string(f), 2);
  };
  if (!gif) {
    draw(args.frame);
    write_png(image, args.output);
  } else {
    GifWriter writer(args.output, width, args.size, delay);
    console::Progress progress("rendering frame", shown.frames.size());
    for (size_t f = 0; f < shown.frames.size(); ++f) {
      progress.update(f + 1);
      draw(f);
      writer.add(image);
    }
    writer.finish();
  }
  console::say("%s: %u × %u pixels%s, %s", args.output.c_str(), width, args.size,
               compare ? (", largest error " + std::to_string(max_error) + (args.max_error ? ", colours up to " + std::to_string(scale) : "")).c_str() : "",
               size_text(args.output).c_str());
  return 0;
}

}  // namespace m4mesh
