#include "cli/pictures.h"

#include <cmath>
#include <filesystem>
#include <optional>

#include "cli/commands3d.h"
#include "cli/console.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "decoder/decoder.h"
#include "render/texture_warp.h"
#include "syntax/mesh3d/container.h"

namespace m4mesh {

int run_render(const RenderArgs& args) {
  namespace fs = std::filesystem;
  refuse_overwriting(args.input, args.output);
  const std::string extension = fs::path(args.output).extension().string();
  if (extension != ".gif" && extension != ".png")
    throw Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset, args.output + ": render writes .gif (every plane) or .png (--plane K)");
  if (!(args.fps > 0 && args.fps <= 100)) throw Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset, "--fps: 0 < fps ≤ 100");
  console::check_output(args.output);
  const std::vector<uint8_t> stream = read_file(args.input);
  if (is_mesh3d_stream(stream))
    throw Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset, args.input + ": a mesh3d stream; render draws 2D mesh streams");
  // First pass: the rectangle every plane fits in, and the plane count.
  Canvas canvas;
  uint32_t planes = 0;
  for (Decoder decoder(stream); decoder.next(); ++planes) canvas = united(canvas, canvas_over(decoder.nodes()));
  if (args.output.ends_with(".png") && args.plane >= planes)
    throw Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset,
                "--plane " + std::to_string(args.plane) + ": the stream has planes 0 … " + std::to_string(planes - 1));
  if (canvas.width > 8192 || canvas.height > 8192)
    throw Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset,
                args.input + ": the planes span " + std::to_string(canvas.width) + " × " + std::to_string(canvas.height) +
                    " pixels; render draws up to 8192 × 8192");
  // Second pass: each plane drawn as it is decoded.
  std::optional<Image> texture;
  if (!args.texture.empty()) texture = read_png(args.texture);
  std::optional<TextureWarp> warp;
  std::optional<GifWriter> gif;
  if (extension == ".gif")
    gif.emplace(args.output, canvas.width, canvas.height, static_cast<uint32_t>(std::lround(100.0 / args.fps)));
  console::Progress progress("rendering plane", planes);
  Decoder decoder(stream);
  for (uint32_t k = 0; decoder.next(); ++k) {
    progress.update(k + 1);
    if (decoder.info().intra) {
      if (!texture) {
        const Canvas box = canvas_over(decoder.nodes());
        texture = checkerboard(box.width, box.height);
      }
      warp.emplace(decoder.nodes(), decoder.triangles(), *texture, canvas);
    }
    if (gif) {
      gif->add(warp->render(decoder.nodes(), args.wireframe));
    } else if (k == args.plane) {
      write_png(warp->render(decoder.nodes(), args.wireframe), args.output);
      break;
    }
  }
  if (gif) gif->finish();
  console::say("%s: %s, %u × %u pixels", args.output.c_str(), gif ? (std::to_string(planes) + " planes").c_str() : ("plane " + std::to_string(args.plane)).c_str(),
               canvas.width, canvas.height);
  return 0;
}

}  // namespace m4mesh
