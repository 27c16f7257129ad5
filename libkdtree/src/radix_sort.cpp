#include "radix_sort.h"

#include <algorithm>
#include <array>
#include <utility>

namespace kdray::detail {

void radix_sort(uint64_t* keys, uint64_t* scratch, size_t count, int first_byte) {
  constexpr int kBytes = 8;
  // One pass over the keys counts the values of all their bytes.
  std::array<std::array<size_t, 256>, kBytes> counts{};
  for (size_t i = 0; i < count; ++i) {
    const uint64_t key = keys[i];
    for (int byte = first_byte; byte < kBytes; ++byte) ++counts[byte][(key >> (8 * byte)) & 0xffu];
  }
  uint64_t* from = keys;
  uint64_t* to = scratch;
  for (int byte = first_byte; byte < kBytes; ++byte) {
    std::array<size_t, 256>& offsets = counts[byte];
    const uint64_t value = (from[0] >> (8 * byte)) & 0xffu;
    if (offsets[value] == count) continue;
    size_t offset = 0;
    for (size_t& bucket : offsets) offset += std::exchange(bucket, offset);
    for (size_t i = 0; i < count; ++i) {
      const uint64_t key = from[i];
      to[offsets[(key >> (8 * byte)) & 0xffu]++] = key;
    }
    std::swap(from, to);
  }
  if (from != keys) std::copy(from, from + count, keys);
}

}  // namespace kdray::detail
