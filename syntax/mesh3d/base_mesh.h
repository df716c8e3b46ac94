// The base mesh unit's syntax (docs/base_mesh.md): its fields, and the
// symbols of its arithmetic-coded and raw sections: the gate traversal's
// symbols, the loose faces, the vertex order and the first frame's
// position residuals. The traversal that calls them is mesh3d/base_mesh.h.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>

#include "bitstream/arithmetic.h"
#include "syntax/io.h"
#include "syntax/mesh3d/container.h"
#include "syntax/mesh3d/residual.h"

namespace m4mesh {

// How the decoded vertices are numbered: in coding order, or in the
// encoder's input order, each input number predicted by the gate's vertex
// or by the parallelogram of input numbers (docs/base_mesh.md).
inline constexpr uint32_t kVertexOrderCoding = 0;
inline constexpr uint32_t kVertexOrderFromGate = 1;
inline constexpr uint32_t kVertexOrderFromParallelogram = 2;

// The weight, in sixteenths, of the known neighbours' mean in a position
// predicted by parallelograms (docs/base_mesh.md, "Positions").
inline constexpr uint32_t kPositionBlendUnit = 16;

struct BaseMeshData {
  uint32_t vertex_order = kVertexOrderFromGate;
  uint32_t position_blend = 0;
  uint32_t loose_face_count = 0;  // faces outside the traversal, coded by their indices
  uint32_t arithmetic_bytes = 0;
  std::span<const uint8_t> bins;
  std::span<const uint8_t> raw;
};

// What the traversal finds behind a gate.
enum class GateSymbol : uint8_t { kNewVertex, kCandidate, kBorder, kFarVertex };

namespace syntax {

template <class IO>
void describe(IO& io, BaseMeshData& b) {
  io.field_in("vertex_order", 8, b.vertex_order, kVertexOrderCoding, kVertexOrderFromParallelogram);
  io.field_in("position_blend", 8, b.position_blend, 0, kPositionBlendUnit);
  io.field("loose_face_count", 32, b.loose_face_count);  // at most face_count: checked by the decoder
  io.field("arithmetic_bytes", 32, b.arithmetic_bytes);
  io.require_length("arithmetic_bytes", b.arithmetic_bytes);
  io.section("bins", b.arithmetic_bytes, b.bins);
  io.tail_section("raw", b.raw);
}

// Channels of the position residuals: x, y, z predicted by parallelograms,
// then x, y, z predicted otherwise.
inline constexpr int kParallelogramChannel = 0;
inline constexpr int kNeighbourChannel = 3;
inline constexpr ResidualNames kPositionNames = M4MESH_RESIDUAL_NAMES("position", "position");
inline constexpr ResidualNames kFarNames = M4MESH_RESIDUAL_NAMES("far", "far_vertex");
inline constexpr ResidualNames kOrderNames = M4MESH_RESIDUAL_NAMES("order", "vertex_order_difference");

// The adaptive state of a base mesh's bins.
struct BaseMeshContexts {
  static constexpr int kGateContexts = 32;
  static constexpr int kChoiceContexts = 64;
  static constexpr int kCandidateSlots = 4;
  static constexpr int kFrontSlots = 4;
  BinContext new_vertex[kGateContexts];
  BinContext candidate[kGateContexts];
  BinContext first_candidate[kChoiceContexts];
  BinContext candidate_index[kCandidateSlots];
  BinContext border[2];
  BinContext seed_new;
  BinContext on_front;
  BinContext front_index[kFrontSlots];
  ResidualCoder<6> positions;
  ResidualCoder<1> order;
  ResidualCoder<1> far;
};

// An index below `limit` in raw bits, as few as `limit` needs.
template <class IO>
void describe_index(IO& io, const char* name, uint32_t limit, uint32_t& index) {
  io.raw(name, std::bit_width(limit - 1), index);
  if (index >= limit) io.fail(ErrorKind::kOutOfRange, name, "an index beyond " + std::to_string(limit - 1));
}

// The contexts of a gate's bins, from the traversal (mesh3d/base_mesh.h).
struct GateContext {
  int gate = 0;    // of gate_new_vertex and gate_candidate
  int choice = 0;  // of the first candidate_index bin
};

// A gate's symbol. `candidates` is the number of vertices a face behind the
// gate can close on; the index of the one it closes on goes to `candidate`.
// A far vertex follows as describe_far_vertex.
template <class IO>
void describe_gate(IO& io, BaseMeshContexts& c, GateContext context, uint32_t candidates, GateSymbol& symbol,
                   uint32_t& candidate) {
  bool is_new = symbol == GateSymbol::kNewVertex;
  io.bin("gate_new_vertex", c.new_vertex[context.gate], context.gate, is_new);
  if (is_new) {
    symbol = GateSymbol::kNewVertex;
    return;
  }
  bool is_candidate = symbol == GateSymbol::kCandidate;
  if (candidates > 0) io.bin("gate_candidate", c.candidate[context.gate], context.gate, is_candidate);
  else is_candidate = false;
  if (is_candidate) {
    symbol = GateSymbol::kCandidate;
    // Unary: bin i is 1 when the index exceeds i.
    uint32_t index = 0;
    for (; index + 1 < candidates; ++index) {
      bool more = candidate > index;
      if (index == 0) {
        io.bin("candidate_index", c.first_candidate[context.choice], context.choice, more);
      } else {
        const int slot = static_cast<int>(std::min<uint32_t>(index, BaseMeshContexts::kCandidateSlots));
        io.bin("candidate_index", c.candidate_index[slot - 1], BaseMeshContexts::kChoiceContexts + slot - 1, more);
      }
      if (!more) break;
    }
    candidate = index;
    return;
  }
  bool border = symbol == GateSymbol::kBorder;
  const int border_context = candidates > 0 ? 1 : 0;
  io.bin("gate_border", c.border[border_context], border_context, border);
  symbol = border ? GateSymbol::kBorder : GateSymbol::kFarVertex;
}

// A far vertex, below `visited`: its index in the gate's `front` when it
// is there, else its difference from the gate's `from` vertex. For an
// empty front nothing says which.
// True when the front named it.
template <class IO>
bool describe_far_vertex(IO& io, BaseMeshContexts& c, std::span<const uint32_t> front, uint32_t visited, uint32_t from,
                         uint32_t& far_vertex) {
  bool on_front = false;
  uint32_t wanted = 0;  // its index in the front (writing)
  if constexpr (!IO::kReading) {
    wanted = static_cast<uint32_t>(std::find(front.begin(), front.end(), far_vertex) - front.begin());
    on_front = wanted < front.size();
  }
  if (!front.empty()) io.bin("far_on_front", c.on_front, 0, on_front);
  if (on_front) {
    uint32_t index = 0;
    for (; index + 1 < front.size(); ++index) {
      const int slot = static_cast<int>(std::min<uint32_t>(index, BaseMeshContexts::kFrontSlots - 1));
      bool more = wanted > index;
      io.bin("front_index", c.front_index[slot], slot, more);
      if (!more) break;
    }
    far_vertex = front[index];
    return true;
  }
  int32_t difference = 0;
  if constexpr (!IO::kReading) difference = static_cast<int32_t>(int64_t{far_vertex} - from);
  c.far.describe(io, 0, difference, kFarNames);
  const int64_t vertex = int64_t{from} + difference;
  if (vertex < 0 || vertex >= visited) io.fail(ErrorKind::kOutOfRange, "far_vertex", "a vertex not numbered yet");
  far_vertex = static_cast<uint32_t>(vertex);
  return false;
}

// A seed face's corner: a new vertex, or one numbered before.
template <class IO>
void describe_seed_corner(IO& io, BaseMeshContexts& c, uint32_t visited, bool& is_new, uint32_t& vertex) {
  io.bin("seed_new_vertex", c.seed_new, 0, is_new);
  if (is_new) return;
  if (visited == 0) io.fail(ErrorKind::kStructure, "seed_new_vertex", "a vertex numbered before, before any vertex");
  describe_index(io, "seed_vertex", visited, vertex);
}

}  // namespace syntax

}  // namespace m4mesh
