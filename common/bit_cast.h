// bit_cast for standard libraries without it (the web build's libc++,
// Emscripten 3.1.6); GCC and Clang both have the builtin it is made of.
#pragma once

#include <type_traits>

namespace m4mesh {

template <class To, class From>
  requires(sizeof(To) == sizeof(From) && std::is_trivially_copyable_v<To> && std::is_trivially_copyable_v<From>)
constexpr To bit_cast(const From& from) noexcept {
  return __builtin_bit_cast(To, from);
}

}  // namespace m4mesh
