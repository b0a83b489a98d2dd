// The vector instructions the passes' run kernels use (pd/bond_runs.hpp). The default build targets the
// x86-64 baseline (SSE2: two doubles a vector), so that one binary runs everywhere; the kernels are also
// compiled for AVX2 (four) and AVX-512 and chosen once, at run time, by what the processor has. The
// AVX-512 clone keeps to vectors of four doubles (AVX-512VL); on an AMD processor with AVX-512 (Zen 4)
// the AVX2 clone is taken. Every clone does the same IEEE operations in the same order (no fused
// multiply-add: -ffp-contract=off; square roots and divisions are correctly rounded at every width), so
// results are the same bits whichever runs (tests/test_bond_runs.cpp).
// Why, and what was measured: docs/decisions/method-notes.md and bench/README.md.
#pragma once

namespace rift {

enum class VectorIsa { sse2, avx2, avx512 };

namespace detail {
inline VectorIsa processor_vector_isa() {
  static const VectorIsa isa = [] {
#if defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl")) return VectorIsa::avx512;
    if (__builtin_cpu_supports("avx2")) return VectorIsa::avx2;
#endif
    return VectorIsa::sse2;
  }();
  return isa;
}

inline VectorIsa& chosen_vector_isa() {
  static VectorIsa isa = [] {
    const VectorIsa widest = processor_vector_isa();
#if defined(__x86_64__) && defined(__GNUC__)
    if (widest == VectorIsa::avx512 && __builtin_cpu_is("amd")) return VectorIsa::avx2;  // faster there (above)
#endif
    return widest;
  }();
  return isa;
}
}  // namespace detail

/// The widest vector instructions the processor has: the clones that can run here.
inline VectorIsa widest_vector_isa() { return detail::processor_vector_isa(); }

/// The vector instructions the kernels use: the widest the processor has, AVX2 on an AMD processor
/// with AVX-512 (above), or the set chosen below.
inline VectorIsa vector_isa() { return detail::chosen_vector_isa(); }

/// Makes the kernels use `isa` where the processor has it (tests; otherwise nothing changes);
/// returns the one before, to be set back.
inline VectorIsa set_vector_isa(VectorIsa isa) {
  const VectorIsa before = detail::chosen_vector_isa();
  if (static_cast<int>(isa) <= static_cast<int>(widest_vector_isa())) detail::chosen_vector_isa() = isa;
  return before;
}

}  // namespace rift

// The attributes of a kernel's clones.
#if defined(__x86_64__) && defined(__GNUC__)
#define RIFT_TARGET_AVX2 __attribute__((target("avx2")))
#define RIFT_TARGET_AVX512 __attribute__((target("avx512f,avx512vl,prefer-vector-width=256")))
#else
#define RIFT_TARGET_AVX2
#define RIFT_TARGET_AVX512
#endif

namespace rift {

// Kernel::run(args) compiled for each instruction set: Kernel::run is always-inline, so each clone
// compiles its body with the clone's instructions.
template <class Kernel, class Args>
bool vector_clone_sse2(const Args& a) { return Kernel::run(a); }
template <class Kernel, class Args>
RIFT_TARGET_AVX2 bool vector_clone_avx2(const Args& a) { return Kernel::run(a); }
template <class Kernel, class Args>
RIFT_TARGET_AVX512 bool vector_clone_avx512(const Args& a) { return Kernel::run(a); }

/// The clone of Kernel::run for the instruction set `isa`.
template <class Kernel, class Args>
auto vector_clone(VectorIsa isa) -> bool (*)(const Args&) {
  switch (isa) {
    case VectorIsa::avx512: return &vector_clone_avx512<Kernel, Args>;
    case VectorIsa::avx2: return &vector_clone_avx2<Kernel, Args>;
    default: return &vector_clone_sse2<Kernel, Args>;
  }
}

}  // namespace rift
