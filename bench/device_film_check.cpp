// device_film_check SCENE.kdscene SCENE.kdtree DEVICE_A DEVICE_B [--wavefront] [--size N] [--spp N]
//                   [--camera PX,PY,PZ,TX,TY,TZ,FOV] [--traversal-a auto|fast|robust] [--traversal-b auto|fast|robust]
// Renders one image on two devices (--device names: host, cpu, gpu, an index) and compares the
// films' fixed-point sums exactly, the film that merges bit for bit across devices (film.h);
// prints one JSON line: each device's times, how many sums differ, the largest difference and
// where the first one is. Needs no image codec, so it runs from a bundle of a few binaries
// (scripts/gpu-check.sh). --wavefront renders DEVICE_A's image with the wavefront kernels and
// DEVICE_B's with the megakernel, which the host alone has and which gives the same film
// (determinism_test.cpp). --traversal-a/-b name a device's traversal (fast or robust; auto, the
// default: the device's own), so that one device can be compared with itself. Exit status: 0 bit
// for bit the same; 3 the films differ; 1 failure; 2 usage.
#include <kdray/kdtree.h>
#include <kdray/render.h>
#include <kdray/scene_file.h>
#include <kdray/trace_opencl.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

namespace {

constexpr int kExitDiffer = 3;

kdray::Camera parse_camera(const std::string& text) {
  float v[7];
  char comma;
  std::istringstream in(text);
  for (int i = 0; i < 7; ++i)
    if (!(in >> v[i]) || (i < 6 && !(in >> comma))) throw std::invalid_argument("--camera wants PX,PY,PZ,TX,TY,TZ,FOV");
  kdray::Camera camera;
  camera.position = {v[0], v[1], v[2]};
  camera.target = {v[3], v[4], v[5]};
  camera.vertical_fov_degrees = v[6];
  return camera;
}

nlohmann::json device_report(const std::string& selection, const kdray::RenderStats& stats) {
  return {{"selection", selection},         {"device", stats.device}, {"traversal", stats.traversal},
          {"kernel_options", stats.kernel_options}, {"build_seconds", stats.build_seconds},
          {"render_seconds", stats.render_seconds}, {"rays", stats.rays},
          {"mrays_per_s", stats.render_seconds > 0 ? double(stats.rays) / stats.render_seconds * 1e-6 : 0.0}};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::cerr << "usage: device_film_check SCENE.kdscene SCENE.kdtree DEVICE_A DEVICE_B [--wavefront] [--size N] "
                 "[--spp N] [--camera PX,PY,PZ,TX,TY,TZ,FOV] [--traversal-a auto|fast|robust] [--traversal-b auto|fast|robust]\n";
    return 2;
  }
  try {
    kdray::RenderSettings settings;
    kdray::DeviceSelection a, b;
    a.device = argv[3];
    b.device = argv[4];
    for (int i = 5; i < argc; ++i) {
      const std::string flag = argv[i];
      const bool has_value = i + 1 < argc;
      if (flag == "--wavefront") {
        settings.form = kdray::RenderForm::Wavefront;
      } else if (flag == "--size" && has_value) {
        settings.width = settings.height = static_cast<uint32_t>(std::strtoul(argv[++i], nullptr, 10));
      } else if (flag == "--spp" && has_value) {
        settings.spp = static_cast<uint32_t>(std::strtoul(argv[++i], nullptr, 10));
      } else if (flag == "--camera" && has_value) {
        settings.camera = parse_camera(argv[++i]);
      } else if (flag == "--traversal-a" && has_value) {
        a.traversal = kdray::parse_traversal_path(argv[++i]);
      } else if (flag == "--traversal-b" && has_value) {
        b.traversal = kdray::parse_traversal_path(argv[++i]);
      } else {
        std::cerr << "device_film_check: error: unknown or incomplete option " << flag << "\n";
        return 2;
      }
    }
    const kdray::Scene scene = kdray::read_scene(argv[1]);
    const kdray::KdTree tree = kdray::read_tree(argv[2]);
    kdray::check_tree_matches_scene(tree, argv[2], kdray::geometry_of(scene), argv[1]);

    kdray::RenderStats stats_a, stats_b;
    const kdray::Film film_a = kdray::render(scene, tree, settings, a, &stats_a);
    kdray::RenderSettings megakernel = settings;
    megakernel.form = kdray::RenderForm::Megakernel;
    const kdray::Film film_b = kdray::render(scene, tree, megakernel, b, &stats_b);

    const size_t channels = film_a.channels.size();
    size_t differing = 0;
    uint64_t largest = 0;
    nlohmann::json first = nullptr;
    for (size_t i = 0; i < film_a.sums.size(); ++i) {
      if (film_a.sums[i] == film_b.sums[i]) continue;
      const int64_t difference = film_a.sums[i] - film_b.sums[i];
      largest = std::max<uint64_t>(largest, difference < 0 ? uint64_t(-difference) : uint64_t(difference));
      if (differing++ == 0) {
        const size_t pixel = i / channels;
        first = {{"x", pixel % film_a.width}, {"y", pixel / film_a.width}, {"channel", film_a.channels[i % channels]},
                 {"a", film_a.sums[i]}, {"b", film_b.sums[i]}};
      }
    }
    const nlohmann::json report = {
        {"scene", argv[1]},
        {"form", settings.form == kdray::RenderForm::Wavefront ? "wavefront" : "megakernel"},
        {"width", settings.width},
        {"height", settings.height},
        {"spp", settings.spp},
        {"a", device_report(a.device, stats_a)},
        {"b", device_report(b.device, stats_b)},
        {"values", film_a.sums.size()},
        {"differing_values", differing},
        {"max_abs_difference", largest},  // in the film's fixed-point units (film.h)
        {"first_difference", first},
        {"bit_exact", differing == 0}};
    std::cout << report.dump() << std::endl;
    return differing == 0 ? 0 : kExitDiffer;
  } catch (const std::exception& error) {
    std::cerr << "device_film_check: error: " << error.what() << "\n";
    return 1;
  }
}
