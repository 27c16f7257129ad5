// Rendering a scene with its k-d tree on OpenCL devices or on the host: the call, and what it
// derives from the scene and the settings (kdray/render_settings.h).
#pragma once

#include <kdray/environment.h>
#include <kdray/film.h>
#include <kdray/kdtree.h>
#include <kdray/opencl_device.h>
#include <kdray/render_settings.h>
#include <kdray/scene.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace kdray {

constexpr float kDefaultLightRadiance = 1.0f;

// The environment a render uses: settings.environment, else the default light when the scene
// has no light of its own and settings.default_light is on, else none.
std::shared_ptr<const Environment> render_environment(const Scene& scene, const RenderSettings& settings);

// Called after each pass with the samples per pixel done so far and the total asked for.
using RenderProgress = std::function<void(uint32_t done, uint32_t total)>;

// The device name that renders with the C++ build of the kernels' code on the CPU.
constexpr const char* kHostDevice = "host";

// The device a render that names no device runs on: "auto" (OpenCL's choice, the GPU) where an
// OpenCL GPU is present; else kHostDevice where this CPU runs the host's x86-64-v3 build, which
// renders 8 paths at a time in AVX2 lanes and rendered every scene measured at least as fast as
// PoCL (BENCHMARKS.md), or where no OpenCL platform is installed at all; else "auto" (PoCL). The
// OpenCL devices are listed once per process.
std::string device_for_render();

// Renders the range; throws kdray::Error for bad settings (size, camera, bounces). With several
// devices (device.device "all" or a list "0,1"), each renders consecutive sample ranges sized by
// its measured speed into its own film, and the films' exact sums add up to the single-device
// image bit for bit. device.device "host" (kHostDevice) renders with the C++ build of the same
// code on device.threads threads instead, no OpenCL involved: the same film, bit for bit.
Film render(const Scene& scene, const KdTree& tree, const RenderSettings& settings,
            const DeviceSelection& device, RenderStats* stats = nullptr, const RenderProgress& progress = {});

// The OpenCL build options (feature defines) for a scene: only what it uses, so a diffuse-only
// scene compiles a diffuse-only kernel; with the traversal a GPU (gpu) or a CPU device gets
// (traversal_path_for, trace_opencl.h).
std::string kernel_feature_options(const Scene& scene, const RenderSettings& settings, const DeviceSelection& device,
                                   bool gpu = false);

// The camera from settings, the scene or default_camera(scene bounds), with settings.fov_degrees
// applied, checked (finite, non-degenerate, 0 < fov < 180, a positive orthographic extent).
Camera render_camera(const Scene& scene, const RenderSettings& settings);

// The image size for a camera, as glTF viewers and Blender frame an asset: both sides as given;
// one side given, the other from the camera's aspect ratio; neither, the longer side
// RenderSettings::kDefaultSize. A camera without an aspect ratio gives square images.
void resolve_image_size(const Camera& camera, uint32_t& width, uint32_t& height);

// The settings with what they leave to the scene filled in: the camera (render_camera) and the
// image size (resolve_image_size). render() does this itself; tools call it to know the size.
RenderSettings resolve_view(const Scene& scene, RenderSettings settings);

// The film's channels for these settings: RGB, then the AOV layers asked for, in the order the
// kernels accumulate them (kernels/pt_codes.h); film_channel_names has film_channel_count names.
uint32_t film_channel_count(const RenderSettings& settings);
std::vector<std::string> film_channel_names(const RenderSettings& settings);

// Identifies the tree an image was rendered with (its nodes and leaf arrays): Film::tree_hash.
uint64_t tree_content_hash(const KdTree& tree);

// Identifies what else decides a render's pixels besides the film's size, samples, seed, bounces,
// sampler, scene and tree: the camera, the environment (its pixels included), whether the default
// light shines and the MIS switch. Film::settings_hash; merging refuses films that differ in it.
uint64_t render_settings_hash(const Scene& scene, const RenderSettings& settings);

}  // namespace kdray
