// kdrender: renders a .kdscene with its prebuilt .kdtree on an OpenCL device or on the host (the
// same code compiled as C++, the same image; the default where there is no GPU) to EXR (linear
// float, AOVs, exact sums, metadata) or PNG/JPEG (sRGB); renders a batch of frames of one scene
// from a jobs file; merges EXRs of adjacent sample ranges exactly; lists devices.
//
//   kdrender scene.kdscene scene.kdtree -o out.png --spp 64
//   kdrender scene.kdscene scene.kdtree --jobs turntable.jobs --spp 16
//   kdrender --merge a.exr b.exr -o merged.exr
//   kdrender --device list
#include "batch.h"
#include "frame_options.h"
#include "render_frame.h"

#include <kdray/clock.h>
#include <kdray/image_io.h>
#include <kdray/kdtree.h>
#include <kdray/render.h>
#include <kdray/tree_cache.h>

#include <device_option.h>
#include <progress.h>
#include <tool_main.h>
#include <tree_memory.h>

#include <filesystem>
#include <optional>
#include <utility>
#include <cstdio>

namespace {

using kdray::tool::kExitOk;
using kdray::tool::UsageError;
using kdray::Clock;


struct Options {
  std::string scene_path, tree_path, cache_folder;
  std::vector<std::string> merge_inputs;
  std::string jobs_path;
  bool resume = false;
  kdray::tool::OutputFlags flags;
  kdrender::FrameOptions frame;  // a single render's frame, or the defaults of every jobs line
  uint64_t max_memory = 0;
};

void add_options(CLI::App& app, Options& o) {
  app.add_option("SCENE", o.scene_path, "The .kdscene to render");
  app.add_option("TREE", o.tree_path, "Its .kdtree (from kdbuild; must match the scene)");
  app.add_option("--cache", o.cache_folder,
                 "Instead of TREE: a tree cache folder (kdbuild --cache) where the scene's tree is found, or built "
                 "with the default settings");
  kdrender::add_frame_options(app, o.frame);
  app.add_option("--merge", o.merge_inputs,
                 "Merge EXRs of sample ranges of one render (any order) into --output, exactly (film.h); "
                 "refuses other renders, overlaps and gaps; with --spp (and --sample-offset) the ranges must "
                 "cover exactly that")
      ->group("Output")
      ->expected(2, 1 << 16);
  app.add_option("--jobs", o.jobs_path,
                 "Render one frame per line of FILE: each line holds this command's per-frame options (-o, "
                 "--cam-pos, --spp, ...); the options given here are the defaults of every line; '#' comments")
      ->group("Batch");
  app.add_flag("--resume", o.resume, "With --jobs: skip frames whose output is already present and complete")
      ->group("Batch");
  kdray::tool::add_max_memory_option(app, o.max_memory);
}

// Merges the sample ranges given in any order; with --spp (and --sample-offset) they must cover
// exactly that range.
int merge(const Options& o, bool range_given) {
  const std::string& output = o.frame.output;
  if (output.empty()) throw UsageError("-o OUTPUT is required");
  if (!kdray::is_supported_image_path(output)) throw UsageError("-o " + output + ": use .exr, .png or .jpg");
  std::vector<kdray::NamedFilm> inputs;
  for (const std::string& path : o.merge_inputs) inputs.push_back({path, kdray::read_film_exr(path)});
  std::optional<std::pair<uint32_t, uint32_t>> expected;
  if (range_given) expected = std::make_pair(o.frame.settings.sample_offset, o.frame.settings.spp);
  kdray::Film merged = kdray::merge_film_ranges(std::move(inputs), expected);
  kdray::write_film_image(output, merged);
  if (o.flags.json) {
    kdray::tool::print_json({{"output", output}, {"inputs", o.merge_inputs}, {"sample_offset", merged.sample_offset},
                             {"spp", merged.sample_count}, {"mean_radiance", merged.mean_radiance()}});
  } else if (!o.flags.quiet) {
    std::printf("merged %zu images: samples %u..%u -> %s\n", o.merge_inputs.size(), merged.sample_offset,
                merged.sample_offset + merged.sample_count - 1, output.c_str());
  }
  return kExitOk;
}

// Peak memory of a render: the scene and the tree (its leaf blocks' corners included) are held
// by the host and again by the OpenCL device (host memory on PoCL), and each film channel keeps
// exact sums, means and the device's accumulators. An estimate with a margin, not a measurement
// (RELIABILITY.md, Resource limits).
constexpr uint64_t kRenderBytesPerInputByte = 3;
constexpr uint64_t kRenderBytesPerPixelChannel = 32;

uint64_t estimated_render_bytes(const Options& o, const kdray::RenderSettings& s) {
  auto size_of = [](const std::string& path) {  // a missing file is reported by its reader
    std::error_code error;
    const uint64_t size = std::filesystem::file_size(path, error);
    return error ? 0 : size;
  };
  // Before the scene is read, a side left to the camera's aspect ratio counts as the default size.
  const uint64_t pixels = uint64_t(s.width ? s.width : kdray::RenderSettings::kDefaultSize) *
                          (s.height ? s.height : kdray::RenderSettings::kDefaultSize);
  return kRenderBytesPerInputByte * (size_of(o.scene_path) + size_of(o.tree_path)) +
         kRenderBytesPerPixelChannel * pixels * kdray::film_channel_count(s);
}

int render(const Options& o) {
  kdrender::EnvironmentCache environments;
  kdrender::Frame frame;
  if (o.jobs_path.empty()) frame = kdrender::resolve_frame(o.frame, environments);
  // A batch is checked against its defaults; each line's size is its own.
  kdray::check_memory_estimate(o.scene_path, "rendering it",
                               estimated_render_bytes(o, o.jobs_path.empty() ? frame.settings : o.frame.settings),
                               o.max_memory);
  auto load_start = Clock::now();
  kdray::SceneAndTree read = kdray::read_scene_and_tree(o.scene_path, o.tree_path, o.cache_folder,
                                                       [](const std::string& line) {
                                                         kdray::tool::print_warning("kdrender", line);
                                                       });
  kdray::Scene& scene = read.scene;
  kdray::KdTree& tree = read.tree;
  double load_seconds = kdray::seconds_since(load_start);
  if (!o.jobs_path.empty()) {
    return kdrender::run_batch(scene, tree, o.frame, {o.scene_path, o.jobs_path, o.resume, o.flags.json, o.flags.quiet},
                               load_seconds);
  }

  frame.settings = kdray::resolve_view(scene, frame.settings);
  kdrender::warn_if_default_light(scene, o.scene_path, frame);
  const double copy_seconds =
      kdray::tool::copy_tree_if_repaid(tree, kdrender::host_rays_of(frame), frame.device.threads);
  kdray::tool::ProgressBar progress("kdrender", !o.flags.quiet);
  kdrender::FrameResult result = kdrender::render_frame(scene, tree, frame, [&](uint32_t done, uint32_t total) {
    progress.update(double(done) / total, std::to_string(done) + "/" + std::to_string(total) + " spp");
  });
  progress.finish();
  if (o.flags.json) {
    nlohmann::json report = kdrender::frame_json(frame, result);
    report["load_seconds"] = load_seconds;
    kdray::tool::add_tree_memory(report, copy_seconds);
    kdray::tool::print_json(report);
  } else if (!o.flags.quiet) {
    kdrender::print_frame_summary(frame, result);
    std::printf("load %.3f s\n", load_seconds);
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Renders a .kdscene with its .kdtree on OpenCL devices or the host (path tracing), a batch of\n"
               "frames (--jobs), or merges EXRs of sample ranges."};
  Options o;
  kdray::tool::add_contract(app, "kdrender", o.flags, "Print statistics as JSON on stdout instead of the summary");
  add_options(app, o);

  return kdray::tool::run(app, argc, argv, [&]() -> int {
    if (kdray::tool::device_kind(o.frame.device.device) == kdray::tool::DeviceKind::List) {
      return kdray::tool::list_opencl_devices(o.flags.json, kdray::device_for_render());
    }
    if (!o.merge_inputs.empty()) {
      if (!o.scene_path.empty() || !o.jobs_path.empty()) throw UsageError("--merge takes EXR files, not a scene and tree");
      return merge(o, app.count("--spp") + app.count("--sample-offset") > 0);
    }
    if (o.resume && o.jobs_path.empty()) throw UsageError("--resume needs --jobs");
    if (o.scene_path.empty() || o.tree_path.empty() == o.cache_folder.empty())
      throw UsageError("SCENE and either TREE or --cache DIR are required");
    return render(o);
  });
}
