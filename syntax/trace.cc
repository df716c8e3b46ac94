#include "syntax/trace.h"

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "common/bit_cast.h"

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
  if (!shown()) return;
  prefix(offset, name, bits);
  out_ << value << '\n';
}

void Trace::binary32(uint64_t offset, std::string_view name, uint32_t bits) {
  if (!shown()) return;
  prefix(offset, name, 32);
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, " (%.9g)", static_cast<double>(bit_cast<float>(bits)));
  out_ << bits << buffer << '\n';
}

void Trace::start_code(uint64_t offset, std::string_view name, uint32_t value) {
  if (name == "mesh_object_plane_start_code") ++part_;  // a 2D plane begins
  if (!shown()) return;
  prefix(offset, name, 32);
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "0x%08x", value);
  out_ << buffer << '\n';
}

void Trace::bit_string(uint64_t offset, std::string_view name, int bits, uint32_t value) {
  if (!shown()) return;
  prefix(offset, name, bits);
  std::string s;
  for (int i = bits - 1; i >= 0; --i) s += ((value >> i) & 1) ? '1' : '0';
  out_ << '\'' << s << "'\n";
}

void Trace::bytes(uint64_t offset, std::string_view name, std::span<const uint8_t> data) {
  if (!shown()) return;
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
  if (!symbols_ || !shown()) return;
  prefix(std::string(section) + ":" + std::to_string(index), name, "b");
  out_ << value << "  ctx " << context << '\n';
}

void Trace::raw(std::string_view section, uint64_t bit, std::string_view name, int bits, int64_t value) {
  if (!symbols_ || !shown()) return;
  prefix(std::string(section) + ":" + std::to_string(bit), name, std::to_string(bits));
  out_ << value << '\n';
}

std::optional<TraceLine> parse_trace_line(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  TraceLine t;
  size_t at = 0;
  if (words.size() > 4 && words[0] == "unit") {
    t.unit = std::stoll(words[1]);
    t.frame = std::stoll(words[3]);
    at = 4;
  } else if (!words.empty() && (words[0] == "object" || words[0] == "end")) {
    at = 1;
  }
  if (words.size() < at + 4) return std::nullopt;
  t.position = words[at];
  t.name = words[at + 1];
  t.size = words[at + 2];
  t.value = words[at + 3];
  if (t.bin() && words.size() == at + 6) t.context = std::stoi(words[at + 5]);
  return t;
}

}  // namespace m4mesh
