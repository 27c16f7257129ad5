// kdrender: renders a .kdscene with its prebuilt .kdtree on an OpenCL device (PoCL on the CPU
// by default) to EXR (linear float, AOVs, exact sums, metadata) or PNG/JPEG (sRGB); merges EXRs
// of adjacent sample ranges exactly; lists devices.
//
//   kdrender scene.kdscene scene.kdtree -o out.png --spp 64
//   kdrender --merge a.exr b.exr -o merged.exr
//   kdrender --device list
#include <kdray/image_io.h>
#include <kdray/kdtree.h>
#include <kdray/render.h>
#include <kdray/scene_file.h>

#include <device_option.h>
#include <progress.h>
#include <tool_main.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

namespace {

using kdray::tool::kExitOk;
using kdray::tool::UsageError;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

kdray::Vec3 parse_vec3(const std::string& option, const std::string& text) {
  kdray::Vec3 v;
  char comma1 = 0, comma2 = 0;
  std::istringstream in(text);
  if (!(in >> v.x >> comma1 >> v.y >> comma2 >> v.z) || comma1 != ',' || comma2 != ',' || !in.eof()) {
    throw UsageError(option + " expects X,Y,Z, got '" + text + "'");
  }
  return v;
}

struct Options {
  std::string scene_path, tree_path, output;
  std::vector<std::string> merge_inputs;
  std::string aovs;
  std::string sampler = kdray::sampler_name(kdray::Sampler::Sobol);
  std::string cam_pos, cam_target, cam_up;
  float fov = 0;
  std::string env_image, env_color;
  float env_strength = 1, env_rotate = 0;
  bool no_default_light = false, no_mis = false;
  bool wavefront = false;
  kdray::tool::OutputFlags flags;
  kdray::RenderSettings settings;
  kdray::DeviceSelection device;
};

void add_options(CLI::App& app, Options& o) {
  app.add_option("SCENE", o.scene_path, "The .kdscene to render");
  app.add_option("TREE", o.tree_path, "Its .kdtree (from kdbuild; must match the scene)");
  app.add_option("-o,--output", o.output, "Output image: .exr (linear float), .png or .jpg (sRGB)")->group("Output");
  app.add_option("--aov", o.aovs, "Extra EXR layers, comma-separated: albedo,normal,depth")->group("Output");
  app.add_option("--merge", o.merge_inputs,
                 "Merge EXRs of adjacent sample ranges of one render into --output (exact: see film.h)")
      ->group("Output")
      ->expected(2, 1 << 16);

  auto& s = o.settings;
  app.add_option("--spp", s.spp, "Samples per pixel to render")
      ->check(CLI::Range(1u, 1u << 30))
      ->capture_default_str()->group("Sampling");
  app.add_option("--sample-offset", s.sample_offset, "First sample index (ranges merge exactly)")
      ->capture_default_str()
      ->group("Sampling");
  app.add_option("--seed", s.seed, "Random seed")->capture_default_str()->group("Sampling");
  app.add_option("--sampler", o.sampler,
                 "sobol (Owen-scrambled Sobol', stratified) or independent (hashed random numbers)")
      ->check(CLI::IsMember({"sobol", "independent"}))
      ->capture_default_str()
      ->group("Sampling");
  app.add_option("--max-bounces", s.max_bounces, "Maximum bounces, as Cycles counts them (0: direct light only)")
      ->check(CLI::Range(0u, kdray::RenderSettings::kMaxBouncesLimit))
      ->capture_default_str()
      ->group("Sampling");
  app.add_option("--time-limit", s.time_limit_seconds,
                 "Stop after the last whole sample pass within SECONDS (0: no limit)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str()
      ->group("Sampling");

  app.add_option("--width", s.width, "Image width in pixels")
      ->check(CLI::Range(1u, 16384u))
      ->capture_default_str()->group("Camera");
  app.add_option("--height", s.height, "Image height in pixels")
      ->check(CLI::Range(1u, 16384u))
      ->capture_default_str()->group("Camera");
  app.add_option("--cam-pos", o.cam_pos, "Camera position X,Y,Z (default: the scene's camera)")->group("Camera");
  app.add_option("--cam-target", o.cam_target, "Point the camera looks at, X,Y,Z")->group("Camera");
  app.add_option("--cam-up", o.cam_up, "Up direction X,Y,Z (default 0,1,0)")->group("Camera");
  app.add_option("--fov", o.fov, "Vertical field of view in degrees (default: the scene's camera)")->group("Camera");

  app.add_option("--env", o.env_image,
                 "Environment map: an equirectangular (lat-long) HDR image (EXR, HDR, ...), +Y up, "
                 "mapped as Mitsuba 3's envmap (README.md)")
      ->group("Lights");
  app.add_option("--env-color", o.env_color, "A uniform environment of radiance R,G,B instead of a map")
      ->group("Lights");
  app.add_option("--env-strength", o.env_strength, "Multiplies the environment's radiance")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str()
      ->group("Lights");
  app.add_option("--env-rotate", o.env_rotate, "Turns the environment about +Y by DEGREES, counter-clockwise seen from above")
      ->capture_default_str()
      ->group("Lights");
  app.add_flag("--no-default-light", o.no_default_light,
               "Render a scene without any light black instead of under the default light (a uniform white "
               "environment of radiance 1)")
      ->group("Lights");
  app.add_flag("--no-mis", o.no_mis, "Test switch: light samples at full weight, no multiple importance sampling")
      ->group("Lights");

  kdray::tool::add_device_option(app, o.device.device, false);
  app.add_option("--local-size", o.device.local_size, "OpenCL work-group size (0: device default, 64 on CPUs)")
      ->capture_default_str()
      ->group("Device");
  app.add_option("--stack-size", o.device.short_stack_size,
                 "Debug: traversal short-stack entries (KD_SHORT_STACK_SIZE; 0: kernel default 8)")
      ->capture_default_str()
      ->group("Device");
  app.add_flag("--wavefront", o.wavefront, "Use the wavefront kernels instead of the (faster) megakernel")
      ->group("Device");
}

void apply_camera_options(Options& o) {
  bool any = !o.cam_pos.empty() || !o.cam_target.empty() || !o.cam_up.empty() || o.fov != 0;
  if (!any) return;
  kdray::Camera camera;
  if (o.cam_pos.empty() || o.cam_target.empty()) throw UsageError("--cam-pos and --cam-target go together");
  camera.position = parse_vec3("--cam-pos", o.cam_pos);
  camera.target = parse_vec3("--cam-target", o.cam_target);
  if (!o.cam_up.empty()) camera.up = parse_vec3("--cam-up", o.cam_up);
  if (o.fov != 0) camera.vertical_fov_degrees = o.fov;
  o.settings.camera = camera;
}

void apply_lights(Options& o) {
  if (!o.env_image.empty() && !o.env_color.empty()) throw UsageError("--env and --env-color exclude each other");
  if (o.env_image.empty() && o.env_color.empty() && (o.env_strength != 1 || o.env_rotate != 0)) {
    throw UsageError("--env-strength and --env-rotate need --env or --env-color");
  }
  if (!o.env_image.empty() || !o.env_color.empty()) {
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
    if (!std::isfinite(o.env_strength) || !std::isfinite(o.env_rotate)) {
      throw UsageError("--env-strength and --env-rotate need finite values");
    }
    env.strength = o.env_strength;
    env.rotate_degrees = o.env_rotate;
    o.settings.environment = std::make_shared<const kdray::Environment>(std::move(env));
  }
  o.settings.default_light = !o.no_default_light;
  o.settings.mis = !o.no_mis;
}

void apply_aovs(Options& o) {
  std::istringstream list(o.aovs);
  std::string name;
  while (std::getline(list, name, ',')) {
    if (name == "albedo") o.settings.aov_albedo = true;
    else if (name == "normal") o.settings.aov_normal = true;
    else if (name == "depth") o.settings.aov_depth = true;
    else throw UsageError("--aov: unknown layer '" + name + "' (albedo, normal, depth)");
  }
}

int merge(const Options& o) {
  kdray::Film merged = kdray::read_film_exr(o.merge_inputs.front());
  for (size_t i = 1; i < o.merge_inputs.size(); ++i) {
    try {
      merged = kdray::merge_films(merged, kdray::read_film_exr(o.merge_inputs[i]));
    } catch (const kdray::Error& error) {
      throw kdray::Error(o.merge_inputs[i], error.what());
    }
  }
  kdray::write_film_image(o.output, merged);
  if (o.flags.json) {
    kdray::tool::print_json({{"output", o.output}, {"inputs", o.merge_inputs}, {"sample_offset", merged.sample_offset},
                             {"spp", merged.sample_count}, {"mean_radiance", merged.mean_radiance()}});
  } else if (!o.flags.quiet) {
    std::printf("merged %zu images: samples %u..%u -> %s\n", o.merge_inputs.size(), merged.sample_offset,
                merged.sample_offset + merged.sample_count - 1, o.output.c_str());
  }
  return kExitOk;
}

int render(Options& o) {
  auto load_start = Clock::now();
  auto env_start = Clock::now();
  apply_lights(o);
  double env_seconds = seconds_since(env_start);
  kdray::Scene scene = kdray::read_scene(o.scene_path);
  kdray::KdTree tree = kdray::read_tree(o.tree_path);
  kdray::check_tree_matches_scene(tree, o.tree_path, scene, o.scene_path);
  double load_seconds = seconds_since(load_start);

  if (kdray::render_environment(scene, o.settings) && !o.settings.environment) {
    kdray::tool::print_warning("kdrender", o.scene_path + ": the scene has no light (no emissive triangles, no punctual "
                                           "lights) and no --env: lighting it with the default light, a uniform white "
                                           "environment of radiance 1 (--no-default-light renders black)");
  }
  kdray::tool::ProgressBar progress("kdrender", !o.flags.quiet);
  kdray::RenderStats stats;
  kdray::Film film = kdray::render(scene, tree, o.settings, o.device, &stats,
                                   [&](uint32_t done, uint32_t total) {
                                     progress.update(double(done) / total, std::to_string(done) + "/" +
                                                                               std::to_string(total) + " spp");
                                   });
  progress.finish();
  auto write_start = Clock::now();
  kdray::write_film_image(o.output, film);
  double write_seconds = seconds_since(write_start);

  double pixel_samples = double(film.pixel_count()) * film.sample_count;
  double samples_per_second = stats.render_seconds > 0 ? pixel_samples / stats.render_seconds : 0;
  double rays_per_second = stats.render_seconds > 0 ? double(stats.rays) / stats.render_seconds : 0;
  if (o.flags.json) {
    kdray::tool::print_json({{"output", o.output},
                             {"device", stats.device},
                             {"form", o.wavefront ? "wavefront" : "megakernel"},
                             {"width", film.width},
                             {"height", film.height},
                             {"spp", film.sample_count},
                             {"spp_requested", o.settings.spp},
                             {"sample_offset", film.sample_offset},
                             {"seed", film.seed},
                             {"max_bounces", film.max_bounces},
                             {"sampler", kdray::sampler_name(film.sampler)},
                             {"kernel_options", stats.kernel_options},
                             {"load_seconds", load_seconds},
                             {"environment", o.settings.environment ? o.settings.environment->source
                                             : stats.default_light  ? "default"
                                                                    : ""},
                             {"environment_seconds", env_seconds},
                             {"build_seconds", stats.build_seconds},
                             {"build_source", stats.build_source},
                             {"upload_seconds", stats.upload_seconds},
                             {"render_seconds", stats.render_seconds},
                             {"write_seconds", write_seconds},
                             {"samples_per_second", samples_per_second},
                             {"rays", stats.rays},
                             {"rays_per_second", rays_per_second},
                             {"mean_radiance", film.mean_radiance()},
                             {"nonfinite_values", stats.nonfinite_values}});
  } else if (!o.flags.quiet) {
    std::printf("%s: %ux%u, %u spp (samples %u..%u), %u max bounces, %s sampler, seed %u\n", o.output.c_str(),
                film.width, film.height, film.sample_count, film.sample_offset,
                film.sample_offset + film.sample_count - 1, film.max_bounces, kdray::sampler_name(film.sampler),
                film.seed);
    std::printf("device %s; kernel %s (%s, %.2f s)\n", stats.device.c_str(), stats.kernel_options.c_str(),
                stats.build_source.c_str(), stats.build_seconds);
    std::printf("load %.3f s, render %.3f s: %.2f M samples/s, %.2f M rays/s\n", load_seconds, stats.render_seconds,
                samples_per_second * 1e-6, rays_per_second * 1e-6);
    if (stats.nonfinite_values) std::printf("warning: %llu NaN/Inf sample values were counted as 0\n",
                                            static_cast<unsigned long long>(stats.nonfinite_values));
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Renders a .kdscene with its .kdtree on an OpenCL device (path tracing), or merges\n"
               "EXRs of sample ranges."};
  Options o;
  kdray::tool::add_contract(app, "kdrender", o.flags, "Print statistics as JSON on stdout instead of the summary");
  add_options(app, o);

  return kdray::tool::run(app, argc, argv, [&]() -> int {
    const kdray::tool::DeviceKind device = kdray::tool::device_kind(o.device.device);
    if (device == kdray::tool::DeviceKind::List) return kdray::tool::list_opencl_devices(o.flags.json);
    if (device == kdray::tool::DeviceKind::All) throw UsageError("--device all: rendering on several devices at once is not built yet");
    if (o.output.empty()) throw UsageError("-o OUTPUT is required");
    if (!kdray::is_supported_image_path(o.output)) throw UsageError("-o " + o.output + ": use .exr, .png or .jpg");
    if (!o.merge_inputs.empty()) {
      if (!o.scene_path.empty()) throw UsageError("--merge takes EXR files, not a scene and tree");
      return merge(o);
    }
    if (o.scene_path.empty() || o.tree_path.empty()) throw UsageError("SCENE and TREE are required");
    if (!o.aovs.empty()) apply_aovs(o);
    bool any_aov = o.settings.aov_albedo || o.settings.aov_normal || o.settings.aov_depth;
    if (any_aov && std::filesystem::path(o.output).extension() != ".exr") throw UsageError("--aov needs an .exr output");
    apply_camera_options(o);
    if (o.wavefront) o.settings.form = kdray::RenderForm::Wavefront;
    o.settings.sampler = *kdray::parse_sampler(o.sampler);
    return render(o);
  });
}
