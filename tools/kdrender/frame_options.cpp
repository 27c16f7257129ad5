#include "frame_options.h"

#include <kdray/clock.h>
#include <kdray/image_io.h>
#include <kdray/trace_opencl.h>
#include <kdray/util.h>

#include <device_option.h>

#include <cmath>
#include <sstream>

namespace kdrender {
namespace {

kdray::Vec3 parse_vec3(const std::string& option, const std::string& text) {
  kdray::Vec3 v;
  char comma1 = 0, comma2 = 0;
  std::istringstream in(text);
  if (!(in >> v.x >> comma1 >> v.y >> comma2 >> v.z) || comma1 != ',' || comma2 != ',' || !in.eof()) {
    throw UsageError(option + " expects X,Y,Z, got '" + text + "'");
  }
  return v;
}

// --fov alone changes the scene camera's angle and keeps its place; --cam-pos and --cam-target
// replace the camera.
void apply_camera(const FrameOptions& o, kdray::RenderSettings& settings) {
  if (o.fov != 0 && !(o.fov > 0 && o.fov < 180)) throw UsageError("--fov must be between 0 and 180 degrees");
  settings.fov_degrees = o.fov;
  if (o.cam_pos.empty() && o.cam_target.empty() && o.cam_up.empty()) return;
  kdray::Camera camera;
  if (o.cam_pos.empty() || o.cam_target.empty()) throw UsageError("--cam-pos and --cam-target go together");
  camera.position = parse_vec3("--cam-pos", o.cam_pos);
  camera.target = parse_vec3("--cam-target", o.cam_target);
  if (!o.cam_up.empty()) camera.up = parse_vec3("--cam-up", o.cam_up);
  settings.camera = camera;
}

void apply_aovs(const FrameOptions& o, kdray::RenderSettings& settings) {
  std::istringstream list(o.aovs);
  std::string name;
  while (std::getline(list, name, ',')) {
    if (name == "albedo") settings.aov_albedo = true;
    else if (name == "normal") settings.aov_normal = true;
    else if (name == "depth") settings.aov_depth = true;
    else throw UsageError("--aov: unknown layer '" + name + "' (albedo, normal, depth)");
  }
  bool any_aov = settings.aov_albedo || settings.aov_normal || settings.aov_depth;
  if (any_aov && kdray::lowercase_extension(o.output) != ".exr") throw UsageError("--aov needs an .exr output");
}

}  // namespace

void add_frame_options(CLI::App& app, FrameOptions& o) {
  // Each block of options is one group of --help; the caller's own options keep its group.
  CLI::OptionDefaults* defaults = app.option_defaults();
  const std::string callers_group = defaults->get_group();

  defaults->group("Output");
  app.add_option("-o,--output", o.output, "Output image: .exr (linear float), .png or .jpg (sRGB)");
  app.add_option("--aov", o.aovs, "Extra EXR layers, comma-separated: albedo,normal,depth");

  auto& s = o.settings;
  defaults->group("Sampling");
  app.add_option("--spp", s.spp, "Samples per pixel to render")->check(CLI::Range(1u, 1u << 30))->capture_default_str();
  app.add_option("--sample-offset", s.sample_offset, "First sample index (ranges merge exactly)")
      ->capture_default_str();
  app.add_option("--seed", s.seed, "Random seed")->capture_default_str();
  app.add_option("--sampler", o.sampler,
                 "sobol (Owen-scrambled Sobol', stratified) or independent (hashed random numbers)")
      ->check(CLI::IsMember({"sobol", "independent"}))
      ->capture_default_str();
  app.add_option("--max-bounces", s.max_bounces, "Maximum bounces, as Cycles counts them (0: direct light only)")
      ->check(CLI::Range(0u, kdray::RenderSettings::kMaxBouncesLimit))
      ->capture_default_str();
  app.add_option("--time-limit", s.time_limit_seconds,
                 "Stop after the last whole sample pass within SECONDS (0: no limit)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();

  defaults->group("Camera");
  app.add_option("--width", s.width,
                 "Image width in pixels (default: from --height and the camera's aspect ratio; with neither, the "
                 "longer side is 512, a camera without an aspect ratio square)")
      ->check(CLI::Range(1u, 16384u));
  app.add_option("--height", s.height, "Image height in pixels (default: from --width and the camera's aspect ratio)")
      ->check(CLI::Range(1u, 16384u));
  app.add_option("--cam-pos", o.cam_pos, "Camera position X,Y,Z (default: the scene's camera)");
  app.add_option("--cam-target", o.cam_target, "Point the camera looks at, X,Y,Z");
  app.add_option("--cam-up", o.cam_up, "Up direction X,Y,Z (default 0,1,0)");
  app.add_option("--fov", o.fov,
                 "Vertical field of view in degrees (default: the scene's camera's; alone, it keeps that camera's "
                 "position and direction)");

  defaults->group("Lights");
  app.add_option("--env", o.env_image,
                 "Environment map: an equirectangular (lat-long) HDR image (EXR, HDR, ...), +Y up, "
                 "mapped as Mitsuba 3's envmap (README.md)");
  app.add_option("--env-color", o.env_color, "A uniform environment of radiance R,G,B instead of a map");
  app.add_option("--env-strength", o.env_strength, "Multiplies the environment's radiance")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--env-rotate", o.env_rotate,
                 "Turns the environment about +Y by DEGREES, counter-clockwise seen from above")
      ->capture_default_str();
  app.add_flag("--no-default-light", o.no_default_light,
               "Render a scene without any light black instead of under the default light (a uniform white "
               "environment of radiance 1)");
  app.add_flag("--no-mis", o.no_mis, "Test switch: light samples at full weight, no multiple importance sampling");

  kdray::tool::add_device_option(app, o.device.device);
  defaults->group("Device");
  kdray::tool::add_threads_option(app, o.device.threads);
  app.add_option("--local-size", o.device.local_size, "OpenCL work-group size (0: device default, 64 on CPUs)")
      ->capture_default_str();
  app.add_option("--stack-size", o.device.short_stack_size,
                 "Debug: traversal short-stack entries (KD_SHORT_STACK_SIZE; 0: kernel default 8)")
      ->capture_default_str();
  app.add_flag("--wavefront", o.wavefront, "Use the wavefront kernels instead of the (faster) megakernel");
  app.add_option("--traversal", o.traversal,
                 "Traversal the OpenCL programs compile: fast (a lean path for common rays, the robust code for the "
                 "rest), robust (the robust code alone), or auto (robust on a GPU, fast on a CPU); the same image")
      ->check(CLI::IsMember({"auto", "fast", "robust"}))
      ->capture_default_str();

  defaults->group(callers_group);
}

std::shared_ptr<const kdray::Environment> EnvironmentCache::get(const FrameOptions& o, double* load_seconds) {
  *load_seconds = 0;
  if (!o.env_image.empty() && !o.env_color.empty()) throw UsageError("--env and --env-color exclude each other");
  if (o.env_image.empty() && o.env_color.empty()) {
    if (o.env_strength != 1 || o.env_rotate != 0) {
      throw UsageError("--env-strength and --env-rotate need --env or --env-color");
    }
    return nullptr;
  }
  if (!std::isfinite(o.env_strength) || !std::isfinite(o.env_rotate)) {
    throw UsageError("--env-strength and --env-rotate need finite values");
  }
  std::ostringstream key;
  key << o.env_image << '\n' << o.env_color << '\n' << o.env_strength << '\n' << o.env_rotate;
  auto& cached = loaded_[key.str()];
  if (cached) return cached;
  auto start = kdray::Clock::now();
  kdray::Environment env;
  if (!o.env_image.empty()) {
    env = kdray::load_environment(o.env_image);
  } else {
    kdray::Vec3 color = parse_vec3("--env-color", o.env_color);
    if (!(color.x >= 0 && color.y >= 0 && color.z >= 0) || !std::isfinite(color.x + color.y + color.z)) {
      throw UsageError("--env-color needs finite values >= 0");
    }
    env = kdray::uniform_environment(color);
  }
  env.strength = o.env_strength;
  env.rotate_degrees = o.env_rotate;
  cached = std::make_shared<const kdray::Environment>(std::move(env));
  *load_seconds = kdray::seconds_since(start);
  return cached;
}

Frame resolve_frame(const FrameOptions& o, EnvironmentCache& environments) {
  if (kdray::tool::device_kind(o.device.device) == kdray::tool::DeviceKind::List) {
    throw UsageError("--device list prints the devices; it renders nothing");
  }
  const bool opencl_only = o.device.local_size || o.device.short_stack_size || o.wavefront || o.traversal == "robust";
  if (o.device.device == kdray::kHostDevice && opencl_only) {
    throw UsageError("--local-size, --stack-size, --wavefront and --traversal robust are for OpenCL devices, not "
                     "--device host");
  }
  if (o.output.empty()) throw UsageError("-o OUTPUT is required");
  if (!kdray::is_supported_image_path(o.output)) throw UsageError("-o " + o.output + ": use .exr, .png or .jpg");
  Frame frame{o.output, o.settings, o.device, 0};
  // auto: a GPU, else the faster CPU path; OpenCL's own choice where an option is OpenCL's alone
  if (frame.device.device == "auto" && !opencl_only) frame.device.device = kdray::device_for_render();
  kdray::tool::check_threads_option(frame.device.device, frame.device.threads);
  frame.device.traversal = kdray::parse_traversal_path(o.traversal);
  kdray::RenderSettings& s = frame.settings;
  apply_aovs(o, s);
  apply_camera(o, s);
  if (o.wavefront) s.form = kdray::RenderForm::Wavefront;
  s.sampler = *kdray::parse_sampler(o.sampler);
  s.environment = environments.get(o, &frame.environment_seconds);
  s.default_light = !o.no_default_light;
  s.mis = !o.no_mis;
  return frame;
}

}  // namespace kdrender
