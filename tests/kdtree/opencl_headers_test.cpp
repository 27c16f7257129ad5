// The device-code headers compile as OpenCL C on PoCL, their compile-time checks hold there too,
// the path-tracing kernels take the scene arguments the host binds, and the kernel's traversal
// returns the same hits, and the sampler the same bits, as the CPU build of the same headers.
#include "test_scenes.h"

#include <kdray/kdtree.h>
#include <kdray/device_build_options.h>
#include <kdray/ray_sets.h>
#include <kdray/traverse.h>

#include <kernels/pt_rng.h>
#include <kernels/pt_scene_args.h>

#include <CL/cl.h>
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace kdray {
namespace {

const char* kProgramSource = R"CL(
#include "kd_traverse.h"
#include "pt_rng.h"

__kernel void report_features(__global int* out) {
  out[0] = KD_HAS_DOUBLE;
  out[1] = KD_SHORT_STACK_SIZE;
}

__kernel void trace_closest(__global const KdNode* nodes, __global const kd_u32* leaf_blocks,
                            __global const float* bounds, __global const RayRecord* rays, __global HitRecord* hits) {
  const KdSceneView scene = kd_scene_view(nodes, leaf_blocks, bounds[0], bounds[1], bounds[2], bounds[3],
                                          bounds[4], bounds[5]);
  size_t i = get_global_id(0);
  hits[i] = kd_intersect_closest(&scene, rays[i]);
}

/* keys: 5 values per query (sampler, seed, pixel, sample index, dimension); bits: 3 per query,
 * the value and both values of the dimension's pair. */
__kernel void sample_bits(__global const kd_u32* keys, __global kd_u32* bits) {
  size_t i = get_global_id(0);
  __global const kd_u32* k = keys + 5 * i;
  PtBits2 pair = pt_sample_bits2(k[0], k[1], k[2], k[3], k[4] & ~1u);
  bits[3 * i] = pt_sample_bits(k[0], k[1], k[2], k[3], k[4]);
  bits[3 * i + 1] = pair.x;
  bits[3 * i + 2] = pair.y;
}

/* keys as above, the dimension a bounce's first; bits: PT_BOUNCE_LANES per query, computed in lanes. */
__kernel void bounce_bits_in_lanes(__global const kd_u32* keys, __global kd_u32* bits) {
  size_t i = get_global_id(0);
  __global const kd_u32* k = keys + 5 * i;
  PtBounceBits lanes = pt_bounce_bits_in_lanes(k[0], pt_sample_hash(k[0], k[1], k[2], k[3]), k[3], k[4]);
  for (uint d = 0; d < PT_BOUNCE_LANES; ++d) bits[PT_BOUNCE_LANES * i + d] = lanes.bits[d];
}
)CL";

class OpenClDevice {
 public:
  OpenClDevice() {
    cl_uint platforms = 0;
    if (clGetPlatformIDs(1, &platform_, &platforms) != CL_SUCCESS || platforms == 0) return;
    if (clGetDeviceIDs(platform_, CL_DEVICE_TYPE_ALL, 1, &device_, nullptr) != CL_SUCCESS) return;
    cl_int status = CL_SUCCESS;
    context_ = clCreateContext(nullptr, 1, &device_, nullptr, nullptr, &status);
    if (status != CL_SUCCESS) context_ = nullptr;
    cl_device_fp_config fp_config = 0;
    clGetDeviceInfo(device_, CL_DEVICE_SINGLE_FP_CONFIG, sizeof fp_config, &fp_config, nullptr);
    device_options_ = device_build_options(fp_config);
  }
  ~OpenClDevice() {
    if (program_) clReleaseProgram(program_);
    if (queue_) clReleaseCommandQueue(queue_);
    if (context_) clReleaseContext(context_);
  }
  bool available() const { return context_ != nullptr; }

  // Builds source as librender builds every program, as OpenCL C 1.2 with the device's own
  // options, with the kernels/ folder on the include path; returns the build log on failure, an
  // empty string on success. On a GPU both matter: NVIDIA's driver otherwise takes the headers'
  // pointers as __generic and refuses to pass them to their private array parameters, and its
  // float division is not the CPU's (bench/LOG.md, "GPU check").
  std::string build(const std::string& options, const char* source = kProgramSource) {
    cl_int status = CL_SUCCESS;
    program_ = clCreateProgramWithSource(context_, 1, &source, nullptr, &status);
    if (status != CL_SUCCESS) return "clCreateProgramWithSource failed";
    const std::string all_options =
        "-cl-std=CL1.2 " + device_options_ + " -I " + std::string(KDRAY_SOURCE_DIR) + "/kernels " + options;
    if (clBuildProgram(program_, 1, &device_, all_options.c_str(), nullptr, nullptr) == CL_SUCCESS) return "";
    size_t size = 0;
    clGetProgramBuildInfo(program_, device_, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size);
    std::string log(size, '\0');
    clGetProgramBuildInfo(program_, device_, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr);
    return "build failed:\n" + log;
  }

  cl_program program() const { return program_; }

  cl_mem buffer(const void* data, size_t size) {
    cl_int status = CL_SUCCESS;
    cl_mem memory = clCreateBuffer(context_, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, size == 0 ? 4 : size,
                                   const_cast<void*>(data ? data : &zero_), &status);
    EXPECT_EQ(status, CL_SUCCESS);
    buffers_.push_back(memory);
    return memory;
  }

  // Runs `name` over `work_items` with the buffers as arguments, then reads `result` back.
  void run(const char* name, const std::vector<cl_mem>& arguments, size_t work_items, cl_mem result,
           void* out, size_t out_size) {
    cl_int status = CL_SUCCESS;
    if (!queue_) queue_ = clCreateCommandQueue(context_, device_, 0, &status);
    cl_kernel kernel = clCreateKernel(program_, name, &status);
    ASSERT_EQ(status, CL_SUCCESS);
    for (cl_uint i = 0; i < arguments.size(); ++i)
      ASSERT_EQ(clSetKernelArg(kernel, i, sizeof(cl_mem), &arguments[i]), CL_SUCCESS);
    ASSERT_EQ(clEnqueueNDRangeKernel(queue_, kernel, 1, nullptr, &work_items, nullptr, 0, nullptr, nullptr),
              CL_SUCCESS);
    ASSERT_EQ(clEnqueueReadBuffer(queue_, result, CL_TRUE, 0, out_size, out, 0, nullptr, nullptr), CL_SUCCESS);
    clReleaseKernel(kernel);
    for (cl_mem memory : buffers_) clReleaseMemObject(memory);
    buffers_.clear();
  }

 private:
  cl_platform_id platform_ = nullptr;
  cl_device_id device_ = nullptr;
  cl_context context_ = nullptr;
  cl_command_queue queue_ = nullptr;
  cl_program program_ = nullptr;
  std::string device_options_;
  std::vector<cl_mem> buffers_;
  uint32_t zero_ = 0;
};

TEST(KdOpenCl, HeadersCompileWithDoublePrecisionFallback) {
  OpenClDevice device;
  if (!device.available()) GTEST_SKIP() << "no OpenCL device";
  ASSERT_EQ(device.build(""), "");
  int features[2] = {0, 0};
  cl_mem out = device.buffer(features, sizeof features);
  device.run("report_features", {out}, 1, out, features, sizeof features);
  EXPECT_EQ(features[0], 1) << "PoCL offers cl_khr_fp64; the edge-function fallback must use it";
  EXPECT_EQ(features[1], 8);
}

TEST(KdOpenCl, StaticAssertionsStopTheKernelBuild) {
  OpenClDevice device;
  if (!device.available()) GTEST_SKIP() << "no OpenCL device";
  const char* failing = "#include \"kd_compat.h\"\nKD_STATIC_ASSERT(sizeof(kd_u32) == 8, \"false\");\n"
                        "__kernel void probe(__global int* out) { out[0] = 1; }\n";
  EXPECT_NE(device.build("", failing), "") << "a false KD_STATIC_ASSERT must fail the OpenCL build";
  OpenClDevice other;
  const char* holding = "#include \"pt_kernel_args.h\"\n"
                        "__kernel void probe(__global int* out) { out[0] = PT_MAX_FILM_CHANNELS; }\n";
  EXPECT_EQ(other.build("", holding), "") << "the layout and code checks of the shared headers hold";
}

// Every kernel of the path-tracing programs starts with PT_SCENE_BUFFERS' buffers and then the
// params, the arguments bind_scene_args binds from the same list.
TEST(KdOpenCl, PathTracingKernelsStartWithTheSceneArguments) {
  std::vector<std::string> expected;
#define KD_ARG_NAME(type, name) expected.push_back(#name);
  PT_SCENE_BUFFERS(KD_ARG_NAME, KD_ARG_NAME)
#undef KD_ARG_NAME
  expected.push_back("params");
  for (const char* source : {"#include \"pt_megakernel.cl\"\n", "#include \"pt_wavefront.cl\"\n"}) {
    OpenClDevice device;
    if (!device.available()) GTEST_SKIP() << "no OpenCL device";
    ASSERT_EQ(device.build("-cl-kernel-arg-info", source), "");
    cl_uint kernel_count = 0;
    ASSERT_EQ(clCreateKernelsInProgram(device.program(), 0, nullptr, &kernel_count), CL_SUCCESS);
    std::vector<cl_kernel> kernels(kernel_count);
    ASSERT_EQ(clCreateKernelsInProgram(device.program(), kernel_count, kernels.data(), nullptr), CL_SUCCESS);
    EXPECT_GT(kernel_count, 0u) << source;
    for (cl_kernel kernel : kernels) {
      char name[256] = {};
      clGetKernelInfo(kernel, CL_KERNEL_FUNCTION_NAME, sizeof name, name, nullptr);
      cl_uint arg_count = 0;
      clGetKernelInfo(kernel, CL_KERNEL_NUM_ARGS, sizeof arg_count, &arg_count, nullptr);
      ASSERT_GE(arg_count, expected.size()) << name;
      for (cl_uint i = 0; i < expected.size(); ++i) {
        char arg[256] = {};
        ASSERT_EQ(clGetKernelArgInfo(kernel, i, CL_KERNEL_ARG_NAME, sizeof arg, arg, nullptr), CL_SUCCESS);
        EXPECT_EQ(std::string(arg), expected[i]) << name << " argument " << i;
      }
      clReleaseKernel(kernel);
    }
  }
}

TEST(KdOpenCl, KernelTraversalMatchesCpuWithDepthOneStack) {
  OpenClDevice device;
  if (!device.available()) GTEST_SKIP() << "no OpenCL device";
  ASSERT_EQ(device.build("-DKD_SHORT_STACK_SIZE=1"), "");
  const Scene scene = test::icosphere_scene(3, {0, 0, 0}, 1.0f);
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  std::vector<RayRecord> rays = random_rays(scene_bounds(scene), 4096, 7);
  std::vector<HitRecord> cpu;
  trace_closest(tree, rays, cpu, {1, TraversalStack::Depth1});

  const float bounds[6] = {tree.bounds.min.x, tree.bounds.min.y, tree.bounds.min.z,
                           tree.bounds.max.x, tree.bounds.max.y, tree.bounds.max.z};
  std::vector<HitRecord> gpu(rays.size());
  cl_mem hits = device.buffer(gpu.data(), gpu.size() * sizeof(HitRecord));
  device.run("trace_closest",
             {device.buffer(tree.nodes.data(), tree.nodes.size() * sizeof(KdNode)),
              device.buffer(tree.leaf_blocks.data(), tree.leaf_blocks.size() * sizeof(uint32_t)),
              device.buffer(bounds, sizeof bounds),
              device.buffer(rays.data(), rays.size() * sizeof(RayRecord)), hits},
             rays.size(), hits, gpu.data(), gpu.size() * sizeof(HitRecord));
  size_t hit_count = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    ASSERT_EQ(gpu[i].triangle, cpu[i].triangle) << "ray " << i;
    if (cpu[i].triangle != KD_NO_HIT) {
      ++hit_count;
      EXPECT_FLOAT_EQ(gpu[i].t, cpu[i].t) << "ray " << i;
    }
  }
  EXPECT_GT(hit_count, rays.size() / 4);
}

TEST(KdOpenCl, SampleValuesMatchTheCpuBitForBit) {
  OpenClDevice device;
  if (!device.available()) GTEST_SKIP() << "no OpenCL device";
  ASSERT_EQ(device.build(""), "");
  std::vector<kd_u32> keys;
  for (kd_u32 sampler : {PT_SAMPLER_SOBOL, PT_SAMPLER_INDEPENDENT}) {
    for (kd_u32 seed : {0u, 12345u}) {
      for (kd_u32 pixel : {0u, 1u, 65535u, 0xffffffffu}) {
        for (kd_u32 index : {0u, 1u, 2u, 3u, 255u, 1000u, 0x7fffffffu, 0xffffffffu}) {
          for (kd_u32 dimension : {0u, 1u, 2u, 3u, 17u, 150u, 4000u}) keys.insert(keys.end(), {sampler, seed, pixel, index, dimension});
        }
      }
    }
  }
  const size_t count = keys.size() / 5;
  std::vector<kd_u32> kernel(3 * count, 0);
  cl_mem out = device.buffer(kernel.data(), kernel.size() * 4);
  device.run("sample_bits", {device.buffer(keys.data(), keys.size() * 4), out}, count, out, kernel.data(),
             kernel.size() * 4);
  for (size_t i = 0; i < count; ++i) {
    const kd_u32* k = &keys[5 * i];
    const kd_u32 pair = k[4] & ~1u;
    ASSERT_EQ(kernel[3 * i], pt_sample_bits(k[0], k[1], k[2], k[3], k[4]))
        << "sampler " << k[0] << " seed " << k[1] << " pixel " << k[2] << " index " << k[3] << " dimension " << k[4];
    // The pair form gives the same bits as two single values.
    ASSERT_EQ(kernel[3 * i + 1], pt_sample_bits(k[0], k[1], k[2], k[3], pair)) << "query " << i;
    ASSERT_EQ(kernel[3 * i + 2], pt_sample_bits(k[0], k[1], k[2], k[3], pair + 1)) << "query " << i;
  }
  // A bounce's first values in OpenCL C's uint8 lanes (what PoCL's programs use).
  for (size_t i = 0; i < count; ++i) keys[5 * i + 4] = PT_BOUNCE_DIMS(keys[5 * i + 4] % 50);
  std::vector<kd_u32> lanes(PT_BOUNCE_LANES * count, 0);
  cl_mem lanes_out = device.buffer(lanes.data(), lanes.size() * 4);
  device.run("bounce_bits_in_lanes", {device.buffer(keys.data(), keys.size() * 4), lanes_out}, count, lanes_out,
             lanes.data(), lanes.size() * 4);
  for (size_t i = 0; i < count; ++i) {
    const kd_u32* k = &keys[5 * i];
    for (kd_u32 d = 0; d < PT_BOUNCE_LANES; ++d) {
      ASSERT_EQ(lanes[PT_BOUNCE_LANES * i + d], pt_sample_bits(k[0], k[1], k[2], k[3], k[4] + d))
          << "sampler " << k[0] << " index " << k[3] << " dimension " << k[4] + d;
    }
  }
}

}  // namespace
}  // namespace kdray
