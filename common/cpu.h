// What the processor offers beyond the build's baseline, asked once.
#pragma once

namespace m4mesh {

#if defined(__x86_64__) && !defined(__EMSCRIPTEN__)
// AVX2, for the loops built with __attribute__((target("avx2"))) beside their SSE2 forms.
inline bool has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
#endif

}  // namespace m4mesh
