// The kernel's texture lookup (pt_texture_lookup in kernels/pt_material.h, built here as OpenCL C
// on PoCL) returns what the CPU computes for the same texels: bilinear filtering between texel
// centres at ((i + 0.5) / W, 1 - (j + 0.5) / H) (v = 0 is the bottom row, rows stored top to
// bottom), repeat wrapping in u and v, on texels the host decoded from sRGB (colour) or kept as
// bytes / 255 (data), at texel centres, edges, corners and coordinates outside [0, 1].
#include <kdray/util.h>

#include <kernels/pt_types.h>

#include <CL/cl.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace kdray {
namespace {

const char* kLookupSource = R"CL(
#define KD_FEATURE_TEXTURES
#include "pt_material.h"

__kernel void lookup(__global const PtTexture* textures, __global const float4* texels, __global const float* uvs,
                     int texture, __global float4* out) {
  size_t i = get_global_id(0);
  out[i] = pt_texture_lookup(textures, texels, texture, vload2(i, uvs));
}
)CL";

// Runs `lookup` over the uv points on the first OpenCL device.
class LookupKernel {
 public:
  LookupKernel() {
    cl_platform_id platform = nullptr;
    cl_uint count = 0;
    if (clGetPlatformIDs(1, &platform, &count) != CL_SUCCESS || count == 0) return;
    if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 1, &device_, nullptr) != CL_SUCCESS) return;
    cl_int status = CL_SUCCESS;
    context_ = clCreateContext(nullptr, 1, &device_, nullptr, nullptr, &status);
    queue_ = clCreateCommandQueue(context_, device_, 0, &status);
    program_ = clCreateProgramWithSource(context_, 1, &kLookupSource, nullptr, &status);
    const std::string options = "-I " + std::string(KDRAY_SOURCE_DIR) + "/kernels";
    built_ = clBuildProgram(program_, 1, &device_, options.c_str(), nullptr, nullptr) == CL_SUCCESS;
  }
  ~LookupKernel() {
    if (program_) clReleaseProgram(program_);
    if (queue_) clReleaseCommandQueue(queue_);
    if (context_) clReleaseContext(context_);
  }
  bool ready() const { return built_; }

  std::vector<float> run(const std::vector<PtTexture>& textures, const std::vector<float>& texels, int texture,
                         const std::vector<float>& uvs) {
    const size_t points = uvs.size() / 2;
    std::vector<float> out(points * 4);
    cl_mem buffers[4] = {input(textures.data(), textures.size() * sizeof(PtTexture)),
                         input(texels.data(), texels.size() * sizeof(float)), input(uvs.data(), uvs.size() * sizeof(float)),
                         clCreateBuffer(context_, CL_MEM_WRITE_ONLY, out.size() * sizeof(float), nullptr, nullptr)};
    cl_kernel kernel = clCreateKernel(program_, "lookup", nullptr);
    for (cl_uint i = 0; i < 3; ++i) clSetKernelArg(kernel, i, sizeof(cl_mem), &buffers[i]);
    clSetKernelArg(kernel, 3, sizeof(int), &texture);
    clSetKernelArg(kernel, 4, sizeof(cl_mem), &buffers[3]);
    EXPECT_EQ(clEnqueueNDRangeKernel(queue_, kernel, 1, nullptr, &points, nullptr, 0, nullptr, nullptr), CL_SUCCESS);
    EXPECT_EQ(clEnqueueReadBuffer(queue_, buffers[3], CL_TRUE, 0, out.size() * sizeof(float), out.data(), 0, nullptr,
                                  nullptr),
              CL_SUCCESS);
    clReleaseKernel(kernel);
    for (cl_mem buffer : buffers) clReleaseMemObject(buffer);
    return out;
  }

 private:
  cl_mem input(const void* data, size_t bytes) {
    return clCreateBuffer(context_, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes, const_cast<void*>(data), nullptr);
  }

  cl_device_id device_ = nullptr;
  cl_context context_ = nullptr;
  cl_command_queue queue_ = nullptr;
  cl_program program_ = nullptr;
  bool built_ = false;
};

// A 5 x 3 texture whose neighbouring bytes differ, rows top to bottom.
constexpr uint32_t kWidth = 5, kHeight = 3;
uint8_t texture_byte(uint32_t x, uint32_t y, int channel) { return uint8_t(17 * (y * kWidth + x) + 50 * channel + 3); }

// The texels as the host uploads them: colour textures decoded from sRGB (alpha linear), data
// textures as bytes / 255.
std::vector<float> texels(bool colour) {
  std::vector<float> out;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x)
      for (int c = 0; c < 4; ++c) {
        const float value = texture_byte(x, y, c) / 255.0f;
        out.push_back(colour && c < 3 ? srgb_to_linear(value) : value);
      }
  return out;
}

// The lookup as specified, in double precision.
std::array<double, 4> cpu_lookup(const std::vector<float>& texels, double u, double v) {
  const double fx = u * kWidth - 0.5, fy = (1 - v) * kHeight - 0.5;
  const double x0 = std::floor(fx), y0 = std::floor(fy), ax = fx - x0, ay = fy - y0;
  auto texel = [&](double x, double y, int c) {
    const long wx = ((long(x) % long(kWidth)) + kWidth) % kWidth, wy = ((long(y) % long(kHeight)) + kHeight) % kHeight;
    return double(texels[(wy * kWidth + wx) * 4 + c]);
  };
  std::array<double, 4> out{};
  for (int c = 0; c < 4; ++c)
    out[c] = (1 - ay) * ((1 - ax) * texel(x0, y0, c) + ax * texel(x0 + 1, y0, c)) +
             ay * ((1 - ax) * texel(x0, y0 + 1, c) + ax * texel(x0 + 1, y0 + 1, c));
  return out;
}

std::vector<float> test_points() {
  std::vector<float> uvs;
  for (uint32_t x = 0; x < kWidth; ++x)  // every texel centre
    for (uint32_t y = 0; y < kHeight; ++y) uvs.insert(uvs.end(), {(x + 0.5f) / kWidth, 1 - (y + 0.5f) / kHeight});
  const float edges[] = {0, 1, 0.5f / kWidth, 1 - 0.25f / kWidth, -0.25f, 1.25f, -1, 2, 3.3f, -2.7f, 0.37f};
  for (float u : edges)
    for (float v : edges) uvs.insert(uvs.end(), {u, v});
  return uvs;
}

class TextureLookup : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!kernel_.ready()) FAIL() << "the lookup kernel does not build on the OpenCL device";
  }
  LookupKernel kernel_;
};

TEST_F(TextureLookup, KernelAgreesWithTheCpuOnColourAndDataTexturesAtEdgesAndWrapAround) {
  const std::vector<float> uvs = test_points();
  const std::vector<float> colour = texels(true), data = texels(false);
  std::vector<float> all = colour;
  all.insert(all.end(), data.begin(), data.end());
  const std::vector<PtTexture> textures = {{0, kWidth, kHeight, 0}, {kWidth * kHeight, kWidth, kHeight, 0}};
  for (int texture = 0; texture < 2; ++texture) {
    const std::vector<float> got = kernel_.run(textures, all, texture, uvs);
    for (size_t i = 0; i < uvs.size() / 2; ++i) {
      const std::array<double, 4> want = cpu_lookup(texture == 0 ? colour : data, uvs[2 * i], uvs[2 * i + 1]);
      for (int c = 0; c < 4; ++c)
        ASSERT_NEAR(got[4 * i + c], want[c], 2e-6)
            << "texture " << texture << " uv (" << uvs[2 * i] << ", " << uvs[2 * i + 1] << ") channel " << c;
    }
  }
}

TEST_F(TextureLookup, KnownAnswersOfTheConvention) {
  const std::vector<float> data = texels(false);
  const std::vector<PtTexture> textures = {{0, kWidth, kHeight, 0}};
  // The centre of texel (1, 0) (top row) is at v near 1; u = 0 lies halfway between the last and
  // the first column (repeat); u = 1 + x reads what u = x reads.
  const std::vector<float> uvs = {1.5f / kWidth, 1 - 0.5f / kHeight, 0, 1 - 0.5f / kHeight,
                                  1 + 1.5f / kWidth, 1 - 0.5f / kHeight};
  const std::vector<float> got = kernel_.run(textures, data, 0, uvs);
  for (int c = 0; c < 4; ++c) {
    EXPECT_FLOAT_EQ(got[c], texture_byte(1, 0, c) / 255.0f);
    EXPECT_NEAR(got[4 + c], (texture_byte(kWidth - 1, 0, c) + texture_byte(0, 0, c)) / 510.0f, 1e-6);
    EXPECT_NEAR(got[8 + c], got[c], 1e-6);
  }
}

}  // namespace
}  // namespace kdray
