// The arrays traversal reads at random (a built tree's nodes and leaf blocks, the shading
// copy of the triangle vertices): vectors whose memory is aligned to and advised for
// transparent huge pages once it spans one, because random rays touch the whole node array and
// with 4 KiB pages nearly every node fetch also misses the TLB. A tree is built straight into
// them, and a read tree views its mapped file instead (TreeArray, below). resize() leaves new
// elements uninitialised: they are plain data overwritten at once, and a zero fill would be one
// more pass over the memory.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <memory>
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

// An array of a tree: memory of its own (a TraversalArray, as a build makes it) or a range of a
// mapped file (read_tree), which stays mapped while any array viewing it lives. A read tree is
// traced where the file's pages are, with nothing copied; changing an array that views a file
// first copies it into memory of its own (tests damage trees that way).
template <typename T>
class TreeArray {
 public:
  TreeArray() = default;
  TreeArray(TraversalArray<T>&& owned) : owned_(std::move(owned)) {}
  TreeArray(std::initializer_list<T> values) : owned_(values) {}
  TreeArray(std::shared_ptr<const void> mapping, const T* data, size_t size)
      : mapping_(std::move(mapping)), view_(data), view_size_(size) {}

  const T* data() const { return mapping_ ? view_ : owned_.data(); }
  size_t size() const { return mapping_ ? view_size_ : owned_.size(); }
  bool empty() const { return size() == 0; }
  const T& operator[](size_t i) const { return data()[i]; }
  const T* begin() const { return data(); }
  const T* end() const { return data() + size(); }
  // Whether the array views a mapped file.
  bool mapped() const { return mapping_ != nullptr; }

  // The array as memory of its own, to change (copied out of the file first if it views one).
  TraversalArray<T>& own() {
    if (mapping_) {
      owned_.assign(view_, view_ + view_size_);
      mapping_.reset();
    }
    return owned_;
  }

 private:
  std::shared_ptr<const void> mapping_;  // set while the array views a file
  const T* view_ = nullptr;
  size_t view_size_ = 0;
  TraversalArray<T> owned_;
};

}  // namespace kdray
