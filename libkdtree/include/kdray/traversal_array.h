// The arrays traversal reads at random (the tree's nodes and leaf references, the gathered
// triangle vertices): vectors whose memory is aligned to and advised for transparent huge
// pages once it spans one, because random rays touch the whole node array and with 4 KiB pages
// nearly every node fetch also misses the TLB. A file is read, and a tree built, straight into
// them, so nothing is copied again before tracing. resize() leaves new elements uninitialised:
// they are plain data overwritten at once, and a zero fill would be one more pass over the
// memory.
#pragma once

#include <cstddef>
#include <new>
#include <utility>
#include <vector>

namespace kdray {
namespace detail {
// The construct() of an allocator whose value-less construction leaves the value uninitialised,
// so that resize() of an array overwritten anyway costs no zero fill.
struct DefaultInitialisingConstruct {
  template <typename U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// Memory of `bytes` bytes, aligned to a huge page and advised for huge pages when it spans one
// (advice only: where the kernel has none to give, it keeps 4 KiB pages). Freed with std::free.
void* allocate_traversal_memory(size_t bytes);
void free_traversal_memory(void* memory) noexcept;
}  // namespace detail

template <typename T>
struct TraversalAllocator : detail::DefaultInitialisingConstruct {
  using value_type = T;
  TraversalAllocator() = default;
  template <typename U>
  TraversalAllocator(const TraversalAllocator<U>&) noexcept {}

  T* allocate(size_t count) {
    if (count > static_cast<size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(detail::allocate_traversal_memory(count * sizeof(T)));
  }
  void deallocate(T* memory, size_t) noexcept { detail::free_traversal_memory(memory); }

  template <typename U>
  bool operator==(const TraversalAllocator<U>&) const noexcept {
    return true;
  }
  template <typename U>
  bool operator!=(const TraversalAllocator<U>&) const noexcept {
    return false;
  }
};

template <typename T>
using TraversalArray = std::vector<T, TraversalAllocator<T>>;

}  // namespace kdray
