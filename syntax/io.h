// I/O policies for the descriptions of syntax/describe.h and
// syntax/mesh3d/: ReadIO parses and range-checks, WriteIO writes (and
// refuses values the syntax does not allow), CountIO counts bits. ReadIO
// and WriteIO trace when given a Trace. Byte sections (arithmetic-coded
// data, raw bits, a Draco mesh, a digest) are placed by `section`; their
// contents are described with syntax/mesh3d/entropy_io.h.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "bitstream/bit_reader.h"
#include "bitstream/bit_writer.h"
#include "bitstream/start_codes.h"
#include "common/error.h"
#include "syntax/trace.h"
#include "syntax/vlc.h"

namespace m4mesh::syntax {

// Whether IO writes a syntax table (syntax/table_io.h): a description
// prints its conditional and repeated parts for it.
template <class IO>
inline constexpr bool kTableOf = requires { IO::kTable; };

// What every policy shares: the plane number, the offset of the element in
// hand, and the error it raises.
class IOBase {
 public:
  void set_plane(int64_t plane) { plane_ = plane; }
  int64_t plane() const { return plane_; }
  Trace* trace() const { return trace_; }
  void set_trace(Trace* trace) { trace_ = trace; }
  uint64_t element_start() const { return element_start_; }

  // An error is placed at the first bit of the element it names: of the
  // last field of that name read (also when a rule checks it later), else
  // of the element in hand (docs/container3d.md, "Errors").
  [[noreturn]] void fail(ErrorKind kind, const char* element, const std::string& message) const {
    fail_at(kind, element, start_of(element), message);
  }
  [[noreturn]] void fail_at(ErrorKind kind, const char* element, uint64_t offset, const std::string& message) const {
    throw Error(kind, element, plane_, static_cast<int64_t>(offset), message);
  }
  void require(bool ok, ErrorKind kind, const char* element, const char* message) const {
    if (!ok) fail(kind, element, message);
  }
  // Records where a field (or a structure: "base_mesh") starts, for later
  // errors. Called for every field read: names are string literals, so a
  // slot chosen by the name's address usually holds it already.
  void note_start(const char* name, uint64_t offset) {
    FieldStart& slot = recent_[recent_slot(name)];
    if (slot.name == name) [[likely]] {
      slot.offset = offset;
      return;
    }
    note_new_start(slot, name, offset);
  }
  // Where an error about the element is placed (fail()).
  uint64_t start_of(const char* element) const {
    for (const FieldStart& held : recent_)
      if (held.name != nullptr && std::string_view(held.name) == element) return held.offset;
    const size_t i = index_of(element);
    return i < starts_.size() ? starts_[i].offset : element_start_;
  }

 protected:
  struct FieldStart {
    const char* name = nullptr;
    uint64_t offset = 0;
  };
  static size_t recent_slot(const char* name) {
    return static_cast<size_t>((reinterpret_cast<uintptr_t>(name) * 0x9e3779b97f4a7c15u) >> 58);
  }
  // Where the name's slot holds another name: that one, and any copy of
  // this name's text held under another address, move to starts_.
  [[gnu::noinline]] void note_new_start(FieldStart& slot, const char* name, uint64_t offset) {
    for (FieldStart& held : recent_)
      if (held.name != nullptr && std::string_view(held.name) == name) move_to_starts(held);
    if (slot.name != nullptr) move_to_starts(slot);
    slot = {name, offset};
  }
  void move_to_starts(FieldStart& held) {
    const size_t i = index_of(held.name);
    if (i == starts_.size()) starts_.push_back(held);
    starts_[i].offset = held.offset;
    held = {};
  }
  // The entry of that name in starts_, or starts_.size().
  size_t index_of(const char* name) const {
    for (size_t i = 0; i < starts_.size(); ++i)
      if (std::string_view(starts_[i].name) == name) return i;
    return starts_.size();
  }
  int64_t plane_ = kNoPlane;
  uint64_t element_start_ = 0;
  Trace* trace_ = nullptr;
  // The latest start of each name read: in its recent_slot, else (moved out
  // of it) in starts_. A text is held once in recent_, and an entry there is
  // newer than starts_' of the same text. Both are bounded by the syntax's names.
  std::array<FieldStart, 64> recent_{};
  std::vector<FieldStart> starts_;
};

class ReadIO : public IOBase {
 public:
  static constexpr bool kReading = true;
  explicit ReadIO(BitReader& reader, Trace* trace = nullptr) : reader_(reader) { trace_ = trace; }

  BitReader& reader() { return reader_; }

  template <class T>
  void field(const char* name, int bits, T& value) {
    element_start_ = reader_.position();
    note_start(name, element_start_);
    const uint32_t raw = reader_.read(bits);
    if (reader_.overrun()) [[unlikely]]
      truncated(name);
    value = static_cast<T>(raw);
    if (trace_) [[unlikely]]
      trace_->element(element_start_, name, bits, static_cast<int64_t>(raw));
  }

  template <class T>
  void field_in(const char* name, int bits, T& value, uint32_t lo, uint32_t hi) {
    field(name, bits, value);
    if (value < lo || value > hi)
      fail(ErrorKind::kOutOfRange, name,
           "value " + std::to_string(value) + " outside " + std::to_string(lo) + "…" + std::to_string(hi));
  }

  template <class T>
  void vlc(const char* name, const VlcTable& table, T& symbol) {
    element_start_ = reader_.position();
    note_start(name, element_start_);
    const VlcTable::Match match = table.match(reader_.peek(table.max_length()));
    if (match.length == 0) [[unlikely]]
      not_a_code(name, table);
    reader_.skip(match.length);
    if (reader_.overrun()) [[unlikely]]
      truncated(name);
    symbol = static_cast<T>(match.symbol);
    if (trace_) [[unlikely]]
      trace_->element(element_start_, name, match.length, match.symbol);
  }

  void start_code(const char* name, uint32_t code) {
    element_start_ = reader_.position();
    uint32_t value = reader_.read(32);
    if (reader_.overrun()) truncated(name);
    if (value != code) {
      char hex[16];
      std::snprintf(hex, sizeof hex, "0x%08x", value);
      fail(ErrorKind::kMissingStartCode, name, std::string("found ") + hex);
    }
    if (trace_) trace_->start_code(element_start_, name, value);
  }

  // next_start_code(): '0' then '1's up to the byte boundary (§2.2).
  void next_start_code() {
    element_start_ = reader_.position();
    int n = stuffing_bit_count(element_start_);
    uint32_t bits = reader_.read(n);
    if (reader_.overrun()) truncated("next_start_code");
    if (trace_) trace_->bit_string(element_start_, "next_start_code", n, bits);
    if (bits != stuffing_pattern(n)) fail(ErrorKind::kBadStuffing, "next_start_code", "stuffing is not '0' followed by '1's");
  }

  // Sizes a list read from the stream; `count` has been range-checked and
  // each item takes at least `min_bits_each` bits, so a count that the
  // remaining data cannot hold fails before anything is allocated.
  template <class T>
  void resize(std::vector<T>& items, uint32_t count, const char* element, int min_bits_each = 1) {
    if (static_cast<uint64_t>(count) * static_cast<uint64_t>(min_bits_each) > reader_.bits_left()) {
      element_start_ = reader_.position();
      fail_at(ErrorKind::kTruncated, element, element_start_,
           std::to_string(count) + " items cannot fit in the " + std::to_string(reader_.bits_left()) +
               " bits left");
    }
    items.resize(count);
  }

  // The next `length` bytes (byte-aligned).
  void section(const char* name, uint64_t length, std::span<const uint8_t>& bytes) {
    element_start_ = reader_.position();
    note_start(name, element_start_);
    require(reader_.byte_aligned(), ErrorKind::kStructure, name, "a byte section not byte-aligned");
    if (length > reader_.bits_left() / 8)
      fail(ErrorKind::kTruncated, name, std::to_string(length) + " bytes where " + std::to_string(reader_.bits_left() / 8) + " are left");
    bytes = std::span<const uint8_t>(reader_.data() + element_start_ / 8, static_cast<size_t>(length));
    reader_.seek(element_start_ + 8 * length);
    if (trace_) trace_->bytes(element_start_, name, bytes);
  }
  // The bytes up to the end of the payload.
  void tail_section(const char* name, std::span<const uint8_t>& bytes) { section(name, reader_.bits_left() / 8, bytes); }

  // The payload's remaining bytes must be exactly `expected` (named after
  // the last field read): more is out of range, fewer leaves bytes over.
  // The error names `element` and is placed where `placed_at` starts (as fail() places it without).
  void require_remaining_bytes(const char* element, uint64_t expected, const char* placed_at = nullptr) const {
    const uint64_t left = reader_.bits_left() / 8;
    const char* at = placed_at ? placed_at : element;
    if (expected > left)
      fail_at(ErrorKind::kOutOfRange, element, start_of(at), std::to_string(expected) + " bytes where the unit holds " + std::to_string(left));
    if (expected < left)
      fail_at(ErrorKind::kStructure, element, start_of(at), std::to_string(left - expected) + " bytes left over after " + std::to_string(expected));
  }
  // A length field must not exceed the bytes left.
  void require_length(const char* element, uint64_t length) const {
    if (length > reader_.bits_left() / 8)
      fail(ErrorKind::kOutOfRange, element, std::to_string(length) + " bytes where the unit holds " + std::to_string(reader_.bits_left() / 8));
  }

 private:
  [[noreturn, gnu::cold, gnu::noinline]] void truncated(const char* name) const {
    fail(ErrorKind::kTruncated, name, "the data ends inside this element");
  }
  // The peeked bits are no code of the table: the data's end where it cuts them short.
  [[noreturn, gnu::cold, gnu::noinline]] void not_a_code(const char* name, const VlcTable& table) const {
    if (reader_.bits_left() < static_cast<uint64_t>(table.max_length())) truncated(name);
    fail(ErrorKind::kInvalidCode, name, "bits are not a code of the table");
  }

  BitReader& reader_;
};

class WriteIO : public IOBase {
 public:
  static constexpr bool kReading = false;
  explicit WriteIO(BitWriter& writer, Trace* trace = nullptr) : writer_(writer) { trace_ = trace; }

  template <class T>
  void field(const char* name, int bits, T& value) {
    element_start_ = writer_.position();
    if constexpr (std::is_signed_v<T>) {
      if (value < 0) fail(ErrorKind::kOutOfRange, name, "negative value " + std::to_string(value));
    }
    uint64_t raw = static_cast<uint64_t>(value);
    if (raw >= (uint64_t{1} << bits))
      fail(ErrorKind::kOutOfRange, name, "value " + std::to_string(value) + " does not fit " + std::to_string(bits) + " bits");
    writer_.write(static_cast<uint32_t>(raw), bits);
    if (trace_) trace_->element(element_start_, name, bits, static_cast<int64_t>(raw));
  }

  template <class T>
  void field_in(const char* name, int bits, T& value, uint32_t lo, uint32_t hi) {
    element_start_ = writer_.position();
    if (value < lo || value > hi)
      fail(ErrorKind::kOutOfRange, name,
           "value " + std::to_string(value) + " outside " + std::to_string(lo) + "…" + std::to_string(hi));
    field(name, bits, value);
  }

  template <class T>
  void vlc(const char* name, const VlcTable& table, T& symbol) {
    element_start_ = writer_.position();
    if (!table.has_symbol(symbol)) fail(ErrorKind::kOutOfRange, name, "value " + std::to_string(symbol) + " has no code");
    const VlcCode& code = table.code(symbol);
    writer_.write(code.bits, code.length);
    if (trace_) trace_->element(element_start_, name, code.length, symbol);
  }

  void start_code(const char* name, uint32_t code) {
    element_start_ = writer_.position();
    if (!writer_.byte_aligned()) fail(ErrorKind::kStructure, name, "start code not byte-aligned");
    writer_.write(code, 32);
    if (trace_) trace_->start_code(element_start_, name, code);
  }

  void next_start_code() {
    element_start_ = writer_.position();
    int n = stuffing_bit_count(element_start_);
    writer_.write(stuffing_pattern(n), n);
    if (trace_) trace_->bit_string(element_start_, "next_start_code", n, stuffing_pattern(n));
  }

  template <class T>
  void resize(std::vector<T>& items, uint32_t count, const char* element, int = 1) {
    element_start_ = writer_.position();
    if (items.size() != count)
      fail(ErrorKind::kStructure, element,
           "holds " + std::to_string(items.size()) + " items where the syntax needs " + std::to_string(count));
  }

  void section(const char* name, uint64_t length, std::span<const uint8_t>& bytes) {
    element_start_ = writer_.position();
    if (!writer_.byte_aligned()) fail(ErrorKind::kStructure, name, "a byte section not byte-aligned");
    if (bytes.size() != length) fail(ErrorKind::kStructure, name, "the section's length differs from its length field");
    for (uint8_t b : bytes) writer_.write(b, 8);
    if (trace_) trace_->bytes(element_start_, name, bytes);
  }
  void tail_section(const char* name, std::span<const uint8_t>& bytes) { section(name, bytes.size(), bytes); }
  void require_remaining_bytes(const char*, uint64_t, const char* = nullptr) const {}
  void require_length(const char*, uint64_t) const {}

 private:
  BitWriter& writer_;
};

// A binary32 field: read and written as its 32-bit pattern, traced with
// its value too.
template <class IO>
void binary32(IO& io, const char* name, uint32_t& bits) {
  Trace* const trace = io.trace();
  {
    struct Untraced {
      IO& io;
      Trace* trace;
      ~Untraced() { io.set_trace(trace); }
    } untraced{io, trace};
    io.set_trace(nullptr);
    io.field(name, 32, bits);
  }
  if (trace) trace->binary32(io.element_start(), name, bits);
}

// Counts the bits a structure takes, with the writer's checks.
class CountIO : public IOBase {
 public:
  static constexpr bool kReading = false;
  // With `watched`, offset_of_watched() is where the field or VLC of that
  // name starts, its first or its `occurrence`-th (from 0).
  explicit CountIO(const char* watched = nullptr, uint64_t occurrence = 0) : watched_(watched), occurrence_(occurrence) {}
  uint64_t bits() const { return bits_; }
  uint64_t offset_of_watched() const { return watched_offset_; }
  bool found_watched() const { return watched_offset_ != kNotSeen; }
  // The watched field's width in bits (a section's: 8 per byte).
  uint64_t bits_of_watched() const { return watched_bits_; }

  template <class T>
  void field(const char* name, int bits, T&) {
    watch(name, static_cast<uint64_t>(bits));
    bits_ += static_cast<uint64_t>(bits);
  }
  template <class T>
  void field_in(const char* name, int bits, T& value, uint32_t lo, uint32_t hi) {
    if (value < lo || value > hi) fail(ErrorKind::kOutOfRange, name, "value out of range");
    field(name, bits, value);
  }
  template <class T>
  void vlc(const char* name, const VlcTable& table, T& symbol) {
    if (!table.has_symbol(symbol)) fail(ErrorKind::kOutOfRange, name, "value has no code");
    watch(name, static_cast<uint64_t>(table.code(symbol).length));
    bits_ += static_cast<uint64_t>(table.code(symbol).length);
  }
  void start_code(const char*, uint32_t) { bits_ += 32; }
  void next_start_code() { bits_ += static_cast<uint64_t>(stuffing_bit_count(bits_)); }
  template <class T>
  void resize(std::vector<T>& items, uint32_t count, const char* element, int = 1) {
    if (items.size() != count) fail(ErrorKind::kStructure, element, "item count differs from the syntax");
  }
  void section(const char* name, uint64_t length, std::span<const uint8_t>&) {
    watch(name, 8 * length);
    bits_ += 8 * length;
  }
  void tail_section(const char*, std::span<const uint8_t>& bytes) { bits_ += 8 * bytes.size(); }
  void require_remaining_bytes(const char*, uint64_t, const char* = nullptr) const {}
  void require_length(const char*, uint64_t) const {}

 private:
  void watch(const char* name, uint64_t bits) {
    if (watched_ && watched_offset_ == kNotSeen && std::string_view(name) == watched_ && seen_++ == occurrence_) {
      watched_offset_ = bits_;
      watched_bits_ = bits;
    }
  }

  static constexpr uint64_t kNotSeen = ~uint64_t{0};
  uint64_t bits_ = 0;
  const char* watched_;
  uint64_t occurrence_, seen_ = 0;
  uint64_t watched_offset_ = kNotSeen;
  uint64_t watched_bits_ = 0;
};

}  // namespace m4mesh::syntax
