// The 3D suite's cases, codec by codec (one file each), and what they
// share: how a case is made from a sequence, a written stream or a
// rejected one, and each codec's encoder options as the suite uses them.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/error.h"
#include "conformance/suite.h"
#include "encoder/mesh3d/codec_options.h"
#include "encoder/mesh3d/container_encoder.h"
#include "mesh3d/sequence.h"
#include "conformance/suite3d/stream_edits.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh::suite3d {

// A stream to decode, with a frame hash unit per frame unless a group is
// given; with `traced`, the encoder's trace of it is kept.
SuiteCase valid(std::string id, std::string purpose, std::vector<std::string> clauses, const MeshSequence& s, Encode3dOptions o,
                bool traced, uint32_t hash_group = 1);

// A stream to decode whose units (some or all) are written symbol by
// symbol, for what m4mesh's encoder never writes.
SuiteCase written_case(std::string id, std::string purpose, std::vector<std::string> clauses, std::vector<uint8_t> stream);

// A stream to reject with the error a decoder must report (the frame as its plane).
SuiteCase invalid(std::string id, std::string purpose, std::vector<std::string> clauses, std::vector<uint8_t> stream, ErrorKind kind,
                  std::string element, int64_t frame);

// A codec with its options, a frame hash unit per frame (the conformance
// streams hash every frame).
Encode3dOptions codec_with(std::string codec, CodecOptionValues values);

// The codecs' options as the suite uses them.
Encode3dOptions lcc(CodecOptionValues values);
// Affine-Octree at ME `me` percent and k bits per matrix element.
Encode3dOptions affine(const std::string& me, int k = 16);
// cpca-wpt with the paper's tools (shape components, basis predicted in
// index order, a unit per refinement) unless `values` name others.
Encode3dOptions cpca(CodecOptionValues values);

// Clustered-PCA streams written symbol by symbol. The position of the n-th
// refinement unit (from 0) among a stream's units; a refinement unit's
// field; a refinement unit of frame `frame` whose data is `r` with the
// bins and raw bits of its symbols, or of one refinement.
size_t refinement_unit(const ContainerParts& parts, size_t n);
FieldBytes refinement_field(const char* name);
std::vector<uint8_t> refinement_unit_bytes(CpcaRefinement r, syntax::EntropyWriteIO<false>& symbols, uint32_t frame = 0);
std::vector<uint8_t> refinement_bytes(uint32_t cluster, uint32_t kind, uint32_t shift, syntax::EntropyWriteIO<false>& symbols,
                                      uint32_t frame = 0);
// The encoder's stream of `s` in one cluster, without hash units: what the
// streams written symbol by symbol start from.
ContainerParts cpca_one_cluster_parts(const MeshSequence& s);
// The object header and base mesh of `parts` (cpca_one_cluster_parts()),
// the header's cluster map replaced by `cluster_of` (and F, the segments'
// frames, by those given); refinement units follow. The base mesh's
// positions (base_mesh_of) predict the components over the mesh.
ContainerWriter cpca_written_start(ContainerParts parts, const std::vector<uint32_t>& cluster_of, uint32_t clusters,
                                   std::optional<uint32_t> fraction_bits, std::optional<uint32_t> segment_frames = std::nullopt);

// A clustered-PCA stream of `s` written symbol by symbol (no hash units):
// two clusters (the first half of the vertices and the rest), each a start
// and one component of unit kind `kind` (2 or 3), over a base mesh whose
// vertices outside the traversal take their coding numbers in the order
// `untraversed` lists them (m4mesh's increasing order when empty).
std::vector<uint8_t> cpca_over_mesh_stream(const MeshSequence& s, uint32_t kind, std::span<const uint32_t> untraversed);

// `stream` (of box_and_sheet(6, …)) with frame 2's unit an intra base mesh
// (encoded with `o`) whose faces differ from frame 0's: two swapped.
std::vector<uint8_t> with_intra_of_other_faces(const std::vector<uint8_t>& stream, const Encode3dOptions& o);

// Each group's streams to decode, in the manifest's order.
std::vector<SuiteCase> affine_octree_cases(bool traced);
std::vector<SuiteCase> bfs3d_cases(bool traced);
std::vector<SuiteCase> lcc_cases(bool traced);
std::vector<SuiteCase> cpca_cases(bool traced);
std::vector<SuiteCase> group_hash_cases(bool traced);
std::vector<SuiteCase> base_mesh_cases(bool traced);
std::vector<SuiteCase> container_cases(bool traced);
std::vector<SuiteCase> untraversed_cases(bool traced);
std::vector<SuiteCase> cpca_segment_cases(bool traced);

// Streams to reject, each made from a valid one of `valid`, in parts that
// keep the manifest's order (suite3d.cc joins them).
std::vector<SuiteCase> container_header_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> affine_octree_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> container_unit_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> bfs3d_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> lcc_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> cpca_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> cpca_segment_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> group_hash_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> base_mesh_unit_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> container_edge_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> base_mesh_count_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> affine_octree_edge_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> bfs3d_prefix_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> base_mesh_traversal_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> bfs3d_header_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> container_rules_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> header_range_ends_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> bfs3d_rules_rejected(const std::vector<SuiteCase>& valid);
std::vector<SuiteCase> base_mesh_rules_rejected(const std::vector<SuiteCase>& valid);

}  // namespace m4mesh::suite3d
