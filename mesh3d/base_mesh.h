// The base mesh's coding (docs/base_mesh.md), shared by both directions:
// the gate traversal that codes the connectivity and numbers the vertices
// in coding order, the vertex order back to the input's, and the first
// frame's positions predicted by parallelograms. Each runs one description
// through a reading or a writing IO (syntax/mesh3d/entropy_io.h); the
// encoder adds an oracle that says what the mesh has behind each gate.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/point3.h"
#include "mesh/topology.h"
#include "mesh3d/gate_traversal.h"
#include "mesh3d/mesh_predictor.h"
#include "syntax/mesh3d/base_mesh.h"

namespace m4mesh {

struct BaseMesh {
  std::vector<Triangle> faces;
  std::vector<IntPoint3> positions;
  std::vector<uint32_t> coding_order;  // the vertices in the order the traversal numbered them
};

// What the encoder's oracle answers (encoder/mesh3d/base_mesh.cc).
struct GateAnswer {
  GateSymbol symbol = GateSymbol::kBorder;
  uint32_t candidate = 0;
  uint32_t far_vertex = 0;
};

// The connectivity: `traversal_faces` faces by the traversal, numbering
// vertices as they appear. The oracle (writing only) answers gate() and
// seed_corner() and hears numbered(c) for the vertex just numbered c.
template <class IO, class Oracle>
void describe_traversal(IO& io, syntax::BaseMeshContexts& contexts, GateTraversal& traversal, uint32_t vertex_count,
                        uint32_t traversal_faces, Oracle* oracle) {
  std::vector<uint32_t> candidates, front;
  while (traversal.faces().size() < traversal_faces) {
    HalfEdge gate{};
    if (!traversal.next_gate(gate)) {
      Triangle face{};
      for (int corner = 0; corner < 3; ++corner) {
        bool is_new = false;
        uint32_t vertex = 0;
        if constexpr (!IO::kReading) is_new = !oracle->seed_corner(corner, vertex);
        syntax::describe_seed_corner(io, contexts, traversal.visited(), is_new, vertex);
        if (is_new) {
          if (traversal.visited() == vertex_count) io.fail(ErrorKind::kStructure, "seed_new_vertex", "more vertices than vertex_count");
          vertex = traversal.new_vertex();
          if constexpr (!IO::kReading) oracle->numbered(vertex);
        }
        face.v[corner] = vertex;
      }
      if (!traversal.seed(face)) io.fail(ErrorKind::kStructure, "seed_vertex", "a seed face repeats a vertex or a directed edge");
      continue;
    }
    traversal.candidates(gate, candidates);
    const uint32_t count = static_cast<uint32_t>(candidates.size());
    GateAnswer answer;
    if constexpr (!IO::kReading) answer = oracle->gate(gate, candidates);
    syntax::describe_gate(io, contexts, traversal.context(gate, count), count, answer.symbol, answer.candidate);
    bool on_front = false;
    if (answer.symbol == GateSymbol::kFarVertex) {
      traversal.front(gate, candidates, front);
      on_front = syntax::describe_far_vertex(io, contexts, front, traversal.visited(), gate.from, answer.far_vertex);
    }
    uint32_t c = 0;
    switch (answer.symbol) {
      case GateSymbol::kBorder:
        traversal.border(gate);
        continue;
      case GateSymbol::kNewVertex:
        if (traversal.visited() == vertex_count) io.fail(ErrorKind::kStructure, "gate_new_vertex", "more vertices than vertex_count");
        c = traversal.new_vertex();
        if constexpr (!IO::kReading) oracle->numbered(c);
        break;
      case GateSymbol::kCandidate:
        c = candidates[answer.candidate];
        break;
      case GateSymbol::kFarVertex:
        c = answer.far_vertex;
        break;
    }
    if (!traversal.attach(gate, c))
      io.fail(ErrorKind::kStructure,
              answer.symbol == GateSymbol::kCandidate ? "candidate_index" : on_front ? "front_index" : "far_vertex",
              "a face that repeats a vertex or a directed edge");
  }
}

// Faces outside the traversal (degenerate, or repeating a directed edge of
// an earlier face): three vertex numbers each.
template <class IO>
void describe_loose_faces(IO& io, uint32_t vertex_count, std::span<Triangle> faces) {
  for (Triangle& face : faces)
    for (NodeIndex& v : face.v) syntax::describe_index(io, "loose_vertex", vertex_count, v);
}

// The input order: input_of[i] is the input number of coded vertex i, each
// coded as the difference of its rank among the input numbers not yet taken
// from the rank of its prediction (by the parents of the traversal).
template <class IO>
void describe_vertex_order(IO& io, syntax::BaseMeshContexts& contexts, uint32_t method, std::span<const Triangle> parents,
                           std::vector<uint32_t>& input_of);

// What the positions' coding takes from the faces alone, built once per
// base mesh: the parallelograms and the position order.
struct PositionCoding {
  PositionCoding(std::span<const Triangle> faces, uint32_t vertex_count);
  MeshPredictor predictor;
  std::vector<uint32_t> order;  // the vertices in the order their positions are coded
};

// A vertex's position prediction from the known vertices, before the
// blend: the channel and its prediction p (a parallelogram's, or the
// known neighbours' mean; channel −1 without a known vertex), and with a
// parallelogram the neighbours' mean too.
struct PositionPrediction {
  int channel = -1;
  std::array<int64_t, 3> p{}, mean{};
};

// The prediction `blend` sixteenths of the way from the parallelogram to
// the neighbours' mean; without a known vertex, the position coded just
// before (`previous`, none for the first: 0) on the neighbour channel.
// Returns the channel.
inline int blended(const PositionPrediction& prediction, uint32_t blend, const IntPoint3* previous, std::array<int64_t, 3>& p) {
  if (prediction.channel < 0) {
    for (int a = 0; a < 3; ++a) p[a] = previous ? (*previous)[a] : 0;
    return syntax::kNeighbourChannel;
  }
  p = prediction.p;
  if (prediction.channel == syntax::kParallelogramChannel && blend > 0)
    for (int a = 0; a < 3; ++a) p[a] = floor_div((kPositionBlendUnit - blend) * p[a] + blend * prediction.mean[a], kPositionBlendUnit);
  return prediction.channel;
}

// Vertex v's prediction from the vertices whose place in the position
// order (`place`) is below i.
PositionPrediction predict_position(const PositionCoding& coding, std::span<const uint32_t> place, uint32_t i, uint32_t v,
                                    std::span<const IntPoint3> positions);

// The first frame's positions in the position order: each the residual
// from the prediction by the vertices before it, a parallelogram
// prediction blended with the known neighbours' mean by `blend` sixteenths.
template <class IO>
void describe_positions(IO& io, syntax::BaseMeshContexts& contexts, const PositionCoding& coding, uint32_t blend,
                        std::vector<IntPoint3>& positions);

// The residuals of known positions (an encoder's) at `blend`, from their
// predictions found once (predict_position of each in the position order):
// what describe_positions writes, with fewer lookups when several blends
// are tried.
template <class IO>
void describe_predicted_positions(IO& io, syntax::BaseMeshContexts& contexts, const PositionCoding& coding, uint32_t blend,
                                  std::span<const PositionPrediction> predictions, std::span<const IntPoint3> positions);

}  // namespace m4mesh
