// Sorting 64-bit integer keys by their bytes, least significant first: the tree build's event
// keys, of which a node has thousands to millions, where a comparison sort's unpredictable
// branches cost more than the radix sort's fixed passes over memory.
#pragma once

#include <cstddef>
#include <cstdint>

namespace kdray::detail {

// Sorts keys[0, count) in increasing order, with scratch[0, count) as the second buffer.
// Bytes that are the same in every key (the high bytes of a node's local triangle indices,
// say) take no pass.
void radix_sort(uint64_t* keys, uint64_t* scratch, size_t count);

}  // namespace kdray::detail
