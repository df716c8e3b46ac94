// The base mesh unit's encoding: the traversal with an oracle that looks
// up what the input has behind each gate, then the vertex order in the
// cheaper of its two codings, then the positions.
#include "encoder/mesh3d/base_mesh.h"

#include <algorithm>

#include "codecs3d/codec_encoder.h"
#include "common/error.h"
#include "mesh3d/base_mesh.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

namespace {

constexpr uint32_t kUnnumbered = 0xFFFFFFFF;

// The input mesh seen from the traversal: which faces it codes (the first
// face of each directed edge, never a degenerate one) and which are loose,
// and the numbering the traversal gives the vertices.
class TraversalOracle {
 public:
  TraversalOracle(std::span<const Triangle> faces, uint32_t vertex_count)
      : faces_(faces), coding_of_(vertex_count, kUnnumbered), coded_(faces.size(), false) {
    // In input order, a face is loose when it is degenerate or when a face
    // before it that is not loose has one of its directed edges.
    owner_.reserve(3 * faces.size() / 2);  // a closed mesh's edges
    for (uint32_t f = 0; f < faces.size(); ++f) {
      const auto [a, b, c] = faces[f].v;
      const bool loose = a == b || b == c || c == a || owner_.find(a, b) != DirectedEdgeIndex::kNone ||
                         owner_.find(b, c) != DirectedEdgeIndex::kNone || owner_.find(c, a) != DirectedEdgeIndex::kNone;
      if (loose) {
        loose_.push_back(f);
        coded_[f] = true;
        continue;
      }
      owner_.insert(a, b, f);
      owner_.insert(b, c, f);
      owner_.insert(c, a, f);
    }
  }

  uint32_t traversal_faces() const { return static_cast<uint32_t>(faces_.size() - loose_.size()); }

  bool seed_corner(int corner, uint32_t& vertex) {
    if (corner == 0) {
      while (coded_[next_seed_]) ++next_seed_;
      coded_[next_seed_] = true;
    }
    return known(faces_[next_seed_].v[corner], vertex);
  }

  GateAnswer gate(HalfEdge gate, std::span<const uint32_t> candidates) {
    const uint32_t a = input_of_[gate.from], b = input_of_[gate.to];
    const uint32_t face = owner_.find(b, a);
    if (face == DirectedEdgeIndex::kNone) return {GateSymbol::kBorder, 0, 0};
    if (coded_[face]) throw Error(ErrorKind::kInput, "base_mesh", kNoPlane, kNoOffset, "encoder: a face behind a gate is coded twice");
    coded_[face] = true;
    GateAnswer answer;
    uint32_t c = 0;
    if (!known(faces_[face].third(a, b), c)) {
      answer.symbol = GateSymbol::kNewVertex;
      return answer;
    }
    const auto found = std::find(candidates.begin(), candidates.end(), c);
    if (found != candidates.end()) return {GateSymbol::kCandidate, static_cast<uint32_t>(found - candidates.begin()), 0};
    return {GateSymbol::kFarVertex, 0, c};
  }

  void numbered(uint32_t c) {
    coding_of_[pending_] = c;
    input_of_.push_back(pending_);
  }

  // After the traversal: the vertices it did not reach, in input order or
  // in the order `untraversed` lists them, and the loose faces in coding
  // numbers.
  std::vector<uint32_t> finish(std::vector<Triangle>& loose_faces, std::span<const uint32_t> untraversed) {
    for (uint32_t v : untraversed) {
      if (v >= coding_of_.size() || coding_of_[v] != kUnnumbered)
        throw Error(ErrorKind::kInput, "base_mesh", kNoPlane, kNoOffset, "encoder: vertex " + std::to_string(v) + " is not outside the traversal");
      coding_of_[v] = static_cast<uint32_t>(input_of_.size());
      input_of_.push_back(v);
    }
    for (uint32_t v = 0; v < coding_of_.size(); ++v)
      if (coding_of_[v] == kUnnumbered) {
        if (!untraversed.empty()) throw Error(ErrorKind::kInput, "base_mesh", kNoPlane, kNoOffset, "encoder: the order misses vertex " + std::to_string(v));
        coding_of_[v] = static_cast<uint32_t>(input_of_.size());
        input_of_.push_back(v);
      }
    for (uint32_t f : loose_) {
      Triangle t = faces_[f];
      for (NodeIndex& v : t.v) v = coding_of_[v];
      loose_faces.push_back(t);
    }
    return input_of_;
  }

 private:
  // Whether input vertex v has its number yet; if not, it is the next one.
  bool known(uint32_t v, uint32_t& number) {
    if (coding_of_[v] != kUnnumbered) {
      number = coding_of_[v];
      return true;
    }
    pending_ = v;
    return false;
  }

  std::span<const Triangle> faces_;
  std::vector<uint32_t> coding_of_, input_of_;
  std::vector<uint32_t> loose_;
  DirectedEdgeIndex owner_;  // directed edge → its traversal face
  std::vector<bool> coded_;
  size_t next_seed_ = 0;
  uint32_t pending_ = 0;
};

// The connectivity in coding numbers: traversal faces, then loose faces.
struct Connectivity {
  std::vector<Triangle> faces;
  std::vector<Triangle> parents;
  std::vector<uint32_t> input_of;
  uint32_t loose_faces = 0;
};

template <class IO>
Connectivity write_connectivity(IO& symbols, syntax::BaseMeshContexts& contexts, std::span<const Triangle> faces, uint32_t vertex_count,
                                std::span<const uint32_t> untraversed) {
  TraversalOracle oracle(faces, vertex_count);
  GateTraversal traversal(oracle.traversal_faces());
  describe_traversal(symbols, contexts, traversal, vertex_count, oracle.traversal_faces(), &oracle);
  Connectivity c;
  c.faces = traversal.faces();
  c.parents = traversal.parents();
  std::vector<Triangle> loose;
  c.input_of = oracle.finish(loose, untraversed);
  c.loose_faces = static_cast<uint32_t>(loose.size());
  describe_loose_faces(symbols, vertex_count, std::span<Triangle>(loose));
  c.faces.insert(c.faces.end(), loose.begin(), loose.end());
  return c;
}

// The bytes the vertex order takes in a coding, alone.
size_t vertex_order_bytes(uint32_t method, const Connectivity& c) {
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  syntax::BaseMeshContexts contexts;
  std::vector<uint32_t> input_of = c.input_of;
  describe_vertex_order(symbols, contexts, method, c.parents, input_of);
  return symbols.finish_bins().size() + symbols.finish_raw().size();
}

// The bytes the positions take with a blend, alone.
// The bytes of the positions' residuals at `blend`, from their predictions.
size_t position_bytes(const PositionCoding& position_coding, std::span<const PositionPrediction> predictions,
                       const std::vector<IntPoint3>& coded, uint32_t blend) {
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  syntax::BaseMeshContexts contexts;
  describe_predicted_positions(symbols, contexts, position_coding, blend, predictions, coded);
  return symbols.finish_bins().size() + symbols.finish_raw().size();
}

// Every vertex's prediction in the position order, found once for the blends tried.
std::vector<PositionPrediction> position_predictions(const PositionCoding& position_coding, const std::vector<IntPoint3>& coded) {
  const uint32_t count = static_cast<uint32_t>(coded.size());
  std::vector<uint32_t> place(count);
  for (uint32_t i = 0; i < count; ++i) place[position_coding.order[i]] = i;
  std::vector<PositionPrediction> predictions(count);
  for (uint32_t i = 0; i < count; ++i) predictions[i] = predict_position(position_coding, place, i, position_coding.order[i], coded);
  return predictions;
}

size_t position_bytes(const PositionCoding& position_coding, const std::vector<IntPoint3>& coded, uint32_t blend) {
  return position_bytes(position_coding, position_predictions(position_coding, coded), coded, blend);
}

// The coding's blend, else the smallest of 0 … 16 (the lowest of equals).
uint32_t chosen_blend(const BaseMeshCoding& coding, const PositionCoding& position_coding, const std::vector<IntPoint3>& coded) {
  if (coding.position_blend) return *coding.position_blend;
  const std::vector<PositionPrediction> predictions = position_predictions(position_coding, coded);
  uint32_t best = 0;
  size_t best_bytes = position_bytes(position_coding, predictions, coded, 0);
  for (uint32_t blend = 1; blend <= kPositionBlendUnit; ++blend)
    if (const size_t bytes = position_bytes(position_coding, predictions, coded, blend); bytes < best_bytes) {
      best = blend;
      best_bytes = bytes;
    }
  return best;
}

// The vertex order's coding and its bytes alone: none in coding order,
// else the cheaper of the two.
struct VertexOrderCoding {
  uint32_t method = kVertexOrderCoding;
  size_t bytes = 0;
};
VertexOrderCoding chosen_vertex_order(const Connectivity& c, bool coding_order) {
  if (coding_order) {
    for (uint32_t i = 0; i < c.input_of.size(); ++i)
      if (c.input_of[i] != i) throw Error(ErrorKind::kInput, "base_mesh", kNoPlane, kNoOffset, "encoder: the vertices are not in coding order");
    return {};
  }
  const size_t by_parallelogram = vertex_order_bytes(kVertexOrderFromParallelogram, c);
  const size_t by_gate = vertex_order_bytes(kVertexOrderFromGate, c);
  return by_parallelogram < by_gate ? VertexOrderCoding{kVertexOrderFromParallelogram, by_parallelogram}
                                    : VertexOrderCoding{kVertexOrderFromGate, by_gate};
}

// The positions in coding numbers.
std::vector<IntPoint3> in_coding_numbers(std::span<const IntPoint3> positions, const Connectivity& c) {
  std::vector<IntPoint3> coded(positions.size());
  for (size_t i = 0; i < coded.size(); ++i) coded[i] = positions[c.input_of[i]];
  return coded;
}

template <class IO>
uint32_t write_data(syntax::WriteIO& io, IO& symbols, std::span<const Triangle> faces, std::span<const IntPoint3> positions,
                    const BaseMeshCoding& coding, std::span<const uint32_t> untraversed) {
  const uint32_t vertex_count = static_cast<uint32_t>(positions.size());
  syntax::BaseMeshContexts contexts;
  Connectivity c = write_connectivity(symbols, contexts, faces, vertex_count, untraversed);
  // Coding numbers back to input numbers, to compare with the faces given.
  std::vector<Triangle> decoded = c.faces;
  for (Triangle& t : decoded)
    for (NodeIndex& v : t.v) v = c.input_of[v];
  if (!std::equal(decoded.begin(), decoded.end(), faces.begin(), faces.end()))
    throw Error(ErrorKind::kInput, "base_mesh", kNoPlane, kNoOffset, "encoder: the faces are not in coding order (plan_base_mesh)");
  BaseMeshData data;
  data.loose_face_count = c.loose_faces;
  data.vertex_order = chosen_vertex_order(c, coding.coding_order).method;
  describe_vertex_order(symbols, contexts, data.vertex_order, c.parents, c.input_of);
  std::vector<IntPoint3> coded = in_coding_numbers(positions, c);
  const PositionCoding position_coding(c.faces, vertex_count);
  data.position_blend = chosen_blend(coding, position_coding, coded);
  describe_positions(symbols, contexts, position_coding, data.position_blend, coded);
  symbols.finish(io, data);
  return data.position_blend;
}

}  // namespace

BaseMeshPlan plan_base_mesh(std::span<const Triangle> faces, uint32_t vertex_count, bool reorder, std::span<const uint32_t> untraversed) {
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  syntax::BaseMeshContexts contexts;
  Connectivity c = write_connectivity(symbols, contexts, faces, vertex_count, untraversed);
  BaseMeshPlan plan{std::move(c.faces), std::move(c.input_of), c.loose_faces};
  if (!reorder)
    for (Triangle& t : plan.faces)
      for (NodeIndex& v : t.v) v = plan.input_of[v];
  return plan;
}

MeshSequence in_coding_order(const MeshSequence& sequence, const BaseMeshPlan& plan, bool reorder) {
  MeshSequence s = reorder ? renumbered(sequence, plan.input_of) : sequence;
  s.faces = plan.faces;
  return s;
}

MeshSequence original_as_decoded(const MeshSequence& original, const MeshSequence& decoded, bool coding_order, const std::string& decoded_name) {
  if (!coding_order || original.vertex_count != decoded.vertex_count) return original;
  // The faces alone fix the coding order: the encoder's plan gives the numbering back.
  const MeshSequence renumbered = in_coding_order(original, plan_base_mesh(original.faces, original.vertex_count, true), true);
  if (!same_faces(renumbered.faces, decoded.faces))
    throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                decoded_name + " numbers its vertices in coding order, but its faces are not the original's in that order: not a stream of this original");
  return renumbered;
}

MeshSequence renumbered(const MeshSequence& sequence, std::span<const uint32_t> input_of) {
  std::vector<uint32_t> coding_of(sequence.vertex_count);
  for (uint32_t i = 0; i < sequence.vertex_count; ++i) coding_of[input_of[i]] = i;
  MeshSequence s{sequence.vertex_count, sequence.faces, std::vector<std::vector<Vec3>>(sequence.frames.size())};
  for (Triangle& t : s.faces)
    for (NodeIndex& v : t.v) v = coding_of[v];
  for (size_t f = 0; f < sequence.frames.size(); ++f) {
    s.frames[f].resize(sequence.vertex_count);
    for (uint32_t i = 0; i < sequence.vertex_count; ++i) s.frames[f][i] = sequence.frames[f][input_of[i]];
  }
  return s;
}

BaseMeshParts base_mesh_parts(std::span<const Triangle> faces, std::span<const IntPoint3> positions, const BaseMeshCoding& coding) {
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  syntax::BaseMeshContexts contexts;
  const Connectivity c = write_connectivity(symbols, contexts, faces, static_cast<uint32_t>(positions.size()), {});
  BaseMeshParts parts;
  parts.connectivity = symbols.finish_bins().size() + symbols.finish_raw().size();
  parts.vertex_order = chosen_vertex_order(c, coding.coding_order).bytes;
  const std::vector<IntPoint3> coded = in_coding_numbers(positions, c);
  const PositionCoding position_coding(c.faces, static_cast<uint32_t>(positions.size()));
  parts.positions = position_bytes(position_coding, coded, chosen_blend(coding, position_coding, coded));
  return parts;
}

uint32_t write_base_mesh(syntax::WriteIO& io, std::span<const Triangle> faces, std::span<const IntPoint3> positions,
                         const BaseMeshCoding& coding, std::span<const uint32_t> untraversed) {
  const syntax::SectionPlace place{"bins", "raw", 0, 0, io.plane()};
  if (io.trace()) {
    syntax::EntropyWriteIO<true> symbols(place, io.trace());
    return write_data(io, symbols, faces, positions, coding, untraversed);
  }
  syntax::EntropyWriteIO<false> symbols(place);
  return write_data(io, symbols, faces, positions, coding, untraversed);
}

}  // namespace m4mesh
