// The render driver: resolves the render once (the view, render_view.cpp; the environment; the
// kernel's feature bits, kernel_features.cpp), builds the program for those features, uploads the
// scene and runs sample passes of the megakernel (or the wavefront form) into a fixed-point film;
// or, for the device "host", runs them with the C++ build of the same code (render_host.cpp).
#include <kdray/render.h>

#include "render_internal.h"

#include <kdray/clock.h>
#include <kdray/error.h>
#include <kdray/trace_opencl.h>

#include <kernels/pt_scene_args.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace kdray {
namespace {

uint32_t aov_mask(const RenderSettings& s) {
  return (s.aov_albedo ? PT_AOV_ALBEDO : 0) | (s.aov_normal ? PT_AOV_NORMAL : 0) | (s.aov_depth ? PT_AOV_DEPTH : 0);
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

// Next-event estimation picks each kind of light that gives light with the same probability.
void set_light_selection(PtRenderParams& params, const SceneArrays& arrays, const Environment* environment) {
  const bool triangles = arrays.light_count > 0;
  const bool env = environment && environment_mean_luminance(*environment) > 0;
  const bool punctual = arrays.punctual_count > 0;
  const int kinds = int(triangles) + int(env) + int(punctual);
  params.select_triangles = triangles ? 1.0f / float(kinds) : 0.0f;
  params.select_environment = env ? 1.0f / float(kinds) : 0.0f;
  params.punctual_count = arrays.punctual_count;
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

uint32_t film_channel_count(const RenderSettings& s) { return pt_film_channel_count(aov_mask(s)); }

std::vector<std::string> film_channel_names(const RenderSettings& s) {
  std::vector<std::string> names = {"R", "G", "B"};
  if (s.aov_albedo) names.insert(names.end(), {"albedo.R", "albedo.G", "albedo.B"});
  if (s.aov_normal) names.insert(names.end(), {"N.X", "N.Y", "N.Z"});
  if (s.aov_depth) names.push_back("Z");
  return names;
}

std::shared_ptr<const Environment> render_environment(const Scene& scene, const RenderSettings& settings) {
  if (settings.environment) return settings.environment;
  if (!settings.default_light || !scene.emissive_triangles.empty() || !scene.lights.empty()) return nullptr;
  static const std::shared_ptr<const Environment> white = std::make_shared<const Environment>(
      uniform_environment({kDefaultLightRadiance, kDefaultLightRadiance, kDefaultLightRadiance}));
  return white;
}

ResolvedRender resolve_render(const Scene& scene, const RenderSettings& requested) {
  ResolvedRender render;
  render.settings = resolve_view(scene, requested);
  check_settings(render.settings);
  render.environment = render_environment(scene, render.settings);
  render.feature_bits = kernel_feature_bits(scene, render.settings, render.camera(), render.environment.get());
  return render;
}

PtRenderParams render_params(const ResolvedRender& render, const SceneArrays& arrays) {
  const RenderSettings& settings = render.settings;
  PtRenderParams params{};
  set_camera(params, render.camera(), settings.width, settings.height);
  for (int axis = 0; axis < 3; ++axis) {
    params.bounds_min[axis] = arrays.geometry.bounds_min[axis];
    params.bounds_max[axis] = arrays.geometry.bounds_max[axis];
  }
  params.width = settings.width;
  params.height = settings.height;
  params.seed = settings.seed;
  params.max_bounces = settings.max_bounces;
  params.sampler = static_cast<uint32_t>(settings.sampler);
  params.light_count = arrays.light_count;
  params.light_area_pdf_scale = arrays.light_area_pdf_scale;
  set_light_selection(params, arrays, render.environment.get());
  params.aov_mask = aov_mask(settings);
  params.film_channels = film_channel_count(settings);
  params.features = render.feature_bits;
  return params;
}

void RenderJob::set_pass(uint32_t sample_offset, uint32_t sample_count) {
  params.sample_offset = sample_offset;
  params.sample_count = sample_count;
  cl::check(clEnqueueWriteBuffer(runtime.queue(), params_buffer.get(), CL_TRUE, 0, sizeof params, &params, 0,
                                 nullptr, nullptr),
            "clEnqueueWriteBuffer");
}

namespace {

// One OpenCL device's part of a render: the scene uploaded to it, its own film and its program.
class DeviceRender : public RenderWorker {
 public:
  DeviceRender(cl::Runtime& runtime, DeviceScene scene, const PtRenderParams& params, cl_program program)
      : job{runtime, std::move(scene), params, {}, {}, {}, {}, program, 0, 0} {}

  void pass(uint32_t first, uint32_t count) override {
    if (!megakernel.get()) return run_wavefront_pass(job, first, count);
    job.set_pass(first, count);
    cl::zero_buffer(job.runtime.queue(), job.counter, sizeof(cl_uint));
    cl::run_kernel(job.runtime.queue(), megakernel.get(), job.global_size, job.local_size);
    cl::check(clFinish(job.runtime.queue()), "clFinish");
  }

  void add_film(std::vector<int64_t>& film, RenderStats& totals) override {
    std::vector<int64_t> sums(film.size());
    cl::read_buffer(job.runtime.queue(), job.film, sums.size() * sizeof(int64_t), sums.data());
    for (size_t i = 0; i < sums.size(); ++i) film[i] += sums[i];
    cl_ulong counters[2] = {0, 0};
    cl::read_buffer(job.runtime.queue(), job.stats, sizeof counters, counters);
    totals.rays += counters[0];
    totals.nonfinite_values += counters[1];
  }

  RenderJob job;
  cl::Kernel megakernel;  // null in the wavefront form
};

std::unique_ptr<RenderWorker> prepare_device(const Scene& scene, const KdTree& tree, const ResolvedRender& render,
                                             const DeviceSelection& device) {
  const RenderSettings& settings = render.settings;
  cl::Runtime& runtime = cl::runtime_for(device);
  RenderStats stats;
  stats.device = runtime.info().name;
  stats.kernel_options = kernel_feature_options(render.feature_bits, device, runtime.info().is_gpu);
  stats.traversal = traversal_path_name(traversal_path_for(device, runtime.info().is_gpu));
  stats.default_light = render.environment && !settings.environment;
  const bool wavefront = settings.form == RenderForm::Wavefront;
  cl::ProgramBuild build = runtime.program(wavefront ? "pt_wavefront.cl" : "pt_megakernel.cl", stats.kernel_options);
  stats.build_seconds = build.seconds;
  stats.build_source = build.source;

  auto upload_start = Clock::now();
  const SceneArrays arrays = scene_arrays(scene, tree, render.environment.get());
  auto device_render =
      std::make_unique<DeviceRender>(runtime, upload_scene(runtime, arrays), render_params(render, arrays), build.program);
  RenderJob& job = device_render->job;
  const size_t film_bytes = size_t(settings.width) * settings.height * job.params.film_channels * sizeof(int64_t);
  job.params_buffer = runtime.buffer(sizeof job.params, &job.params);
  job.film = runtime.buffer(film_bytes, nullptr, CL_MEM_READ_WRITE);
  job.counter = runtime.buffer(sizeof(cl_uint), nullptr, CL_MEM_READ_WRITE);
  job.stats = runtime.buffer(2 * sizeof(cl_ulong), nullptr, CL_MEM_READ_WRITE);
  cl::zero_buffer(runtime.queue(), job.film, film_bytes);
  cl::zero_buffer(runtime.queue(), job.stats, 2 * sizeof(cl_ulong));
  job.local_size = runtime.local_size(device);
  job.global_size = runtime.persistent_global_size(job.local_size);
  if (!wavefront) {
    device_render->megakernel = cl::create_kernel(build.program, "pt_render");
    cl_kernel kernel = device_render->megakernel.get();
    bind_scene_args(kernel, job.scene, job.params_buffer, job.film, job.counter, job.stats);
  }
  cl::check(clFinish(runtime.queue()), "clFinish");
  stats.upload_seconds = seconds_since(upload_start);
  device_render->stats = stats;
  device_render->device_index = runtime.info().index;
  return device_render;
}

// Hands out the render's samples to the devices as consecutive ranges. First pass: every device
// gets one sample, to measure its speed (no device gets a second range before each has had its
// first). Then each range lasts about half a second at the device's measured speed, but never
// more than its speed's share of what is left (a device not measured yet counts at the mean
// speed), so the devices finish together. With a time limit, a range starts only when its
// predicted end is within the limit. Ranges are handed out in order and every range handed out
// completes, so the samples rendered are sample_offset .. sample_offset + handed_out - 1,
// whatever the split.
class SampleScheduler {
 public:
  SampleScheduler(const RenderSettings& settings, size_t devices, const RenderProgress& progress)
      : settings_(settings), rates_(devices, 0.0), started_(devices, false), progress_(progress),
        start_(Clock::now()) {}

  // The next range for `device` (count 0: none left for it).
  std::pair<uint32_t, uint32_t> next(size_t device) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (started_[device]) {
      first_pass_done_.wait(lock, [&] { return failed_ || handed_out_ == settings_.spp || all_started(); });
    }
    // A device that gets nothing more counts as started, so no other waits for it.
    auto none = [&]() -> std::pair<uint32_t, uint32_t> {
      started_[device] = true;
      first_pass_done_.notify_all();
      return {0, 0};
    };
    const uint32_t left = settings_.spp - handed_out_;
    if (failed_ || left == 0) return none();
    const double elapsed = seconds_since(start_);
    uint32_t count = 1;
    const double rate = rates_[device];
    if (rate > 0) {
      double budget = 0.5;
      if (settings_.time_limit_seconds > 0) budget = std::min(budget, settings_.time_limit_seconds - elapsed);
      double known = 0;
      size_t measured = 0;
      for (double r : rates_) {
        known += r;
        measured += r > 0;
      }
      const double total = known + (rates_.size() - measured) * (known / measured);
      const double share = std::ceil(double(left) * rate / total);
      count = static_cast<uint32_t>(std::clamp(std::min(budget * rate, share), 1.0, double(left)));
      if (settings_.time_limit_seconds > 0 && elapsed + count / rate > settings_.time_limit_seconds) return none();
    } else if (settings_.time_limit_seconds > 0 && handed_out_ > 0 && elapsed > settings_.time_limit_seconds) {
      return none();
    }
    const uint32_t first = settings_.sample_offset + handed_out_;
    handed_out_ += count;
    started_[device] = true;
    first_pass_done_.notify_all();
    return {first, count};
  }

  void finished(size_t device, uint32_t count, double seconds) {
    std::lock_guard<std::mutex> lock(mutex_);
    rates_[device] = seconds > 0 ? count / seconds : 1e9;
    completed_ += count;
    if (progress_) progress_(completed_, settings_.spp);
  }
  void fail() {
    std::lock_guard<std::mutex> lock(mutex_);
    failed_ = true;
    first_pass_done_.notify_all();
  }
  uint32_t handed_out() const { return handed_out_; }

 private:
  bool all_started() const { return std::all_of(started_.begin(), started_.end(), [](bool s) { return s; }); }

  const RenderSettings& settings_;
  std::mutex mutex_;
  std::condition_variable first_pass_done_;
  std::vector<double> rates_;  // samples per second per device; 0 until its first range ends
  std::vector<bool> started_;  // the device has had its first range
  uint32_t handed_out_ = 0, completed_ = 0;
  bool failed_ = false;
  const RenderProgress& progress_;
  Clock::time_point start_;
};

// Renders ranges on one device until the scheduler has none left for it.
void run_device(RenderWorker& device, size_t index, SampleScheduler& scheduler, DeviceShare& share) {
  for (;;) {
    auto [first, count] = scheduler.next(index);
    if (count == 0) return;
    auto start = Clock::now();
    device.pass(first, count);
    const double seconds = seconds_since(start);
    share.samples += count;
    share.seconds += seconds;
    scheduler.finished(index, count, seconds);
  }
}

std::string join_distinct(const std::vector<std::string>& items, const char* separator) {
  std::string joined;
  std::vector<std::string> seen;
  for (const std::string& item : items) {
    if (std::find(seen.begin(), seen.end(), item) != seen.end()) continue;
    joined += (seen.empty() ? "" : separator) + item;
    seen.push_back(item);
  }
  return joined;
}

}  // namespace

Film render(const Scene& scene, const KdTree& tree, const RenderSettings& requested, const DeviceSelection& device,
            RenderStats* stats_out, const RenderProgress& progress) {
  const ResolvedRender resolved = resolve_render(scene, requested);
  const RenderSettings& settings = resolved.settings;
  std::vector<std::unique_ptr<RenderWorker>> devices;
  if (device.device == kHostDevice) {
    if (settings.form == RenderForm::Wavefront) throw Error("", "the wavefront form is for OpenCL devices, not the host");
    devices.push_back(prepare_host(scene, tree, resolved, device));
  } else {
    if (device.threads) throw Error("", "threads are for the host device; OpenCL devices run their own");
    for (const DeviceSelection& selection : split_device_selection(device)) {
      devices.push_back(prepare_device(scene, tree, resolved, selection));
    }
  }

  RenderStats stats = devices.front()->stats;
  std::vector<std::string> names, sources, traversals;
  for (size_t i = 1; i < devices.size(); ++i) {
    stats.build_seconds += devices[i]->stats.build_seconds;
    stats.upload_seconds += devices[i]->stats.upload_seconds;
  }
  for (const auto& d : devices) {
    names.push_back(d->stats.device);
    sources.push_back(d->stats.build_source);
    traversals.push_back(d->stats.traversal);
    stats.devices.push_back({d->stats.device, d->device_index, d->stats.traversal, 0, 0});
  }
  stats.build_source = join_distinct(sources, ", ");
  stats.traversal = join_distinct(traversals, ", ");

  auto render_start = Clock::now();
  SampleScheduler scheduler(settings, devices.size(), progress);
  if (devices.size() == 1) {
    run_device(*devices.front(), 0, scheduler, stats.devices.front());
  } else {
    std::vector<std::thread> threads;
    std::vector<std::exception_ptr> errors(devices.size());
    for (size_t i = 0; i < devices.size(); ++i) {
      threads.emplace_back([&, i] {
        try {
          run_device(*devices[i], i, scheduler, stats.devices[i]);
        } catch (...) {
          errors[i] = std::current_exception();
          scheduler.fail();
        }
      });
    }
    for (std::thread& thread : threads) thread.join();
    for (const std::exception_ptr& error : errors) {
      if (error) std::rethrow_exception(error);
    }
  }
  stats.render_seconds = seconds_since(render_start);
  stats.samples_rendered = scheduler.handed_out();
  stats.device = names.size() == 1 ? names.front() : std::to_string(names.size()) + " devices: " + join_distinct(names, ", ");

  // Fixed-point sums add exactly, so the devices' films sum to the single-device film.
  Film film;
  film.width = settings.width;
  film.height = settings.height;
  film.channels = film_channel_names(settings);
  film.sums.assign(film.pixel_count() * film.channels.size(), 0);
  for (auto& d : devices) d->add_film(film.sums, stats);
  film.sample_offset = settings.sample_offset;
  film.sample_count = stats.samples_rendered;
  film.seed = settings.seed;
  film.max_bounces = settings.max_bounces;
  film.sampler = settings.sampler;
  film.scene_hash = scene.content_hash;
  film.tree_hash = tree_content_hash(tree);
  film.settings_hash = render_settings_hash(settings, resolved.camera(), resolved.environment.get());
  film.render_seconds = stats.render_seconds;
  if (stats_out) *stats_out = stats;
  return film;
}

}  // namespace kdray
