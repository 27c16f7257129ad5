// The render driver: picks the kernel features, builds the program, uploads the scene and
// runs sample passes of the megakernel (or the wavefront form) into a fixed-point film.
#include "render_internal.h"

#include <kdray/error.h>

#include <kernels/pt_rng.h>

#include <xxhash.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace kdray {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
Vec3 sub(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
float length(const Vec3& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }
Vec3 scale(const Vec3& v, float s) { return {v.x * s, v.y * s, v.z * s}; }
void store(float* out, const Vec3& v) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
  out[3] = 0;
}

void set_camera(PtRenderParams& params, const Camera& camera, uint32_t width, uint32_t height) {
  Vec3 forward = sub(camera.target, camera.position);
  forward = scale(forward, 1.0f / length(forward));
  Vec3 right = cross(forward, camera.up);
  right = scale(right, 1.0f / length(right));
  Vec3 up = cross(right, forward);
  float tan_half = std::tan(camera.vertical_fov_degrees * 3.14159265358979f / 360.0f);
  store(params.cam_origin, camera.position);
  store(params.cam_forward, forward);
  store(params.cam_right, scale(right, tan_half * float(width) / float(height)));
  store(params.cam_up, scale(up, tan_half));
}

uint32_t film_channel_count(const RenderSettings& s) {
  return 3 + (s.aov_albedo ? 3 : 0) + (s.aov_normal ? 3 : 0) + (s.aov_depth ? 1 : 0);
}

std::vector<std::string> film_channel_names(const RenderSettings& s) {
  std::vector<std::string> names = {"R", "G", "B"};
  if (s.aov_albedo) names.insert(names.end(), {"albedo.R", "albedo.G", "albedo.B"});
  if (s.aov_normal) names.insert(names.end(), {"N.X", "N.Y", "N.Z"});
  if (s.aov_depth) names.push_back("Z");
  return names;
}

void check_settings(const RenderSettings& s) {
  if (s.width == 0 || s.height == 0 || s.width > 16384 || s.height > 16384) {
    throw Error("", "image size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                        " is out of range (1..16384 per side)");
  }
  if (s.spp == 0) throw Error("", "samples per pixel must be at least 1");
  if (uint64_t(s.sample_offset) + s.spp > 0xFFFFFFFFull) throw Error("", "first sample index + samples per pixel exceeds 2^32");
  if (s.max_bounces > RenderSettings::kMaxBouncesLimit) {
    throw Error("", "max bounces " + std::to_string(s.max_bounces) + " exceeds " +
                        std::to_string(RenderSettings::kMaxBouncesLimit));
  }
  if (!(s.time_limit_seconds >= 0)) throw Error("", "time limit must be >= 0 seconds");
}

// Identifies the tree an image was rendered with (its nodes and leaf arrays).
uint64_t tree_content_hash(const KdTree& tree) {
  XXH3_state_t* state = XXH3_createState();
  XXH3_64bits_reset(state);
  XXH3_64bits_update(state, tree.nodes.data(), tree.nodes.size() * sizeof(KdNode));
  XXH3_64bits_update(state, tree.leaf_triangles.data(), tree.leaf_triangles.size() * sizeof(uint32_t));
  uint64_t hash = XXH3_64bits_digest(state);
  XXH3_freeState(state);
  return hash;
}

// Next-event estimation picks each kind of light that gives light with the same probability.
void set_light_selection(PtRenderParams& params, const DeviceScene& device, const Environment* environment) {
  const bool triangles = device.light_count > 0;
  const bool env = environment && environment_mean_luminance(*environment) > 0;
  const bool punctual = device.punctual_count > 0;
  const int kinds = int(triangles) + int(env) + int(punctual);
  params.select_triangles = triangles ? 1.0f / float(kinds) : 0.0f;
  params.select_environment = env ? 1.0f / float(kinds) : 0.0f;
  params.punctual_count = device.punctual_count;
  if (environment) {
    params.env_width = environment->width;
    params.env_height = environment->height;
    const double angle = environment->rotate_degrees * 3.14159265358979323846 / 180.0;
    params.env_rotate_cos = float(std::cos(angle));
    params.env_rotate_sin = float(std::sin(angle));
    params.env_strength = environment->strength;
  }
}

}  // namespace

Camera render_camera(const Scene& scene, const RenderSettings& settings) {
  Camera camera = settings.camera         ? *settings.camera
                  : scene.cameras.empty() ? default_camera(scene_bounds(scene))
                                          : scene.cameras.front();
  Vec3 forward = sub(camera.target, camera.position);
  if (!finite(camera.position) || !finite(camera.target) || !finite(camera.up) || !(length(forward) > 0) ||
      !(length(cross(forward, camera.up)) > 0)) {
    throw Error("", "degenerate camera: position, target and up must be finite, distinct and not collinear");
  }
  if (!(camera.vertical_fov_degrees > 0 && camera.vertical_fov_degrees < 180)) {
    throw Error("", "vertical field of view must be between 0 and 180 degrees");
  }
  return camera;
}

std::shared_ptr<const Environment> render_environment(const Scene& scene, const RenderSettings& settings) {
  if (settings.environment) return settings.environment;
  if (!settings.default_light || !scene.emissive_triangles.empty() || !scene.lights.empty()) return nullptr;
  static const std::shared_ptr<const Environment> white = std::make_shared<const Environment>(
      uniform_environment({kDefaultLightRadiance, kDefaultLightRadiance, kDefaultLightRadiance}));
  return white;
}

std::string kernel_feature_options(const Scene& scene, const RenderSettings& settings, const DeviceSelection& device) {
  bool mirror = false, glossy = false, glass = false, metal_rough = false, alpha = false;
  bool color_textures = false, metal_rough_textures = false, normal_maps = false, emissive_textures = false;
  const bool uvs = !scene.uvs.empty();
  for (const Material& m : scene.materials) {
    mirror |= m.type == MaterialType::Mirror;
    glossy |= m.type == MaterialType::RoughConductor;
    glass |= m.type == MaterialType::Dielectric;
    metal_rough |= m.type == MaterialType::MetallicRoughness;
    alpha |= m.alpha_mode != AlphaMode::Opaque;
    color_textures |= uvs && m.diffuse_texture >= 0;
    metal_rough_textures |= uvs && m.metal_rough_texture >= 0;
    normal_maps |= uvs && m.normal_texture >= 0;
    emissive_textures |= uvs && m.emissive_texture >= 0;
  }
  const bool emission = !scene.emissive_triangles.empty();
  std::string options = "-cl-std=CL1.2";
  if (emission) options += " -DKD_FEATURE_EMISSION";
  if (mirror) options += " -DKD_FEATURE_MIRROR";
  if (glossy) options += " -DKD_FEATURE_GLOSSY";
  if (glass) options += " -DKD_FEATURE_GLASS";
  if (metal_rough) options += " -DKD_FEATURE_METALLIC_ROUGHNESS";
  if (alpha) options += " -DKD_FEATURE_ALPHA";
  if (color_textures || metal_rough_textures || normal_maps || emissive_textures) options += " -DKD_FEATURE_TEXTURES";
  if (metal_rough_textures) options += " -DKD_FEATURE_METAL_ROUGH_TEXTURE";
  if (normal_maps) options += " -DKD_FEATURE_NORMAL_MAP";
  if (emission && emissive_textures) options += " -DKD_FEATURE_EMISSIVE_TEXTURE";
  if (!scene.normals.empty()) options += " -DKD_FEATURE_NORMALS";
  if (render_environment(scene, settings)) options += " -DKD_FEATURE_ENVIRONMENT";
  if (!scene.lights.empty()) options += " -DKD_FEATURE_PUNCTUAL";
  if (!settings.mis) options += " -DKD_MIS_OFF";
  if (device.short_stack_size) options += " -DKD_SHORT_STACK_SIZE=" + std::to_string(device.short_stack_size);
  return options;
}

void RenderJob::set_pass(uint32_t sample_offset, uint32_t sample_count) {
  params.sample_offset = sample_offset;
  params.sample_count = sample_count;
  cl::check(clEnqueueWriteBuffer(runtime.queue(), params_buffer.get(), CL_TRUE, 0, sizeof params, &params, 0,
                                 nullptr, nullptr),
            "clEnqueueWriteBuffer");
}

namespace {

void run_megakernel_pass(RenderJob& job, cl_kernel kernel, uint32_t first, uint32_t count) {
  job.set_pass(first, count);
  cl::zero_buffer(job.runtime.queue(), job.counter, sizeof(cl_uint));
  cl::run_kernel(job.runtime.queue(), kernel, job.global_size, job.local_size);
  cl::check(clFinish(job.runtime.queue()), "clFinish");
}

}  // namespace

Film render(const Scene& scene, const KdTree& tree, const RenderSettings& settings, const DeviceSelection& device,
            RenderStats* stats_out, const RenderProgress& progress) {
  check_settings(settings);
  Camera camera = render_camera(scene, settings);
  RenderStats stats;
  cl::Runtime& runtime = cl::runtime_for(device);
  stats.device = runtime.info().name;
  stats.kernel_options = kernel_feature_options(scene, settings, device);
  const std::shared_ptr<const Environment> environment = render_environment(scene, settings);
  stats.default_light = environment && !settings.environment;
  const bool wavefront = settings.form == RenderForm::Wavefront;
  cl::ProgramBuild build = runtime.program(wavefront ? "pt_wavefront.cl" : "pt_megakernel.cl", stats.kernel_options);
  stats.build_seconds = build.seconds;
  stats.build_source = build.source;

  auto upload_start = Clock::now();
  RenderJob job{runtime, upload_scene(runtime, scene, tree, environment.get()), PtRenderParams{}, {}, {}, {}, {}, build.program, 0, 0};
  PtRenderParams& params = job.params;
  set_camera(params, camera, settings.width, settings.height);
  for (int axis = 0; axis < 3; ++axis) {
    params.bounds_min[axis] = job.scene.geometry.bounds_min[axis];
    params.bounds_max[axis] = job.scene.geometry.bounds_max[axis];
  }
  params.width = settings.width;
  params.height = settings.height;
  params.seed = settings.seed;
  params.max_bounces = settings.max_bounces;
  static_assert(uint32_t(Sampler::Sobol) == PT_SAMPLER_SOBOL && uint32_t(Sampler::Independent) == PT_SAMPLER_INDEPENDENT,
                "Sampler numbers PT_SAMPLER_*");
  params.sampler = static_cast<uint32_t>(settings.sampler);
  params.light_count = job.scene.light_count;
  params.light_area_pdf_scale = job.scene.light_area_pdf_scale;
  set_light_selection(params, job.scene, environment.get());
  params.aov_mask = (settings.aov_albedo ? PT_AOV_ALBEDO : 0) | (settings.aov_normal ? PT_AOV_NORMAL : 0) |
                    (settings.aov_depth ? PT_AOV_DEPTH : 0);
  params.film_channels = film_channel_count(settings);
  const size_t film_bytes = size_t(settings.width) * settings.height * params.film_channels * sizeof(int64_t);
  job.params_buffer = runtime.buffer(sizeof params, &params);
  job.film = runtime.buffer(film_bytes, nullptr, CL_MEM_READ_WRITE);
  job.counter = runtime.buffer(sizeof(cl_uint), nullptr, CL_MEM_READ_WRITE);
  job.stats = runtime.buffer(2 * sizeof(cl_ulong), nullptr, CL_MEM_READ_WRITE);
  cl::zero_buffer(runtime.queue(), job.film, film_bytes);
  cl::zero_buffer(runtime.queue(), job.stats, 2 * sizeof(cl_ulong));
  job.local_size = runtime.local_size(device);
  job.global_size = runtime.persistent_global_size(job.local_size);
  cl::Kernel megakernel;
  if (!wavefront) {
    megakernel = cl::create_kernel(build.program, "pt_render");
    cl_uint next = bind_scene_args(megakernel.get(), job.scene, job.params_buffer);
    cl::set_arg(megakernel.get(), next++, job.film);
    cl::set_arg(megakernel.get(), next++, job.counter);
    cl::set_arg(megakernel.get(), next++, job.stats);
  }
  cl::check(clFinish(runtime.queue()), "clFinish");
  stats.upload_seconds = seconds_since(upload_start);

  // Passes grow to about half a second each; with a time limit, a pass only starts when its
  // predicted end is within the limit. The pass split never changes the image (fixed point).
  auto render_start = Clock::now();
  uint32_t done = 0;
  double seconds_per_sample = 0;
  while (done < settings.spp) {
    uint32_t count = 1;
    double elapsed = seconds_since(render_start);
    if (seconds_per_sample > 0) {
      double budget = 0.5;
      if (settings.time_limit_seconds > 0) budget = std::min(budget, settings.time_limit_seconds - elapsed);
      count = static_cast<uint32_t>(std::clamp(budget / seconds_per_sample, 1.0, double(settings.spp - done)));
    }
    if (settings.time_limit_seconds > 0 && done > 0 && elapsed + count * seconds_per_sample > settings.time_limit_seconds) {
      break;
    }
    auto pass_start = Clock::now();
    if (wavefront) {
      run_wavefront_pass(job, settings.sample_offset + done, count);
    } else {
      run_megakernel_pass(job, megakernel.get(), settings.sample_offset + done, count);
    }
    seconds_per_sample = seconds_since(pass_start) / count;
    done += count;
    if (progress) progress(done, settings.spp);
  }
  stats.render_seconds = seconds_since(render_start);
  stats.samples_rendered = done;

  Film film;
  film.width = settings.width;
  film.height = settings.height;
  film.channels = film_channel_names(settings);
  film.sums.resize(film_bytes / sizeof(int64_t));
  cl::read_buffer(runtime.queue(), job.film, film_bytes, film.sums.data());
  cl_ulong counters[2] = {0, 0};
  cl::read_buffer(runtime.queue(), job.stats, sizeof counters, counters);
  stats.rays = counters[0];
  stats.nonfinite_values = counters[1];
  film.sample_offset = settings.sample_offset;
  film.sample_count = done;
  film.seed = settings.seed;
  film.max_bounces = settings.max_bounces;
  film.sampler = settings.sampler;
  film.scene_hash = scene.content_hash;
  film.tree_hash = tree_content_hash(tree);
  film.render_seconds = stats.render_seconds;
  if (stats_out) *stats_out = stats;
  return film;
}

}  // namespace kdray
