#include "cli/demo.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>

#include "cli/console.h"
#include "decoder/mesh_object_decoder.h"
#include "encoder/mesh_object_encoder.h"
#include "render/texture_warp.h"

namespace m4mesh {

MeshPlane waving_flag_plane(const DemoOptions& options, uint32_t t) {
  UniformParams grid{options.cols, options.rows, options.spacing, options.spacing, 0};
  MeshPlane plane;
  plane.nodes = uniform_nodes(grid);
  if (t == 0) {
    plane.info.kind = MeshKind::kUniform;
    plane.info.uniform = grid;
    return plane;
  }
  plane.info.intra = false;
  const double amplitude = 1.5 * options.spacing;
  for (uint32_t r = 0; r < options.rows; ++r)
    for (uint32_t c = 0; c < options.cols; ++c) {
      // The wave travels away from the pole (c = 0) and grows with c.
      const double free_end = static_cast<double>(c) / (options.cols - 1);
      const double phase = 2 * std::numbers::pi * (1.5 * free_end - t / 30.0) + 0.3 * r / options.rows;
      Point& p = plane.nodes[r * options.cols + c];
      p.x += static_cast<int32_t>(std::lround(0.25 * amplitude * free_end * (std::cos(phase) - 1)));
      p.y += static_cast<int32_t>(std::lround(amplitude * free_end * std::sin(phase)));
    }
  return plane;
}

int run_demo(const DemoOptions& options) {
  using Clock = std::chrono::steady_clock;
  const double node_frames = static_cast<double>(options.cols) * options.rows * static_cast<double>(options.frames);
  std::printf("m4mesh demo: waving flag, uniform %ux%u nodes, %u planes\n", options.cols, options.rows, options.frames);

  // The planes are made as they are coded, and again to check each decoded
  // one (making them is not timed).
  double encode_s = 0, decode_s = 0;
  Encoder encoder;
  console::Progress encoding("encoding plane", options.frames);
  for (uint32_t t = 0; t < options.frames; ++t) {
    encoding.update(t + 1);
    const MeshPlane plane = waving_flag_plane(options, t);
    const auto start = Clock::now();
    encoder.add(plane);
    encode_s += std::chrono::duration<double>(Clock::now() - start).count();
  }
  auto start = Clock::now();
  const EncodeResult encoded = encoder.finish();
  encode_s += std::chrono::duration<double>(Clock::now() - start).count();
  // The picture: every plane fits the rectangle of all of them.
  Canvas canvas;
  std::optional<GifWriter> gif;
  std::optional<Image> texture;
  std::optional<TextureWarp> warp;
  if (!options.gif.empty()) {
    console::check_output(options.gif);
    for (uint32_t t = 0; t < options.frames; ++t) canvas = united(canvas, canvas_over(waving_flag_plane(options, t).nodes));
    gif.emplace(options.gif, canvas.width, canvas.height, 4);
  }
  Decoder decoder(encoded.stream);
  uint32_t k = 0;
  bool exact = true;
  console::Progress decoding("decoding plane", options.frames);
  for (start = Clock::now(); decoder.next(); start = Clock::now()) {
    decoding.update(k + 1);
    decode_s += std::chrono::duration<double>(Clock::now() - start).count();
    if (k < options.frames) {
      const MeshPlane plane = waving_flag_plane(options, k);
      exact = exact && std::equal(decoder.nodes().begin(), decoder.nodes().end(), plane.nodes.begin(), plane.nodes.end());
    }
    if (gif) {
      if (decoder.info().intra) {
        const Canvas box = canvas_over(decoder.nodes());
        texture = checkerboard(box.width, box.height);
        warp.emplace(decoder.nodes(), decoder.triangles(), *texture, canvas);
      }
      gif->add(warp->render(decoder.nodes(), false));
    }
    ++k;
  }
  decode_s += std::chrono::duration<double>(Clock::now() - start).count();
  exact = exact && k == options.frames;

  const double bits = 8.0 * static_cast<double>(encoded.stream.size());
  std::printf("stream: %zu bytes (%lld I-plane, %lld P-planes)\n", encoded.stream.size(),
              static_cast<long long>(encoded.intra_planes), static_cast<long long>(encoded.inter_planes));
  std::printf("rate: %.4f bits per node per frame\n", bits / node_frames);
  std::printf("encode: %.3f ms, %.1f M nodes/s\n", encode_s * 1e3, node_frames / encode_s / 1e6);
  std::printf("decode: %.3f ms, %.1f M nodes/s\n", decode_s * 1e3, node_frames / decode_s / 1e6);
  std::printf("decoded positions %s the input: %s\n", exact ? "match" : "DIFFER FROM", exact ? "bit-exact" : "FAILED");
  if (gif) {
    gif->finish();
    std::printf("picture: %s, the decoded planes warping a checkerboard, %u × %u pixels\n", options.gif.c_str(), canvas.width, canvas.height);
  }
  return exact ? 0 : 1;
}

}  // namespace m4mesh
