// I/O policies for the contents of a 3D payload's byte sections: an
// arithmetic-coded bin section (bitstream/arithmetic.h) with the raw bit
// section beside it. The codecs' descriptions (syntax/mesh3d/*.h) call
// bin() and raw() and are run through EntropyReadIO to decode and through
// EntropyWriteIO to encode; with kTraced both print every symbol.
#pragma once

#include <cstdint>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "bitstream/arithmetic.h"
#include "bitstream/bit_reader.h"
#include "bitstream/bit_writer.h"
#include "common/error.h"
#include "syntax/io.h"
#include "syntax/mesh3d/container.h"
#include "syntax/trace.h"

namespace m4mesh::syntax {

// Where a pair of sections lies in its unit's payload, for errors and
// traces.
struct SectionPlace {
  const char* bins_name = "bins";
  const char* raw_name = "raw";
  uint64_t bins_offset = 0;  // bits from the payload's start
  uint64_t raw_offset = 0;
  int64_t frame = kNoPlane;
};

// An error in a section: the element, and the bit where the decoder was.
[[noreturn]] void entropy_error(ErrorKind kind, const char* element, const std::string& message, int64_t frame, uint64_t bit);

template <bool kTraced>
class EntropyReadIO {
 public:
  static constexpr bool kReading = true;

  EntropyReadIO(std::span<const uint8_t> bins, std::span<const uint8_t> raw, const SectionPlace& place, Trace* trace = nullptr)
      : bins_(bins), raw_(raw.data(), raw.size()), place_(place), trace_(trace) {}

  // `context` numbers the bin's context for the trace only. A bin that
  // needs a byte past the section's end stops the decoding (truncated):
  // zeros would go on decoding, a whole unit's symbols from a few bytes.
  // Always inlined, as the bin decoder is: clang left both as calls in
  // WebAssembly, 7 % of bfs3d's decoding time.
  [[gnu::always_inline]] void bin(const char* name, BinContext& context_state, int context, bool& value) {
    value = bins_.decode(context_state) != 0;
    if constexpr (kTraced) trace_->bin(place_.bins_name, bin_index_++, name, context, value);
    if (bins_.overrun() != 0) bins_ended();
  }
  void raw(const char* name, int bits, uint32_t& value) {
    if constexpr (kTraced) raw_start_ = raw_.position();
    value = raw_.read(bits);
    if constexpr (kTraced) trace_->raw(place_.raw_name, raw_start_, name, bits, value);
    if (raw_.overrun()) raw_ended();
  }
  [[noreturn]] void fail(ErrorKind kind, const char* element, const std::string& message) const {
    entropy_error(kind, element, message, place_.frame, place_.bins_offset + 8 * bins_.position());
  }
  // After the last symbol: the decoder has read exactly the bin section's
  // bytes, and the raw bits up to their last byte, whose padding is zeros.
  void finish(const char* element) {
    const uint64_t bins_end = place_.bins_offset + 8 * bins_.position();
    if (bins_.overrun() != 0) bins_ended();
    if (bins_.position() != bins_.size())
      entropy_error(ErrorKind::kStructure, element,
                    std::to_string(bins_.size() - bins_.position()) + " bytes of the arithmetic-coded section left over", place_.frame, bins_end);
    if (raw_.overrun()) raw_ended();
    const int padding = static_cast<int>((8 - raw_.position() % 8) % 8);
    const uint64_t padding_at = place_.raw_offset + raw_.position();
    if (raw_.read(padding) != 0)
      entropy_error(ErrorKind::kStructure, "raw_padding", "padding bits that are not zero", place_.frame, padding_at);
    if (raw_.bits_left() != 0)
      entropy_error(ErrorKind::kStructure, element, std::to_string(raw_.bits_left() / 8) + " bytes of the raw bit section left over",
                    place_.frame, place_.raw_offset + raw_.position());
  }

 private:
  [[noreturn]] void bins_ended() const {
    entropy_error(ErrorKind::kTruncated, place_.bins_name, "the arithmetic-coded section ends early", place_.frame,
                  place_.bins_offset + 8 * bins_.position());
  }
  [[noreturn]] void raw_ended() const {
    entropy_error(ErrorKind::kTruncated, place_.raw_name, "the raw bit section ends early", place_.frame, place_.raw_offset + raw_.size_bits());
  }

  ArithmeticDecoder bins_;
  BitReader raw_;
  const SectionPlace place_;
  Trace* trace_;
  uint64_t bin_index_ = 0;
  uint64_t raw_start_ = 0;
};

template <bool kTraced>
class EntropyWriteIO {
 public:
  static constexpr bool kReading = false;

  // With kTraced, lines go to a buffer in `like`'s location (trace_text()),
  // for the caller to print after the fields that precede the sections.
  explicit EntropyWriteIO(const SectionPlace& place, Trace* like = nullptr)
      : place_(place), trace_(buffer_, like ? *like : Trace(buffer_)) {}

  void bin(const char* name, BinContext& context_state, int context, bool& value) {
    bins_.encode(context_state, value);
    if constexpr (kTraced) trace_.bin(place_.bins_name, bin_index_++, name, context, value);
  }
  void raw(const char* name, int bits, uint32_t& value) {
    if constexpr (kTraced) trace_.raw(place_.raw_name, raw_.position(), name, bits, value);
    raw_.write(value, bits);
  }
  [[noreturn]] void fail(ErrorKind kind, const char* element, const std::string& message) const {
    throw Error(kind, element, place_.frame, kNoOffset, "encoder: " + message);
  }

  std::vector<uint8_t> finish_bins() { return bins_.finish(); }
  // The raw bits written so far.
  uint64_t raw_bits() const { return raw_.position(); }
  // The raw bits, zero-padded to a byte.
  std::vector<uint8_t> finish_raw() {
    raw_.write(0, static_cast<int>((8 - raw_.position() % 8) % 8));
    return raw_.take_bytes();
  }
  std::string trace_text() const { return buffer_.str(); }

  // After the last symbol, the mirror of EntropyReadIO::finish(): the
  // unit's `data` written through `io` with these sections (their length
  // field, arithmetic_bytes, set), then the symbols' trace after its fields.
  template <class Data>
  void finish(WriteIO& io, Data& data) {
    const std::vector<uint8_t> bins = finish_bins(), raw = finish_raw();
    data.arithmetic_bytes = static_cast<uint32_t>(bins.size());
    data.bins = bins;
    data.raw = raw;
    describe(io, data);  // unqualified: the unit's describe() is found where this is used
    if (io.trace()) io.trace()->stream() << trace_text();
  }

 private:
  ArithmeticEncoder bins_;
  BitWriter raw_;
  const SectionPlace place_;
  std::ostringstream buffer_;
  Trace trace_;
  uint64_t bin_index_ = 0;
};

}  // namespace m4mesh::syntax
