#include <kdray/device_build_options.h>

#include <CL/cl.h>

namespace kdray {

std::string device_build_options(uint64_t single_fp_config) {
  return single_fp_config & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT ? "-cl-fp32-correctly-rounded-divide-sqrt" : "";
}

}  // namespace kdray
