// The build options an OpenCL device's floating point asks for, which every program on it gets.
#pragma once

#include <cstdint>
#include <string>

namespace kdray {

// What the runtime adds to every program on a device with this CL_DEVICE_SINGLE_FP_CONFIG:
// correctly rounded float division and sqrt where the device offers them, so the kernels'
// arithmetic is the C++ build's (kernels/kd_math.h).
std::string device_build_options(uint64_t single_fp_config);

}  // namespace kdray
