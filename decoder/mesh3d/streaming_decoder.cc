#include "decoder/mesh3d/streaming_decoder.h"

#include <algorithm>

namespace m4mesh {

size_t StreamingMesh3dDecoder::push(std::span<const uint8_t> bytes) {
  const uint64_t end = bytes_received() + bytes.size();
  received_.insert(received_.end(), bytes.begin(), bytes.end());
  // Bytes that cannot start a stream fail now, as finish() would fail them.
  if (!decoder_ && received_start_ == 0 && received_.size() >= 4 && !is_mesh3d_stream(received_))
    split_container(std::span(received_).first(4));  // throws the framing error
  // Only the new bytes are searched for start codes (one may straddle the pieces).
  for (uint64_t at = std::max(scanned_, received_start_); at + 3 <= end; ++at) {
    const size_t i = static_cast<size_t>(at - received_start_);
    if (received_[i + 2] > 1) {
      at += 2;  // no prefix 00 00 01 can start at i, i + 1 or i + 2
      continue;
    }
    if (received_[i] == 0 && received_[i + 1] == 0 && received_[i + 2] == 1) last_start_code_ = at;
  }
  scanned_ = end >= 2 ? end - 2 : 0;
  // A payload is whole once the start code after it has arrived.
  return last_start_code_ > bytes_decoded_ ? take(static_cast<size_t>(last_start_code_ - received_start_)) : 0;
}

size_t StreamingMesh3dDecoder::finish() {
  ended_ = true;
  return take(received_.size());
}

size_t StreamingMesh3dDecoder::take(size_t size) {
  const std::span<const uint8_t> whole(received_.data(), size);
  if (!decoder_ && (size > 0 || ended_)) {
    decoder_ = std::make_unique<Mesh3dDecoder>(whole);
  } else if (decoder_) {
    decoder_->extend(whole, received_start_);
  }
  if (!decoder_) return 0;
  const size_t units = decoder_->take_received_units();
  bytes_decoded_ = received_start_ + size;
  const size_t taken = decoder_->units_taken();
  const uint64_t keep = taken < decoder_->units_received() ? decoder_->unit_offset(taken) : received_start_ + size;
  received_.erase(received_.begin(), received_.begin() + static_cast<std::ptrdiff_t>(keep - received_start_));
  received_start_ = keep;
  return units;
}

}  // namespace m4mesh
