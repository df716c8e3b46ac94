// What the processor offers beyond the build's baseline, asked once.
#pragma once

namespace m4mesh {

#if defined(__x86_64__) && !defined(__EMSCRIPTEN__)
// AVX2, for the loops built with __attribute__((target("avx2"))) beside their SSE2 forms.
inline bool has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
// AVX-512 Foundation, for the loops built with __attribute__((target("avx512f"))).
inline bool has_avx512f() {
  static const bool has = __builtin_cpu_supports("avx512f");
  return has;
}
#endif

}  // namespace m4mesh
