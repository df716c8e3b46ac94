#include "decoder/mesh3d/container_decoder.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "bitstream/bit_reader.h"
#include "codecs3d/registry.h"
#include "common/md5_lanes.h"
#include "decoder/mesh3d/codec_decoders.h"
#include "syntax/mesh3d/base_mesh.h"

namespace m4mesh {

namespace {

// An error inside a payload, moved to the stream: its offset counted from
// the payload start becomes one from the stream start (the payload follows
// a 32-bit start code); `frame` is used when the error names none. An
// error placed already (in_object_payload) stays.
Error located(const Error& e, uint64_t start_code_byte, int64_t frame, int64_t unit) {
  if (e.mesh3d()) return e;
  const int64_t start = static_cast<int64_t>(start_code_byte * 8);
  const int64_t at = e.bit_offset() == kNoOffset ? start : start + 32 + e.bit_offset();
  return Error(e.kind(), e.element(), e.plane() == kNoPlane ? frame : e.plane(), at, e.message()).in_mesh3d(unit);
}

}  // namespace

Error in_object_payload(const Error& e) { return located(e, 0, kNoPlane, kNoUnit); }

namespace {

// Frame buffers kept for reuse once their frame is handed out.
constexpr size_t kSpareFrames = 64;
// The most bytes of frames kept for their digests to be taken together.
constexpr size_t kDigestBatchBytes = size_t{16} << 20;

}  // namespace

Mesh3dDecoder::Mesh3dDecoder(std::span<const uint8_t> stream, const Decode3dOptions& options)
    : Mesh3dDecoder(ContainerSource(stream), options) {}

Mesh3dDecoder::Mesh3dDecoder(ContainerSource source, const Decode3dOptions& options) : parts_(std::move(source)), options_(options) {
  BitReader reader(parts_.object_payload().data(), parts_.object_payload().size());
  syntax::ReadIO io(reader, options_.trace);
  if (options_.trace) options_.trace->begin_payload(-1, "object", "mesh3d_object_start_code", kMesh3dObjectStartCode);
  try {
    syntax::describe(io, header_);
    codec_row_ = find_codec3d(header_.codec_id);
    const MakeDecoder3d* make_decoder = codec_row_ ? find_decoder3d(header_.codec_id) : nullptr;
    if (!make_decoder) io.fail(ErrorKind::kReservedValue, "codec_id", "unknown codec " + std::to_string(header_.codec_id));
    codec_ = (*make_decoder)(header_, io);
    if (reader.bits_left() != 0)
      throw Error(ErrorKind::kStructure, "object_payload", kNoPlane, static_cast<int64_t>(reader.position()),
                  std::to_string(reader.bits_left() / 8) + " bytes left over after the " + codec_row_->name + " header");
    codec_->set_trace(options_.trace);
  } catch (const Error& e) {
    throw located(e, 0, kNoPlane, kNoUnit);
  }
}

void Mesh3dDecoder::fail(ErrorKind kind, size_t index, int64_t frame, const char* element, const std::string& message) const {
  throw Error(kind, element, frame, static_cast<int64_t>(parts_.unit_offset(index) * 8 + syntax::unit_header_offset(element)), message)
      .in_mesh3d(static_cast<int64_t>(index));
}

UnitHeader Mesh3dDecoder::read_unit_header(size_t index, bool traced) {
  const std::vector<uint8_t>& payload = parts_.payload(index);
  BitReader reader(payload.data(), payload.size());
  syntax::ReadIO io(reader, traced ? options_.trace : nullptr);
  UnitHeader header;
  try {
    syntax::describe(io, header);
  } catch (const Error& e) {
    throw located(e, parts_.unit_offset(index), kNoPlane, static_cast<int64_t>(index));  // the frame is not known before the header is read
  }
  return header;
}

uint32_t Mesh3dDecoder::seek(uint32_t frame) {
  if (next_unit_ != 0 || codec_->holds_frames()) return 0;
  size_t refresh = 0;
  uint32_t start = 0;
  for (size_t u = 1; u < parts_.units(); ++u) {
    if (is_hash_unit(u)) continue;
    const UnitHeader header = read_unit_header(u, false);
    parts_.drop_before(u + 1);
    if (header.frame_index > frame) break;
    if (header.type() == UnitType::kBaseMesh) {
      refresh = u;
      start = header.frame_index;
    }
  }
  if (refresh == 0 || !codec_->start_at(start)) return 0;
  next_unit_ = refresh;
  next_display_ = start;
  // Frames before the refresh are skipped: never output, and not missing.
  if (decoded_.size() < start) decoded_.resize(start);
  std::fill_n(decoded_.begin(), start, true);
  return start;
}

std::optional<BaseMeshData> Mesh3dDecoder::first_base_mesh_fields() const {
  for (size_t u = 0; u < parts_.units(); ++u) {
    const std::vector<uint8_t>& payload = parts_.payload(u);
    BitReader reader(payload.data(), payload.size());
    syntax::ReadIO io(reader);
    try {
      UnitHeader header;
      syntax::describe(io, header);
      if (header.type() != UnitType::kBaseMesh) continue;
      BaseMeshData data;
      syntax::describe(io, data);
      return data;
    } catch (const Error&) {
      return std::nullopt;
    }
  }
  return std::nullopt;
}

std::optional<uint32_t> Mesh3dDecoder::vertex_order() const {
  const std::optional<BaseMeshData> data = first_base_mesh_fields();
  return data ? std::optional<uint32_t>(data->vertex_order) : std::nullopt;
}

std::optional<uint32_t> Mesh3dDecoder::position_blend() const {
  const std::optional<BaseMeshData> data = first_base_mesh_fields();
  return data ? std::optional<uint32_t>(data->position_blend) : std::nullopt;
}

UnitHeader Mesh3dDecoder::begin_unit(size_t index) {
  const UnitHeader header = read_unit_header(index, false);
  if (options_.trace) {
    // The location names the frame, which the header gives: read it again, traced.
    options_.trace->begin_payload(static_cast<int64_t>(index), "unit " + std::to_string(index) + " frame " + std::to_string(header.frame_index), "mesh3d_unit_start_code",
                                  kMesh3dUnitStartCode);
    read_unit_header(index, true);
  }
  return header;
}

template <class Read>
void Mesh3dDecoder::read_unit_data(size_t index, int64_t frame, Read&& read) {
  const std::vector<uint8_t>& payload = parts_.payload(index);
  BitReader reader(payload.data(), payload.size());
  reader.seek(syntax::unit_data_offset() - 32);
  syntax::ReadIO io(reader, options_.trace);
  io.set_plane(frame);
  // The unit header was read before: errors the codec finds in it are placed there too.
  static const uint64_t kUnitType = syntax::unit_header_offset("unit_type") - 32, kFrameIndex = syntax::unit_header_offset("frame_index") - 32;
  io.note_start("unit_type", kUnitType);
  io.note_start("frame_index", kFrameIndex);
  try {
    read(io);
  } catch (const Error& e) {
    throw located(e, parts_.unit_offset(index), frame, static_cast<int64_t>(index));
  }
}

void Mesh3dDecoder::decode_unit(size_t index) {
  unit_.frames.clear();
  unit_.verified.clear();
  const UnitHeader header = begin_unit(index);
  // A refinement unit refines every frame: its errors name none.
  const int64_t frame = header.type() == UnitType::kRefinement ? kNoPlane : int64_t{header.frame_index};
  if (index == 0 && (header.type() != UnitType::kBaseMesh || header.frame_index != 0))
    fail(ErrorKind::kStructure, index, frame, "unit_type", "the first unit must be the base mesh of frame 0");
  if (header.type() == UnitType::kFrameHash)
    fail(ErrorKind::kStructure, index, frame, "unit_type", "a hash unit for a frame the unit before it did not decode");
  if (header.type() == UnitType::kGroupHash)
    fail(ErrorKind::kStructure, index, frame, "unit_type", "a group hash unit before any frame is decoded");
  if (!codec_row_->uses(header.type()))
    fail(ErrorKind::kStructure, index, frame, "unit_type",
         std::string("unit_type ") + std::to_string(header.unit_type) + " (" + unit_type_name(header.type()) + ") is not used by " +
             codec_row_->name);
  if (header_.frame_count != 0 && header.frame_index >= header_.frame_count)
    fail(ErrorKind::kStructure, index, frame, "frame_index", "more frames than the object header's frame_count");
  unit_.index = index;
  unit_.header = header;
  unit_.byte_offset = parts_.unit_offset(index);
  if (codec_->holds_frames() && decoded_count_ > 0) release_before(codec_->first_held_frame(header));
  read_unit_data(index, frame, [&](syntax::ReadIO& io) { codec_->decode_unit(header, io, unit_.frames); });
  if (codec_->holds_frames()) {
    hashed_.clear();
    decoded_count_ = codec_->frames_decoded();
    return;
  }
  for (uint32_t f : unit_.frames) {
    if (f >= decoded_.size()) decoded_.resize(f + size_t{1});
    decoded_[f] = true;
  }
}

void Mesh3dDecoder::release_before(uint32_t first_held) {
  for (uint32_t f = held_from_; f < first_held; ++f) {
    take_held_frame(f, released_[f]);
    unit_.released.push_back(f);
  }
  held_from_ = std::max(held_from_, first_held);
}

void Mesh3dDecoder::take_held_frame(uint32_t frame, std::vector<Float3>& positions) {
  if (auto it = hashed_.find(frame); it != hashed_.end()) {
    positions = std::move(it->second);
    hashed_.erase(it);
    return;
  }
  if (positions.empty() && !spare_.empty()) {
    positions = std::move(spare_.back());
    spare_.pop_back();
  }
  positions.resize(header_.vertex_count);
  codec_->frame(frame, positions);
}

void Mesh3dDecoder::take_digests() {
  if (undigested_.empty()) return;
  // Each frame's latest decoding: not handed out yet, handed out now, or before.
  const auto buffer = [&](uint32_t f) -> std::span<const Float3> {
    if (auto it = ready_.find(f); it != ready_.end()) return it->second;
    if (!positions_.empty() && frame_index_ == f) return positions_;
    for (auto it = handed_out_.rbegin(); it != handed_out_.rend(); ++it)
      if (it->first == f) return it->second;
    throw std::logic_error("a frame to hash has no buffer");
  };
  std::vector<std::span<const Float3>> frames;
  for (const uint32_t f : undigested_) frames.push_back(buffer(f));
  std::vector<Digest> digests(frames.size());
  frame_digests(frames, digests);
  for (size_t k = 0; k < digests.size(); ++k) digests_[undigested_[k]] = digests[k];
  undigested_.clear();
  for (auto& [f, positions] : handed_out_)
    if (spare_.size() < kSpareFrames) spare_.push_back(std::move(positions));
  handed_out_.clear();
}

bool Mesh3dDecoder::holds(uint32_t frame) const { return frame >= held_from_ && frame < decoded_count_; }

void Mesh3dDecoder::check_hash(size_t index) {
  const UnitHeader header = begin_unit(index);
  if (header.type() == UnitType::kGroupHash) return check_group_hash(index, header);
  const uint32_t frame = header.frame_index;
  const bool covered = codec_->holds_frames() ? holds(frame) : std::find(unit_.frames.begin(), unit_.frames.end(), frame) != unit_.frames.end();
  if (!covered) fail(ErrorKind::kStructure, index, frame, "frame_index", "a hash unit for a frame the unit before it did not decode");
  FrameHash hash;
  read_unit_data(index, frame, [&](syntax::ReadIO& io) { syntax::describe(io, hash); });
  if (options_.hashes == HashCheck::kSkip) return;
  take_digests();
  Digest digest;
  if (codec_->holds_frames()) {
    std::vector<Float3> positions(header_.vertex_count);
    codec_->frame(frame, positions);
    digest = frame_digest(positions);
    hashed_[frame] = std::move(positions);
  } else {
    digest = digests_.at(frame);
  }
  record_hash(index, false, frame, 1, std::equal(digest.begin(), digest.end(), hash.md5.begin()));
}

void Mesh3dDecoder::check_group_hash(size_t index, const UnitHeader& header) {
  const uint32_t first = header.frame_index;
  GroupHash hash;
  read_unit_data(index, first, [&](syntax::ReadIO& io) {
    syntax::describe(io, hash);
    const uint64_t end = uint64_t{first} + hash.group_frames;
    if (header_.frame_count != 0 && end > header_.frame_count) io.fail(ErrorKind::kStructure, "group_frames", "a group beyond frame_count");
    for (uint64_t f = first; f < end; ++f) {
      const bool decoded = codec_->holds_frames() ? holds(static_cast<uint32_t>(f)) : f < decoded_.size() && decoded_[static_cast<size_t>(f)];
      if (!decoded)
        io.fail(ErrorKind::kStructure, "group_frames",
                "a group hash covering frame " + std::to_string(f) + ", which is not decoded yet" +
                    (codec_->holds_frames() && f < held_from_ ? " (its segment is complete already)" : ""));
    }
  });
  if (options_.hashes == HashCheck::kSkip) return;
  take_digests();
  std::vector<Digest> frames(hash.group_frames);
  if (codec_->holds_frames()) {
    // The codec's frames, a batch of MD5 lanes at a time, kept for their release.
    for (uint32_t k = 0; k < hash.group_frames; k += kMd5Batch) {
      const uint32_t count = std::min<uint32_t>(kMd5Batch, hash.group_frames - k);
      std::vector<std::span<Float3>> positions;
      for (uint32_t j = 0; j < count; ++j) {
        std::vector<Float3>& held = hashed_[first + k + j];
        held.resize(header_.vertex_count);
        positions.push_back(held);
      }
      codec_->frames(first + k, positions);
      frame_digests(std::vector<std::span<const Float3>>(positions.begin(), positions.end()), std::span(frames).subspan(k, count));
    }
  } else {
    for (uint32_t k = 0; k < hash.group_frames; ++k) {
      // A frame that failed to decode (a check carries on past it) has no digest: the group stays unchecked.
      const auto it = digests_.find(first + k);
      if (it == digests_.end()) return;
      frames[k] = it->second;
    }
  }
  const Digest digest = group_digest(frames);
  record_hash(index, true, first, hash.group_frames, std::equal(digest.begin(), digest.end(), hash.md5.begin()));
}

namespace {

// Where a hash unit's digest starts, in bits from the unit data's start.
template <class Hash>
uint64_t digest_offset(const char* element) {
  syntax::CountIO count(element);
  Hash hash;
  syntax::describe(count, hash);
  return count.offset_of_watched();
}

}  // namespace

Error Mesh3dDecoder::mismatch_error(uint32_t frame) const {
  const HashOutcome& h = hash_results_.at(frame);
  const char* element = h.group ? "group_md5" : "frame_md5";
  const uint64_t digest = h.group ? digest_offset<GroupHash>(element) : digest_offset<FrameHash>(element);
  const std::string message =
      h.group ? "frames " + std::to_string(h.first) + " … " + std::to_string(h.first + h.frames - 1) +
                    " as decoded do not match their group hash unit (the MD5 of their digests)"
              : "frame " + std::to_string(h.first) + " as decoded does not match its hash unit (the MD5 of its positions)";
  return Error(ErrorKind::kStructure, element, h.first, static_cast<int64_t>(parts_.unit_offset(h.unit) * 8 + syntax::unit_data_offset() + digest),
               message)
      .in_mesh3d(static_cast<int64_t>(h.unit));
}

void Mesh3dDecoder::record_hash(size_t index, bool group, uint32_t first, uint32_t frames, bool match) {
  for (uint32_t f = first; f < first + frames; ++f) {
    hash_results_[f] = {match, index, group, first, frames};
    unit_.verified.push_back(f);
  }
  if (!match && options_.hashes == HashCheck::kRequire) throw mismatch_error(first);
}

void Mesh3dDecoder::finish() {
  if (finished_) return;
  finished_ = true;
  if (parts_.units() == 0) throw Error(ErrorKind::kTruncated, "base_mesh", 0, kNoOffset, "the stream has no base mesh unit").in_mesh3d(kNoUnit);
  for (uint32_t f = 0; f < header_.frame_count; ++f)
    if (codec_->holds_frames() ? f >= decoded_count_ : f >= decoded_.size() || !decoded_[f])
      throw Error(ErrorKind::kTruncated, "mesh3d_unit_start_code", f, kNoOffset,
                  "the stream ends before frame " + std::to_string(f) + " of " + std::to_string(header_.frame_count) + " is decoded")
          .in_mesh3d(kNoUnit);
  if (options_.trace && parts_.has_end_code()) options_.trace->begin_payload(Trace::kEndPart, "end", "mesh_object_end_code", kMeshObjectEndCode);
}

bool Mesh3dDecoder::is_hash_unit(size_t index) const {
  const std::vector<uint8_t>& payload = parts_.payload(index);
  return !payload.empty() && payload[0] < kUnitTypes && m4mesh::is_hash_unit(static_cast<UnitType>(payload[0]));
}

bool Mesh3dDecoder::next_unit() {
  if (next_unit_ >= parts_.units()) {
    finish();
    return false;
  }
  parts_.drop_before(next_unit_);
  const size_t index = next_unit_++;
  unit_.released.clear();
  released_.clear();
  decode_unit(index);
  if (!codec_->holds_frames()) {
    for (uint32_t f : unit_.frames) {
      std::vector<Float3>& slot = ready_[f];
      if (slot.empty() && !spare_.empty()) {
        slot = std::move(spare_.back());
        spare_.pop_back();
      }
      slot.resize(header_.vertex_count);
      codec_->frame(f, slot);
      if (options_.hashes != HashCheck::kSkip) undigested_.push_back(f);
    }
    if (undigested_.size() * header_.vertex_count * sizeof(Float3) >= kDigestBatchBytes || undigested_.size() >= kMd5Batch) take_digests();
  }
  while (next_unit_ < parts_.units() && is_hash_unit(next_unit_)) check_hash(next_unit_++);
  return true;
}

size_t Mesh3dDecoder::take_received_units() {
  size_t taken = 0;
  for (; next_unit_ < parts_.units(); ++taken) {
    next_unit();
    ready_.merge(released_);
  }
  return taken;
}

void Mesh3dDecoder::extend(std::span<const uint8_t> window, uint64_t window_start) {
  parts_.extend(window, window_start);
  if (next_unit_ > 0)
    while (next_unit_ < parts_.units() && is_hash_unit(next_unit_)) check_hash(next_unit_++);
}

void Mesh3dDecoder::resume() {
  if (codec_->holds_frames()) unit_.frames.clear();
  for (uint32_t f : unit_.frames) {
    if (f >= decoded_.size()) decoded_.resize(f + size_t{1});
    decoded_[f] = true;
  }
  while (next_unit_ < parts_.units() && is_hash_unit(next_unit_)) ++next_unit_;
}

std::optional<uint32_t> Mesh3dDecoder::first_mismatch() const {
  for (const auto& [frame, outcome] : hash_results_)
    if (!outcome.match) return frame;
  return std::nullopt;
}

void Mesh3dDecoder::require_hashes_match() const {
  if (const std::optional<uint32_t> f = first_mismatch()) throw mismatch_error(*f);
}

std::optional<bool> Mesh3dDecoder::hash_result(uint32_t frame) const {
  auto it = hash_results_.find(frame);
  if (it == hash_results_.end()) return std::nullopt;
  return it->second.match;
}

bool Mesh3dDecoder::next_frame() {
  for (;;) {
    if (auto it = ready_.find(next_display_); it != ready_.end()) {
      // A frame's buffer is kept for its digest, then for the frames to come, as many as one unit releases at most.
      if (!positions_.empty() && std::find(undigested_.begin(), undigested_.end(), frame_index_) != undigested_.end())
        handed_out_.emplace_back(frame_index_, std::move(positions_));
      else if (spare_.size() < kSpareFrames)
        spare_.push_back(std::move(positions_));
      positions_ = std::move(it->second);
      ready_.erase(it);
      frame_index_ = next_display_++;
      return true;
    }
    if (!next_unit()) {
      if (!codec_->holds_frames() || !holds(next_display_)) return false;
      take_held_frame(next_display_, positions_);
      frame_index_ = next_display_++;
      return true;
    }
    ready_.merge(released_);
  }
}

void Mesh3dDecoder::frame(uint32_t index, std::span<Float3> positions) const {
  const auto hashed = hashed_.find(index);
  if (hashed == hashed_.end() && (!codec_->holds_frames() || holds(index))) return codec_->frame(index, positions);
  const std::vector<Float3>& released = hashed != hashed_.end() ? hashed->second : released_.at(index);
  std::copy(released.begin(), released.end(), positions.begin());
}

void for_each_prefix(std::span<const uint8_t> stream,
                     const std::function<void(size_t units, uint64_t bytes, const MeshSequence& decoded)>& visit) {
  const ContainerParts parts = split_container(stream);
  Mesh3dDecoder decoder(stream);
  if (!decoder.progressive())
    throw usage_error(decoder.codec().name + " decodes frame by frame; progressive needs a progressive codec (cpca-wpt)");
  MeshSequence decoded;
  decoded.vertex_count = decoder.header().vertex_count;
  decoded.frames.resize(decoder.header().frame_count, std::vector<Vec3>(decoded.vertex_count));
  std::vector<Float3> positions(decoded.vertex_count);
  uint32_t final_frames = 0;  // frames before this are final: their segment has ended, and they are kept
  for (size_t units = 1; decoder.next_unit(); ++units) {
    // The frames the unit released (a segment's, in order) are read once more, then kept.
    const std::vector<uint32_t>& released = decoder.unit().released;
    const uint32_t first = released.empty() ? final_frames : released.front();
    final_frames = released.empty() ? final_frames : released.back() + 1;
    for (uint32_t f = first; f < decoded.frames.size(); ++f) {
      decoder.frame(f, positions);
      for (size_t v = 0; v < positions.size(); ++v) decoded.frames[f][v] = {positions[v][0], positions[v][1], positions[v][2]};
    }
    decoded.faces = decoder.faces();
    const size_t taken = decoder.units_taken();
    visit(units, taken < parts.units.size() ? parts.units[taken].byte_offset : stream.size(), decoded);
  }
}

std::vector<uint8_t> decoded_frames3d(std::span<const uint8_t> stream) {
  Mesh3dDecoder decoder(stream);
  std::vector<uint8_t> out;
  while (decoder.next_frame()) append_frame_bytes(decoder.positions(), out);
  return out;
}

MeshSequence decode_mesh3d(std::span<const uint8_t> stream) {
  Mesh3dDecoder decoder(stream);
  MeshSequence s;
  s.vertex_count = decoder.header().vertex_count;
  while (decoder.next_frame()) {
    std::vector<Vec3> frame;
    frame.reserve(decoder.positions().size());
    for (const Float3& p : decoder.positions()) frame.push_back({p[0], p[1], p[2]});
    s.frames.push_back(std::move(frame));
  }
  s.faces = decoder.faces();
  return s;
}

uint32_t trace_mesh3d(std::span<const uint8_t> stream, std::ostream& out) {
  Trace trace(out);
  Decode3dOptions options;
  options.trace = &trace;
  Mesh3dDecoder decoder(stream, options);
  while (decoder.next_unit()) {
  }
  return decoder.header().codec_id;
}

}  // namespace m4mesh
