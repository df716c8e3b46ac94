#include "common/parse_number.h"

#include <charconv>
#include <cstdlib>
#include <string>

namespace m4mesh {

const char* parse_double(const char* begin, const char* end, double& value) {
#if defined(__cpp_lib_to_chars)
  const auto [next, error] = std::from_chars(begin, end, value);
  return error == std::errc() ? next : begin;
#else
  if (begin == end || *begin == '+' || *begin == ' ' || (*begin >= '\t' && *begin <= '\r')) return begin;
  const std::string text(begin, end);
  char* stop = nullptr;
  value = std::strtod(text.c_str(), &stop);
  return begin + (stop - text.c_str());
#endif
}

}  // namespace m4mesh
