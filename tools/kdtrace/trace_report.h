// What kdtrace prints: the JSON summary of --json, or the text lines.
#pragma once

#include "trace_options.h"
#include "trace_run.h"

#include <nlohmann/json.hpp>

#include <cstddef>

namespace kdtrace {

// `work` is the counting pass's (count_work), for the per-ray figures.
nlohmann::json trace_json(const Options& o, bool host, size_t ray_count, const TraceRun& run,
                          const kdray::TraversalWork& work);
void print_trace(bool host, size_t ray_count, const TraceRun& run);

}  // namespace kdtrace
