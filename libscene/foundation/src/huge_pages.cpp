#include <kdray/huge_pages.h>

#include <cstdint>

#include <sys/mman.h>

namespace kdray {

void advise_huge_pages(void* data, size_t bytes) noexcept {
  const uintptr_t start = reinterpret_cast<uintptr_t>(data);
  const uintptr_t begin = (start + kHugePageBytes - 1) & ~uintptr_t{kHugePageBytes - 1};
  const uintptr_t end = (start + bytes) & ~uintptr_t{kHugePageBytes - 1};
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

}  // namespace kdray
