#include "syntax/trace.h"

#include <cstdio>
#include <string>

namespace m4mesh {

void Trace::prefix(uint64_t offset, std::string_view name, int bits) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "%10llu  %-28.*s %2d  ", static_cast<unsigned long long>(offset),
                static_cast<int>(name.size()), name.data(), bits);
  out_ << buffer;
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

}  // namespace m4mesh
