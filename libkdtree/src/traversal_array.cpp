#include <kdray/huge_pages.h>
#include <kdray/traversal_array.h>

#include <algorithm>
#include <cstdlib>

namespace kdray::detail {

void* allocate_traversal_memory(size_t bytes) {
  // Arrays under one huge page gain nothing; they keep the ordinary alignment.
  bytes = std::max<size_t>(bytes, 1);
  const size_t alignment = bytes >= kHugePageBytes ? kHugePageBytes : alignof(std::max_align_t);
  const size_t rounded = (bytes + alignment - 1) / alignment * alignment;
  void* memory = std::aligned_alloc(alignment, rounded);
  if (!memory) throw std::bad_alloc();
  if (alignment == kHugePageBytes) advise_huge_pages(memory, rounded);
  return memory;
}

void free_traversal_memory(void* memory) noexcept { std::free(memory); }

}  // namespace kdray::detail
