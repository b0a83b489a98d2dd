// FNV-1a, 64 bits (Fowler, Noll and Vo): a hash of a byte stream fed in pieces of any size,
// h = (h xor byte) * prime from the offset basis. The checkpoint's checksum (io/checkpoint.cpp) and a
// scene text's fingerprint (scene/parse.cpp) use it.
#pragma once
#include <cstddef>
#include <cstdint>

namespace rift {

inline constexpr std::uint64_t fnv_offset = 14695981039346656037ull, fnv_prime = 1099511628211ull;

inline std::uint64_t fnv1a(std::uint64_t h, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t k = 0; k < bytes; ++k) h = (h ^ p[k]) * fnv_prime;
  return h;
}

}  // namespace rift
