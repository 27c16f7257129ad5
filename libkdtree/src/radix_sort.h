// Sorting 64-bit integer keys by their bytes, least significant first: the tree build's event
// keys, of which a node has thousands to millions, where a comparison sort's unpredictable
// branches cost more than the radix sort's fixed passes over memory.
#pragma once

#include <cstddef>
#include <cstdint>

namespace kdray::detail {

// Sorts keys[0, count) in increasing order, with scratch[0, count) as the second buffer.
// Bytes that are the same in every key (the high bytes of a node's local triangle indices,
// say) take no pass. The sort is stable and passes over bytes `first_byte` to 7 only: keys
// whose lower bytes already increase along the array (events made in the order of their
// triangles, whose index fills the low bytes) come out fully sorted with fewer passes.
void radix_sort(uint64_t* keys, uint64_t* scratch, size_t count, int first_byte = 0);

}  // namespace kdray::detail
