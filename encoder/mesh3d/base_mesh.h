// The base mesh as the encoder codes it (docs/base_mesh.md). The decoder
// outputs faces in coding order, so the container encoder puts a
// sequence's faces in that order before a codec sees them, and with
// `--reorder` renumbers its vertices too; write_base_mesh
// (codecs3d/codec_encoder.h) then codes faces that are already in order.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mesh/topology.h"
#include "mesh3d/sequence.h"

namespace m4mesh {

struct BaseMeshPlan {
  std::vector<Triangle> faces;     // in coding order, numbered as the decoder outputs them
  std::vector<uint32_t> input_of;  // coding number → input number
  uint32_t loose_faces = 0;
};

// The traversal of `faces`; with `reorder`, faces numbered in coding order.
// The vertices outside the traversal take the last coding numbers in
// increasing input order, or in the order `untraversed` lists them all (any
// order is valid: the conformance suite's streams use others).
BaseMeshPlan plan_base_mesh(std::span<const Triangle> faces, uint32_t vertex_count, bool reorder, std::span<const uint32_t> untraversed = {});

// The sequence with the plan's faces, and with its vertices in coding order
// when the plan renumbered them.
MeshSequence in_coding_order(const MeshSequence& sequence, const BaseMeshPlan& plan, bool reorder);

// The original numbered as `decoded` numbers its vertices: when a stream
// of encode3d --reorder was decoded (`coding_order`), in coding order (the
// encoder's plan of the original's faces); an input error when it is not
// this original's.
MeshSequence original_as_decoded(const MeshSequence& original, const MeshSequence& decoded, bool coding_order, const std::string& decoded_name);

// The sequence with vertex i taken from input vertex input_of[i].
MeshSequence renumbered(const MeshSequence& sequence, std::span<const uint32_t> input_of);

}  // namespace m4mesh
