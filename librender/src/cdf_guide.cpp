#include "cdf_guide.h"

#include <kernels/pt_sampling.h>

namespace kdray {

std::vector<uint32_t> cdf_guide(const float* values, uint32_t n) {
  const uint32_t cells = pt_cdf_guide_size(n);
  std::vector<uint32_t> guide(cells + 1);
  uint32_t index = 0;
  for (uint32_t k = 0; k < cells; ++k) {
    const float u = float(k) / float(cells);
    while (!(u < values[index])) ++index;  // ends: the last value is 1 > u
    guide[k] = index;
  }
  guide[cells] = n - 1;
  return guide;
}

}  // namespace kdray
