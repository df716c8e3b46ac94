#include "cli/demo.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "decoder/decoder.h"
#include "encoder/encoder.h"

namespace m4mesh {

std::vector<MeshPlane> waving_flag(const DemoOptions& options) {
  UniformParams grid{options.cols, options.rows, options.spacing, options.spacing, 0};
  std::vector<MeshPlane> planes;
  MeshPlane intra;
  intra.info.kind = MeshKind::kUniform;
  intra.info.uniform = grid;
  intra.nodes = uniform_nodes(grid);
  planes.push_back(intra);
  const double amplitude = 1.5 * options.spacing;
  for (uint32_t t = 1; t < options.frames; ++t) {
    MeshPlane inter;
    inter.info.intra = false;
    inter.nodes = intra.nodes;
    for (uint32_t r = 0; r < options.rows; ++r) {
      for (uint32_t c = 0; c < options.cols; ++c) {
        // The wave travels away from the pole (c = 0) and grows with c.
        const double free_end = static_cast<double>(c) / (options.cols - 1);
        const double phase = 2 * std::numbers::pi * (1.5 * free_end - t / 30.0) + 0.3 * r / options.rows;
        Point& p = inter.nodes[r * options.cols + c];
        p.x += static_cast<int32_t>(std::lround(0.25 * amplitude * free_end * (std::cos(phase) - 1)));
        p.y += static_cast<int32_t>(std::lround(amplitude * free_end * std::sin(phase)));
      }
    }
    planes.push_back(std::move(inter));
  }
  return planes;
}

int run_demo(const DemoOptions& options) {
  using Clock = std::chrono::steady_clock;
  const std::vector<MeshPlane> planes = waving_flag(options);
  const double node_frames = static_cast<double>(options.cols) * options.rows * static_cast<double>(planes.size());
  std::printf("m4mesh demo: waving flag, uniform %ux%u nodes, %zu planes\n", options.cols, options.rows, planes.size());

  const auto t0 = Clock::now();
  const EncodeResult encoded = encode(planes);
  const auto t1 = Clock::now();
  Decoder decoder(encoded.stream);
  size_t k = 0;
  bool exact = true;
  while (decoder.next()) {
    exact = exact && k < planes.size() && std::equal(decoder.nodes().begin(), decoder.nodes().end(), planes[k].nodes.begin(),
                                                     planes[k].nodes.end());
    ++k;
  }
  const auto t2 = Clock::now();
  exact = exact && k == planes.size();

  const double encode_s = std::chrono::duration<double>(t1 - t0).count();
  const double decode_s = std::chrono::duration<double>(t2 - t1).count();
  const double bits = 8.0 * static_cast<double>(encoded.stream.size());
  std::printf("stream: %zu bytes (%lld I-plane, %lld P-planes)\n", encoded.stream.size(),
              static_cast<long long>(encoded.intra_planes), static_cast<long long>(encoded.inter_planes));
  std::printf("rate: %.4f bits per node per frame\n", bits / node_frames);
  std::printf("encode: %.3f ms, %.1f M nodes/s\n", encode_s * 1e3, node_frames / encode_s / 1e6);
  std::printf("decode: %.3f ms, %.1f M nodes/s\n", decode_s * 1e3, node_frames / decode_s / 1e6);
  std::printf("decoded positions %s the input: %s\n", exact ? "match" : "DIFFER FROM", exact ? "bit-exact" : "FAILED");
  return exact ? 0 : 1;
}

}  // namespace m4mesh
