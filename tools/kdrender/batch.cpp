#include "batch.h"

#include "jobs.h"
#include "render_frame.h"

#include <kdray/clock.h>

#include <tool_main.h>
#include <tree_memory.h>

#include <cstdio>

namespace kdrender {
namespace {

using kdray::Clock;

struct FrameOutcome {
  enum Status { Rendered, Skipped, Failed } status = Rendered;
  std::string error;
  nlohmann::json stats;
};

const char* status_name(FrameOutcome::Status status) {
  return status == FrameOutcome::Rendered ? "rendered" : status == FrameOutcome::Skipped ? "skipped" : "failed";
}

}  // namespace

int run_batch(const kdray::Scene& scene, kdray::KdTree& tree, const FrameOptions& defaults,
              const BatchOptions& batch, double load_seconds) {
  const auto start = Clock::now();
  std::vector<JobLine> jobs = read_jobs(batch.jobs_path, defaults);
  EnvironmentCache environments;
  std::vector<Frame> frames;
  for (const JobLine& job : jobs) {
    try {
      frames.push_back(resolve_frame(job.options, environments));
    } catch (const UsageError& e) {
      throw UsageError(batch.jobs_path + ":" + std::to_string(job.line_number) + ": " + e.what());
    }
  }

  // The tree is placed for the host before the first host frame that renders (not one skipped
  // by --resume), for the rays of it and every host frame after it, with its threads.
  std::vector<uint64_t> host_rays_from(frames.size() + 1, 0);
  for (size_t i = frames.size(); i-- > 0;) host_rays_from[i] = host_rays_from[i + 1] + host_rays_of(frames[i]);
  bool tree_placed = false;
  double copy_seconds = -1;

  const uint64_t tree_hash = kdray::tree_content_hash(tree);
  const bool report = !batch.quiet && !batch.json;
  std::vector<FrameOutcome> outcomes(frames.size());
  size_t counts[3] = {0, 0, 0};
  for (size_t i = 0; i < frames.size(); ++i) {
    Frame& frame = frames[i];
    FrameOutcome& outcome = outcomes[i];
    auto frame_start = Clock::now();
    try {
      frame.settings = kdray::resolve_view(scene, frame.settings);
      if (batch.resume && frame_already_written(frame, scene, tree_hash)) {
        outcome.status = FrameOutcome::Skipped;
      } else {
        warn_if_default_light(scene, batch.scene_path, frame);
        if (!tree_placed && host_rays_of(frame) > 0) {
          copy_seconds = kdray::tool::copy_tree_if_repaid(tree, host_rays_from[i], frame.device.threads);
          tree_placed = true;
        }
        FrameResult result = render_frame(scene, tree, frame);
        outcome.stats = frame_json(frame, result);
      }
    } catch (const std::exception& e) {
      outcome.status = FrameOutcome::Failed;
      outcome.error = e.what();
      kdray::tool::print_error("kdrender", frame.output + " (" + batch.jobs_path + ":" +
                                               std::to_string(jobs[i].line_number) + "): " + outcome.error);
    }
    ++counts[outcome.status];
    if (report) {
      std::fprintf(stderr, "kdrender: frame %zu/%zu %s: %s (%.2f s)\n", i + 1, frames.size(), frame.output.c_str(),
                   outcome.status == FrameOutcome::Skipped ? "already present, skipped" : status_name(outcome.status),
                   kdray::seconds_since(frame_start));
    }
  }
  const double seconds = kdray::seconds_since(start) + load_seconds;
  const size_t rendered = counts[FrameOutcome::Rendered], skipped = counts[FrameOutcome::Skipped],
               failed = counts[FrameOutcome::Failed];

  if (batch.json) {
    nlohmann::json list = nlohmann::json::array(), failures = nlohmann::json::array();
    for (size_t i = 0; i < frames.size(); ++i) {
      nlohmann::json entry = outcomes[i].stats.is_null() ? nlohmann::json{{"output", frames[i].output}} : outcomes[i].stats;
      entry["line"] = jobs[i].line_number;
      entry["status"] = status_name(outcomes[i].status);
      if (outcomes[i].status == FrameOutcome::Failed) {
        entry["error"] = outcomes[i].error;
        failures.push_back(frames[i].output);
      }
      list.push_back(std::move(entry));
    }
    nlohmann::json summary = {{"jobs", batch.jobs_path}, {"frames", list},       {"rendered", rendered},
                              {"skipped", skipped},       {"failed", failed},     {"failed_frames", failures},
                              {"load_seconds", load_seconds}, {"seconds", seconds}};
    kdray::tool::add_tree_memory(summary, copy_seconds);
    kdray::tool::print_json(summary);
  } else if (!batch.quiet) {
    std::printf("%s: %zu frames, %zu rendered, %zu skipped, %zu failed in %.2f s (load %.3f s)\n",
                batch.jobs_path.c_str(), frames.size(), rendered, skipped, failed, seconds, load_seconds);
  }
  if (failed) {
    std::fprintf(stderr, "kdrender: %zu of %zu frames failed:\n", failed, frames.size());
    for (size_t i = 0; i < frames.size(); ++i) {
      if (outcomes[i].status != FrameOutcome::Failed) continue;
      std::fprintf(stderr, "  %s:%d %s: %s\n", batch.jobs_path.c_str(), jobs[i].line_number, frames[i].output.c_str(),
                   outcomes[i].error.c_str());
    }
  }
  return failed ? kdray::tool::kExitFailure : kdray::tool::kExitOk;
}

}  // namespace kdrender
