// Transparent huge pages for large arrays read at random or filled at once: with 4 KiB pages a
// random access to a large array usually also misses the TLB, and filling fresh memory faults
// once per page; a 2 MiB page serves 512 of them.
#pragma once

#include <cstddef>

namespace kdray {

constexpr size_t kHugePageBytes = size_t{2} << 20;

// Advice, before the memory is first touched, that [data, data + bytes) be backed by huge
// pages: the whole huge pages inside it are advised. Where the kernel has none to give, the
// memory keeps 4 KiB pages.
void advise_huge_pages(void* data, size_t bytes) noexcept;

}  // namespace kdray
