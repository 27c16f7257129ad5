#include "build_context.h"

#include <algorithm>
#include <cmath>

namespace kdray::detail {

void FinishedSubtrees::report(uint32_t depth) {
  if (!progress_) return;
  const uint64_t weight = uint64_t{1} << (63 - std::min<uint32_t>(depth, 63));
  const uint64_t before = finished_mass_.fetch_add(weight);
  constexpr uint64_t kPercent = (uint64_t{1} << 63) / 100;
  if ((before + weight) / kPercent != before / kPercent) {
    // Reading the total under the lock keeps the reported fractions increasing.
    std::lock_guard<std::mutex> lock(mutex_);
    progress_(std::min(1.0, std::ldexp(static_cast<double>(finished_mass_.load()), -63)));
  }
}

}  // namespace kdray::detail
