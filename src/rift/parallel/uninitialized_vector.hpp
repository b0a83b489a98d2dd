// A std::vector whose resize() leaves new elements default-initialized: for the plain types of the
// bond arrays, not written at all. A vector of hundreds of millions of bonds is then first touched
// by the parallel pass that fills it (or by parallel_fill), not by resize's zeroing on one thread,
// which would take all of its first-touch page faults (gigabytes of bond arrays) on one core
// (bench/README.md).
#pragma once
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "rift/parallel/team.hpp"

namespace rift {

/// std::allocator, except that a value-initialization (resize, the count constructor) becomes a
/// default-initialization.
template <class T>
struct default_init_allocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = default_init_allocator<U>;
  };
  default_init_allocator() noexcept = default;
  template <class U>
  default_init_allocator(const default_init_allocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using uninitialized_vector = std::vector<T, default_init_allocator<T>>;

/// v.resize(n) with every element set to value, the pages first touched by all threads.
template <class T>
void parallel_fill(uninitialized_vector<T>& v, std::size_t n, const T& value) {
  v.resize(n);
  T* const data = v.data();
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t k = 0; k < n; ++k) data[k] = value;
}

}  // namespace rift
