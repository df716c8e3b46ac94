#include "syntax/trace.h"

#include <cstdio>
#include <string>

namespace m4mesh {

void Trace::prefix(std::string_view position, std::string_view name, std::string_view size) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "%10.*s  %-28.*s %2.*s  ", static_cast<int>(position.size()), position.data(),
                static_cast<int>(name.size()), name.data(), static_cast<int>(size.size()), size.data());
  if (!location_.empty()) out_ << location_ << "  ";
  out_ << buffer;
}

void Trace::prefix(uint64_t offset, std::string_view name, int bits) {
  prefix(std::to_string(offset + offset_base_), name, std::to_string(bits));
}

void Trace::element(uint64_t offset, std::string_view name, int bits, int64_t value) {
  prefix(offset, name, bits);
  out_ << value << '\n';
}

void Trace::start_code(uint64_t offset, std::string_view name, uint32_t value) {
  prefix(offset, name, 32);
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "0x%08x", value);
  out_ << buffer << '\n';
}

void Trace::bit_string(uint64_t offset, std::string_view name, int bits, uint32_t value) {
  prefix(offset, name, bits);
  std::string s;
  for (int i = bits - 1; i >= 0; --i) s += ((value >> i) & 1) ? '1' : '0';
  out_ << '\'' << s << "'\n";
}

void Trace::bytes(uint64_t offset, std::string_view name, std::span<const uint8_t> data) {
  prefix(std::to_string(offset + offset_base_), name, "B");
  out_ << data.size() << " bytes";
  if (data.size() <= 16) {
    static const char kHex[] = "0123456789abcdef";
    out_ << ' ';
    for (uint8_t b : data) out_ << kHex[b >> 4] << kHex[b & 15];
  }
  out_ << '\n';
}

void Trace::bin(std::string_view section, uint64_t index, std::string_view name, int context, int value) {
  prefix(std::string(section) + ":" + std::to_string(index), name, "b");
  out_ << value << "  ctx " << context << '\n';
}

void Trace::raw(std::string_view section, uint64_t bit, std::string_view name, int bits, int64_t value) {
  prefix(std::string(section) + ":" + std::to_string(bit), name, std::to_string(bits));
  out_ << value << '\n';
}

}  // namespace m4mesh
