#include "syntax/mesh3d/container.h"

#include "bitstream/emulation.h"
#include "bitstream/start_codes.h"
#include "common/error.h"

namespace m4mesh {

const char* unit_type_name(UnitType type) {
  static const char* const kNames[kUnitTypes] = {"base mesh", "frame", "refinement", "frame hash", "group hash"};
  return static_cast<uint32_t>(type) < kUnitTypes ? kNames[static_cast<uint32_t>(type)] : "unknown";
}

namespace {

// Byte offset of the next 0x000001 prefix at or after `from`, or size.
size_t next_prefix(std::span<const uint8_t> s, size_t from) {
  for (size_t i = from; i + 2 < s.size(); ++i)
    if (s[i] == 0 && s[i + 1] == 0 && s[i + 2] == 1) return i;
  return s.size();
}

Error container_error(ErrorKind kind, const char* element, uint64_t byte, const std::string& message) {
  return Error(kind, element, kNoPlane, static_cast<int64_t>(byte * 8), message);
}

}  // namespace

bool is_mesh3d_stream(std::span<const uint8_t> s) {
  return s.size() >= 4 && s[0] == 0 && s[1] == 0 && s[2] == 1 && s[3] == (kMesh3dObjectStartCode & 0xFF);
}

namespace {

// The framing of a container of `size` bytes: `word(at)` reads 4 bytes,
// `prefix(from)` finds the next 0x000001 at or after `from` (or `size`);
// payload(code, start, end) for the object's and each unit's payload, whose
// start code is at `start`. Returns whether an end code closes it. With
// `from` above 0 the scan continues one that ended there, at a unit's
// start code.
template <class Word, class Prefix, class Payload>
bool scan_container(uint64_t size, Word&& word, Prefix&& prefix, Payload&& payload, uint64_t from = 0) {
  if (from == 0 && size < 4) throw container_error(ErrorKind::kTruncated, "mesh3d_object_start_code", 0, "the data ends inside this element");
  if (from == 0 && word(0) != kMesh3dObjectStartCode)
    throw container_error(ErrorKind::kMissingStartCode, "mesh3d_object_start_code", 0, "not a mesh3d container");
  uint64_t at = from;
  bool first = from == 0;
  while (at < size) {
    if (at + 4 > size) throw container_error(ErrorKind::kTruncated, "start code", at, "the data ends inside a start code");
    const uint32_t code = word(at);
    if (code == kMeshObjectEndCode) {
      if (first) throw container_error(ErrorKind::kStructure, "mesh_object_end_code", at, "no object header");
      if (at + 4 != size)
        throw container_error(ErrorKind::kTrailingData, "mesh_object_end_code", at + 4, std::to_string(size - at - 4) + " bytes after the end code");
      return true;
    }
    const bool object = code == kMesh3dObjectStartCode;
    if (object != first || (!object && code != kMesh3dUnitStartCode))
      throw container_error(ErrorKind::kMissingStartCode, first ? "mesh3d_object_start_code" : "mesh3d_unit_start_code", at,
                            "unexpected start code");
    const uint64_t end = prefix(at + 4);
    payload(code, at, end);
    first = false;
    at = end;
  }
  return false;
}

// Bytes of a stream in memory (whose offsets fit size_t).
uint32_t word_at(std::span<const uint8_t> s, uint64_t at) {
  const size_t i = static_cast<size_t>(at);
  return uint32_t{s[i]} << 24 | uint32_t{s[i + 1]} << 16 | uint32_t{s[i + 2]} << 8 | s[i + 3];
}
std::span<const uint8_t> payload_bytes(std::span<const uint8_t> s, uint64_t start, uint64_t end) {
  return s.subspan(static_cast<size_t>(start + 4), static_cast<size_t>(end - start - 4));
}

}  // namespace

ContainerParts split_container(std::span<const uint8_t> s) {
  ContainerParts parts;
  parts.has_end_code = scan_container(
      s.size(), [&](uint64_t at) { return word_at(s, at); }, [&](uint64_t from) { return uint64_t{next_prefix(s, static_cast<size_t>(from))}; },
      [&](uint32_t code, uint64_t start, uint64_t end) {
        std::vector<uint8_t> payload = unescape_payload(payload_bytes(s, start, end));
        if (code == kMesh3dObjectStartCode)
          parts.object_payload = std::move(payload);
        else
          parts.units.push_back({code, start, std::move(payload)});
      });
  return parts;
}

ContainerSource::ContainerSource(std::span<const uint8_t> stream) : memory_(stream), size_(stream.size()) {
  has_end_code_ = scan_container(
      size_, [&](uint64_t at) { return word_at(stream, at); },
      [&](uint64_t from) { return uint64_t{next_prefix(stream, static_cast<size_t>(from))}; },
      [&](uint32_t code, uint64_t start, uint64_t end) {
        if (code == kMesh3dObjectStartCode)
          object_payload_ = unescape_payload(payload_bytes(stream, start, end));
        else
          offsets_.push_back(start);
        units_end_ = end;
      });
}

void ContainerSource::extend(std::span<const uint8_t> window, uint64_t window_start) {
  if (file_ || window_start < memory_start_ || window_start > units_end_ || window_start + window.size() < size_)
    throw usage_error("the bytes received do not continue those decoded so far");
  memory_ = window;
  memory_start_ = window_start;
  size_ = window_start + window.size();
  has_end_code_ = scan_container(
      size_, [&](uint64_t at) { return word_at(window, at - window_start); },
      [&](uint64_t from) { return window_start + next_prefix(window, static_cast<size_t>(from - window_start)); },
      [&](uint32_t, uint64_t start, uint64_t end) {
        offsets_.push_back(start);
        units_end_ = end;
      },
      units_end_);
}

ContainerSource ContainerSource::open_file(const std::string& path) {
  ContainerSource source;
  source.file_ = std::make_shared<std::ifstream>(path, std::ios::binary);
  if (!*source.file_) throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, path + ": cannot open");
  source.file_->seekg(0, std::ios::end);
  source.size_ = static_cast<uint64_t>(source.file_->tellg());
  // The framing pass reads the file in blocks; a prefix may straddle two.
  constexpr uint64_t kBlock = uint64_t{1} << 20;
  std::vector<uint8_t> block;
  uint64_t block_start = 0;
  auto byte = [&](uint64_t at) {
    if (at < block_start || at >= block_start + block.size()) {
      block_start = at;
      block = source.read(at, std::min(kBlock, source.size_ - at));
    }
    return block[static_cast<size_t>(at - block_start)];
  };
  auto word = [&](uint64_t at) { return uint32_t{byte(at)} << 24 | uint32_t{byte(at + 1)} << 16 | uint32_t{byte(at + 2)} << 8 | byte(at + 3); };
  auto prefix = [&](uint64_t from) {
    for (uint64_t i = from; i + 2 < source.size_; ++i)
      if (byte(i) == 0 && byte(i + 1) == 0 && byte(i + 2) == 1) return i;
    return source.size_;
  };
  source.has_end_code_ = scan_container(source.size_, word, prefix, [&](uint32_t code, uint64_t start, uint64_t end) {
    if (code == kMesh3dObjectStartCode)
      source.object_payload_ = unescape_payload(source.read(start + 4, end - start - 4));
    else
      source.offsets_.push_back(start);
    source.units_end_ = end;
  });
  return source;
}

std::vector<uint8_t> ContainerSource::read(uint64_t first, uint64_t count) const {
  std::vector<uint8_t> bytes(static_cast<size_t>(count));
  file_->clear();
  file_->seekg(static_cast<std::streamoff>(first));
  if (!file_->read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(count)))
    throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, "the stream's file changed while it was read");
  return bytes;
}

const std::vector<uint8_t>& ContainerSource::payload(size_t index) const {
  auto it = payloads_.find(index);
  if (it != payloads_.end()) return it->second;
  const uint64_t start = offsets_.at(index) + 4, end = index + 1 < offsets_.size() ? offsets_[index + 1] : units_end_;
  if (!file_ && start - 4 < memory_start_) throw usage_error("unit " + std::to_string(index) + ": its bytes were dropped before it was read");
  return payloads_[index] = file_ ? unescape_payload(read(start, end - start)) : unescape_payload(payload_bytes(memory_, start - 4 - memory_start_, end - memory_start_));
}

void ContainerSource::drop_before(size_t index) const { payloads_.erase(payloads_.begin(), payloads_.lower_bound(index)); }

void ContainerWriter::start_code(uint32_t code) {
  for (int shift = 24; shift >= 0; shift -= 8) bytes_.push_back(static_cast<uint8_t>(code >> shift));
}

void ContainerWriter::object(std::span<const uint8_t> payload) {
  start_code(kMesh3dObjectStartCode);
  const std::vector<uint8_t> escaped = escape_payload(payload);
  bytes_.insert(bytes_.end(), escaped.begin(), escaped.end());
  flush();
}

ContainerPrefix container_prefix(const ContainerParts& parts, uint64_t stream_size, uint64_t max_bytes) {
  if (stream_size <= max_bytes) return {stream_size, parts.units.size()};
  ContainerPrefix prefix;
  for (size_t k = 0; k < parts.units.size(); ++k) {
    const uint64_t end = k + 1 < parts.units.size() ? parts.units[k + 1].byte_offset : stream_size - (parts.has_end_code ? 4 : 0);
    if (end > max_bytes) break;
    prefix = {end, k + 1};
  }
  return prefix;
}

size_t whole_payloads_size(std::span<const uint8_t> received) {
  for (size_t at = received.size() < 3 ? 0 : received.size() - 3; at > 0; --at)
    if (received[at] == 0 && received[at + 1] == 0 && received[at + 2] == 1) return at;
  return 0;
}

uint64_t ContainerWriter::unit_size(std::span<const uint8_t> payload) { return 4 + escape_payload(payload).size(); }

void ContainerWriter::unit(std::span<const uint8_t> payload) {
  start_code(kMesh3dUnitStartCode);
  const std::vector<uint8_t> escaped = escape_payload(payload);
  bytes_.insert(bytes_.end(), escaped.begin(), escaped.end());
  flush();
}

void ContainerWriter::flush() {
  if (!output_) return;
  output_(bytes_);
  written_ += bytes_.size();
  bytes_.clear();
}

std::vector<uint8_t> ContainerWriter::finish(bool with_end_code) {
  if (with_end_code) start_code(kMeshObjectEndCode);
  flush();
  written_ += bytes_.size();
  return std::move(bytes_);
}

}  // namespace m4mesh
