// Progress of a long stage on stderr, as one redrawn bar. Drawn only when stderr is a terminal
// (redrawing needs carriage returns, which do not belong in a log), and only once the stage has
// run for a second, so quick runs stay silent.
#pragma once

#include <kdray/clock.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace kdray::tool {

class ProgressBar {
 public:
  ProgressBar(std::string tool_name, bool enabled)
      : tool_name_(std::move(tool_name)),
        enabled_(enabled && isatty(STDERR_FILENO) != 0),
        start_(kdray::Clock::now()) {}
  ~ProgressBar() { finish(); }

  // `fraction` of the work is done; `detail` follows the bar (e.g. "12/64 spp").
  void update(double fraction, const std::string& detail = "") {
    if (!enabled_) return;
    const double elapsed = kdray::seconds_since(start_);
    if (elapsed < 1.0) return;
    constexpr int kWidth = 40;
    const int filled = std::clamp(static_cast<int>(fraction * kWidth), 0, kWidth);
    std::fprintf(stderr, "\r%s: [%s%s] %3d%% %s %.1f s", tool_name_.c_str(), std::string(filled, '#').c_str(),
                 std::string(kWidth - filled, ' ').c_str(), static_cast<int>(fraction * 100.0), detail.c_str(),
                 elapsed);
    std::fflush(stderr);
    drawn_ = true;
  }

  // Ends the bar's line, so what follows starts on a fresh one.
  void finish() {
    if (drawn_) std::fprintf(stderr, "\n");
    drawn_ = false;
  }

 private:
  std::string tool_name_;
  bool enabled_;
  bool drawn_ = false;
  kdray::Clock::time_point start_;
};

}  // namespace kdray::tool
