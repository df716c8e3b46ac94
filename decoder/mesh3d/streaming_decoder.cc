#include "decoder/mesh3d/streaming_decoder.h"

namespace m4mesh {

size_t StreamingMesh3dDecoder::push(std::span<const uint8_t> bytes) {
  received_.insert(received_.end(), bytes.begin(), bytes.end());
  return take(whole_payloads_size(received_));
}

size_t StreamingMesh3dDecoder::finish() {
  ended_ = true;
  return take(received_.size());
}

size_t StreamingMesh3dDecoder::take(size_t size) {
  const std::span<const uint8_t> whole(received_.data(), size);
  if (!decoder_ && (size > 0 || ended_)) {
    Decode3dOptions options;
    options.verify = true;
    decoder_ = std::make_unique<Mesh3dDecoder>(whole, options);
  } else if (decoder_) {
    decoder_->extend(whole, received_start_);
  }
  if (!decoder_) return 0;
  const size_t units = decoder_->take_received_units();
  decoder_->require_hashes_match();
  bytes_decoded_ = received_start_ + size;
  const size_t taken = decoder_->units_taken();
  const uint64_t keep = taken < decoder_->units_received() ? decoder_->unit_offset(taken) : received_start_ + size;
  received_.erase(received_.begin(), received_.begin() + static_cast<std::ptrdiff_t>(keep - received_start_));
  received_start_ = keep;
  return units;
}

}  // namespace m4mesh
