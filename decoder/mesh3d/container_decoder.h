// The decoder of §12 containers. It splits the stream, reads the object
// header, finds the codec in the registry (codecs3d/registry.h), enforces
// the container's rules on units and hands every unit but hash units to
// the codec; hash units are checked against the frames they cover.
// Two ways to consume it: unit by unit (next_unit(), then frame() for the
// frames the unit decoded), or frame by frame in display order
// (next_frame()). Use one of them per decoder.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "codecs3d/codec_decoder.h"
#include "common/error.h"
#include "mesh3d/frame_hash.h"
#include "mesh3d/sequence.h"
#include "syntax/mesh3d/base_mesh.h"
#include "syntax/mesh3d/container.h"
#include "syntax/trace.h"

namespace m4mesh {

struct Codec3d;

// What a decoder does with the stream's hash units.
enum class HashCheck {
  // A frame that differs from its hash unit is an error where the unit is
  // read (structure, element frame_md5 or group_md5, at the digest).
  kRequire,
  // Every hashed frame is compared and the result kept (hash_result):
  // `m4mesh check` and `decode3d --verify` list them all.
  kRecord,
  // Hash units are read, their frames not compared (trace, benchmarks of
  // the codecs alone).
  kSkip,
};

struct Decode3dOptions {
  HashCheck hashes = HashCheck::kRequire;
  Trace* trace = nullptr;  // print every element read
};

// What the last next_unit() decoded.
struct DecodedUnit {
  size_t index = 0;  // among the stream's units, hash units included
  UnitHeader header;
  uint64_t byte_offset = 0;      // of its start code
  std::vector<uint32_t> frames;  // frames it (re)decoded (a progressive codec: those of the segment it refines)
  // A progressive codec's frames that became final before the unit (its
  // segment ended): frame() gives them until the next unit.
  std::vector<uint32_t> released;
  std::vector<uint32_t> verified;  // frames the hash units after it compared
};

class Mesh3dDecoder {
 public:
  // The stream is not copied: it must outlive the decoder.
  explicit Mesh3dDecoder(std::span<const uint8_t> stream, const Decode3dOptions& options = {});
  Mesh3dDecoder(std::vector<uint8_t>&&, const Decode3dOptions& = {}) = delete;
  // A stream in memory or read from its file unit by unit (ContainerSource::open_file).
  explicit Mesh3dDecoder(ContainerSource source, const Decode3dOptions& options = {});

  const ObjectHeader& header() const { return header_; }
  const Codec3d& codec() const { return *codec_row_; }
  const std::vector<Triangle>& faces() const { return codec_->faces(); }
  bool has_end_code() const { return parts_.has_end_code(); }
  // The first base mesh unit's vertex_order and position_blend
  // (syntax/mesh3d/base_mesh.h); none when the stream has no readable base
  // mesh unit.
  std::optional<uint32_t> vertex_order() const;
  std::optional<uint32_t> position_blend() const;
  // Whether units refine frames decoded before (a progressive codec).
  bool progressive() const { return codec_->holds_frames(); }

  // Before the first unit: starts at the last intra refresh (a base mesh
  // unit) at or before `frame`, when the stream has one and the codec can;
  // returns the frame decoding starts at (0 when it cannot skip). Earlier
  // frames are never output, and group hashes reaching back before the
  // refresh stay unchecked.
  uint32_t seek(uint32_t frame);

  // Decodes the next unit that is not a hash unit, then the hash units
  // that follow it; false after the last (when the stream's frames are
  // all decoded, else an error).
  bool next_unit();
  const DecodedUnit& unit() const { return unit_; }
  // After next_unit() failed: counts the frames the codec took the failed
  // unit for as consumed and skips its hash units, so that next_unit() carries on with the next
  // unit from the state the failed one left (`m4mesh check`).
  void resume();
  // A stream in memory still arriving: `window` holds its bytes from
  // `window_start` (at most the start of the first unit not taken,
  // unit_offset(units_taken())) to every byte so far, cut where a unit starts
  // (whole_payloads_size) or at the stream's end. Its new units join the
  // decoder's; the hash units right after the last unit taken are checked
  // now, as next_unit() would have.
  void extend(std::span<const uint8_t> window, uint64_t window_start = 0);
  // Where unit `index` starts in the stream (its start code).
  uint64_t unit_offset(size_t index) const { return parts_.unit_offset(index); }
  // A stream still arriving (extend): decodes every unit received and not
  // taken yet; the frames they finish wait for next_frame(). Returns how
  // many units it decoded, hash units aside.
  size_t take_received_units();
  // Whether next_frame() has its frame without another unit.
  bool next_frame_ready() const { return ready_.contains(next_display_); }
  // Units the decoder holds, taken or not, hash units included.
  size_t units_received() const { return parts_.units(); }
  // Units taken so far, hash units included (after an error in a unit, the
  // failed one is the last taken).
  size_t units_taken() const { return next_unit_; }
  // A frame the last unit decoded; of a progressive codec, any frame it
  // holds (its segment's and the later ones) or the last unit released.
  void frame(uint32_t index, std::span<Float3> positions) const;
  // Whether a progressive codec holds the frame (decoded, not released).
  bool holds(uint32_t frame) const;
  // Each frame's last hash check: absent when no hash unit covered it
  // (or HashCheck::kSkip), else whether it matched. A group hash unit
  // checks its frames after the last of them is decoded: a frame's result
  // may come after next_frame() handed the frame out.
  std::optional<bool> hash_result(uint32_t frame) const;
  // The first frame whose last hash check failed.
  std::optional<uint32_t> first_mismatch() const;
  // With HashCheck::kRecord: throws the error of the first frame whose
  // last hash check failed, as kRequire would have thrown it at its unit.
  void require_hashes_match() const;
  // The error of a frame whose last hash comparison failed: its hash unit,
  // the digest's element and first bit.
  Error mismatch_error(uint32_t frame) const;

  // Decodes the next frame in display order, once no later unit can
  // change it; false after the last.
  bool next_frame();
  uint32_t frame_index() const { return frame_index_; }
  const std::vector<Float3>& positions() const { return positions_; }

 private:
  std::optional<BaseMeshData> first_base_mesh_fields() const;
  UnitHeader read_unit_header(size_t index, bool traced);
  // The unit's header, traced with the unit's location when tracing.
  UnitHeader begin_unit(size_t index);
  // Runs read(io) on the unit's data; errors are located in the stream.
  template <class Read>
  void read_unit_data(size_t index, int64_t frame, Read&& read);
  void decode_unit(size_t index);
  void check_hash(size_t index);
  void check_group_hash(size_t index, const UnitHeader& header);
  bool is_hash_unit(size_t index) const;
  // Records a hash unit's comparison for its frames; with kRequire a mismatch throws.
  void record_hash(size_t index, bool group, uint32_t first, uint32_t frames, bool match);
  // A progressive codec's frames before `first_held` become final: copied out.
  void release_before(uint32_t first_held);
  // A held frame into `positions`: the one its hash unit made, else the codec's.
  void take_held_frame(uint32_t frame, std::vector<Float3>& positions);
  // The digests of the frames decoded since the last call, in MD5 lanes.
  void take_digests();
  void finish();
  // An error of a unit header's element (unit_type, frame_index).
  [[noreturn]] void fail(ErrorKind kind, size_t index, int64_t frame, const char* element, const std::string& message) const;

  ContainerSource parts_;
  Decode3dOptions options_;
  ObjectHeader header_;
  const Codec3d* codec_row_ = nullptr;
  std::unique_ptr<CodecDecoder3d> codec_;
  size_t next_unit_ = 0;
  DecodedUnit unit_;
  std::vector<bool> decoded_;  // frames decoded at least once (frame by frame codecs)
  uint32_t decoded_count_ = 0;  // a progressive codec's frames decoded: 0 … this − 1
  uint32_t held_from_ = 0;      // the first frame a progressive codec holds
  // A frame's last hash comparison and the hash unit that made it.
  struct HashOutcome {
    bool match = false;
    size_t unit = 0;
    bool group = false;
    uint32_t first = 0, frames = 1;  // the frames the unit covers
  };
  std::map<uint32_t, HashOutcome> hash_results_;
  // Unless kSkip, the MD5 of every frame as it was decoded (a codec that
  // holds every frame is hashed when a hash unit is read).
  std::map<uint32_t, Digest> digests_;
  // Frames decoded whose digests are not taken yet: hashed together when a batch is full or a hash unit needs
  // them. Their buffers are in ready_, in positions_ or, handed out before, in handed_out_.
  std::vector<uint32_t> undigested_;
  std::vector<std::pair<uint32_t, std::vector<Float3>>> handed_out_;
  // A progressive codec's held frames as made for their hash unit, until a unit changes them or they are taken.
  std::map<uint32_t, std::vector<Float3>> hashed_;
  // Display order: frames copied out of the codec until their turn.
  std::map<uint32_t, std::vector<Float3>> ready_;
  std::map<uint32_t, std::vector<Float3>> released_;  // by the last unit
  std::vector<std::vector<Float3>> spare_;
  uint32_t next_display_ = 0;
  uint32_t frame_index_ = 0;
  std::vector<Float3> positions_;
  bool finished_ = false;
};

// A progressive stream unit by unit: after every unit but hash units,
// visit(units so far, bytes received through the unit and the hash units
// after it, the animation decoded so far). Needs a codec that holds every
// frame (a usage error otherwise).
void for_each_prefix(std::span<const uint8_t> stream,
                     const std::function<void(size_t units, uint64_t bytes, const MeshSequence& decoded)>& visit);

// The decoded output whose MD5 the 3D suite's manifest holds: every frame's
// canonical bytes (binary32 x, y, z per vertex, little-endian), frame after
// frame; a hash mismatch is an error.
std::vector<uint8_t> decoded_frames3d(std::span<const uint8_t> stream);

// The whole sequence (tests, tools); a hash mismatch is an error.
MeshSequence decode_mesh3d(std::span<const uint8_t> stream);

// Decodes every unit, tracing every element to `out` (the lines before an
// error stay there when the error is thrown); returns the codec's id.
uint32_t trace_mesh3d(std::span<const uint8_t> stream, std::ostream& out);

}  // namespace m4mesh
