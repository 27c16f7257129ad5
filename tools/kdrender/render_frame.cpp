#include "render_frame.h"

#include <kdray/clock.h>
#include <kdray/image_io.h>
#include <kdray/util.h>

#include <tool_main.h>

#include <cstdio>
#include <filesystem>

namespace kdrender {
namespace {

double rate(double count, double seconds) { return seconds > 0 ? count / seconds : 0; }

}  // namespace

FrameResult render_frame(const kdray::Scene& scene, const kdray::KdTree& tree, const Frame& frame,
                         const kdray::RenderProgress& progress) {
  FrameResult result;
  // For an output OpenImageIO writes (PNG, JPEG; EXR needs none of it), its libraries load while
  // the device renders, from the first finished pass on: PoCL has loaded its kernel library by
  // then, so neither load waits for the other.
  auto progress_then_preload = [&progress, &frame](uint32_t done, uint32_t total) {
    kdray::preload_image_io(frame.output);
    if (progress) progress(done, total);
  };
  result.film = kdray::render(scene, tree, frame.settings, frame.device, &result.stats, progress_then_preload);
  auto write_start = kdray::Clock::now();
  kdray::write_film_image(frame.output, result.film);
  result.write_seconds = kdray::seconds_since(write_start);
  return result;
}

uint64_t host_rays_of(const Frame& frame) {
  if (frame.device.device != kdray::kHostDevice) return 0;
  const kdray::RenderSettings& s = frame.settings;
  const uint64_t width = s.width ? s.width : kdray::RenderSettings::kDefaultSize;
  const uint64_t height = s.height ? s.height : kdray::RenderSettings::kDefaultSize;
  return width * height * s.spp * (uint64_t{s.max_bounces} + 1);
}

nlohmann::json frame_json(const Frame& frame, const FrameResult& result) {
  const kdray::Film& film = result.film;
  const kdray::RenderStats& stats = result.stats;
  const double pixel_samples = double(film.pixel_count()) * film.sample_count;
  const auto& environment = frame.settings.environment;
  nlohmann::json devices = nlohmann::json::array();
  for (const kdray::DeviceShare& share : stats.devices) {
    devices.push_back({{"device", share.device},
                       {"index", share.index},
                       {"traversal", share.traversal},
                       {"samples", share.samples},
                       {"share", film.sample_count ? double(share.samples) / film.sample_count : 0.0},
                       {"seconds", share.seconds},
                       {"samples_per_second", rate(double(film.pixel_count()) * share.samples, share.seconds)}});
  }
  nlohmann::json report = {{"devices", devices},
          {"output", frame.output},
          {"device", stats.device},
          {"form", frame.settings.form == kdray::RenderForm::Wavefront ? "wavefront" : "megakernel"},
          {"width", film.width},
          {"height", film.height},
          {"spp", film.sample_count},
          {"spp_requested", frame.settings.spp},
          {"sample_offset", film.sample_offset},
          {"seed", film.seed},
          {"max_bounces", film.max_bounces},
          {"sampler", kdray::sampler_name(film.sampler)},
          {"kernel_options", stats.kernel_options},
          {"traversal", stats.traversal},
          {"environment", environment ? environment->source : stats.default_light ? "default" : ""},
          {"environment_seconds", frame.environment_seconds},
          {"build_seconds", stats.build_seconds},
          {"build_source", stats.build_source},
          {"upload_seconds", stats.upload_seconds},
          {"render_seconds", stats.render_seconds},
          {"write_seconds", result.write_seconds},
          {"samples_per_second", rate(pixel_samples, stats.render_seconds)},
          {"rays", stats.rays},
          {"mrays_per_s", rate(double(stats.rays), stats.render_seconds) * 1e-6},
          {"mean_radiance", film.mean_radiance()},
          {"nonfinite_values", stats.nonfinite_values}};
  if (stats.device == kdray::kHostDevice) report["threads"] = stats.threads;
  return report;
}

void print_frame_summary(const Frame& frame, const FrameResult& result) {
  const kdray::Film& film = result.film;
  const kdray::RenderStats& stats = result.stats;
  const double pixel_samples = double(film.pixel_count()) * film.sample_count;
  std::printf("%s: %ux%u, %u spp (samples %u..%u), %u max bounces, %s sampler, seed %u\n", frame.output.c_str(),
              film.width, film.height, film.sample_count, film.sample_offset,
              film.sample_offset + film.sample_count - 1, film.max_bounces, kdray::sampler_name(film.sampler),
              film.seed);
  const std::string threads = stats.device == kdray::kHostDevice ? " (" + std::to_string(stats.threads) + " threads)" : "";
  std::printf("device %s%s; kernel %s (%s, %.2f s); %s traversal\n", stats.device.c_str(), threads.c_str(),
              stats.kernel_options.c_str(), stats.build_source.c_str(), stats.build_seconds, stats.traversal.c_str());
  std::printf("render %.3f s: %.2f M samples/s, %.2f M rays/s\n", stats.render_seconds,
              rate(pixel_samples, stats.render_seconds) * 1e-6, rate(double(stats.rays), stats.render_seconds) * 1e-6);
  if (stats.devices.size() > 1) {
    for (const kdray::DeviceShare& share : stats.devices) {
      std::printf("  device %d (%s): %u spp (%.0f%%), %.2f M samples/s\n", share.index, share.device.c_str(),
                  share.samples, film.sample_count ? 100.0 * share.samples / film.sample_count : 0.0,
                  rate(double(film.pixel_count()) * share.samples, share.seconds) * 1e-6);
    }
  }
  if (stats.nonfinite_values) {
    std::printf("warning: %llu NaN/Inf sample values were counted as 0\n",
                static_cast<unsigned long long>(stats.nonfinite_values));
  }
}

void warn_if_default_light(const kdray::Scene& scene, const std::string& scene_path, const Frame& frame) {
  static bool warned = false;
  if (warned || frame.settings.environment || !kdray::render_environment(scene, frame.settings)) return;
  warned = true;
  kdray::tool::print_warning("kdrender", scene_path +
                                             ": the scene has no light (no emissive triangles, no punctual lights) "
                                             "and no --env: lighting it with the default light, a uniform white "
                                             "environment of radiance 1 (--no-default-light renders black)");
}

bool frame_already_written(const Frame& frame, const kdray::Scene& scene, uint64_t tree_hash) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(frame.output, error)) return false;
  const kdray::RenderSettings& s = frame.settings;
  if (kdray::lowercase_extension(frame.output) != ".exr") {
    auto size = kdray::read_image_size(frame.output);
    return size && size->first == s.width && size->second == s.height;
  }
  kdray::Film film;
  try {
    film = kdray::read_film_exr(frame.output);
  } catch (const kdray::Error&) {
    return false;  // not an image of ours: render it again
  }
  return film.width == s.width && film.height == s.height && film.channels.size() == kdray::film_channel_count(s) &&
         film.sample_offset == s.sample_offset && film.sample_count == s.spp && film.seed == s.seed &&
         film.max_bounces == s.max_bounces && film.sampler == s.sampler && film.scene_hash == scene.content_hash &&
         film.tree_hash == tree_hash && film.settings_hash == kdray::render_settings_hash(scene, s);
}

}  // namespace kdrender
