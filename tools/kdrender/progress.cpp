#include "progress.h"

#include <cstdio>

#include <unistd.h>

namespace kdrender {

ProgressReport::ProgressReport(bool enabled)
    : enabled_(enabled), terminal_(isatty(STDERR_FILENO) != 0), start_(std::chrono::steady_clock::now()),
      last_line_(start_) {}

void ProgressReport::update(uint32_t done, uint32_t total) {
  if (!enabled_ || total == 0) return;
  auto now = std::chrono::steady_clock::now();
  double elapsed = std::chrono::duration<double>(now - start_).count();
  if (terminal_) {
    const int width = 30;
    int filled = static_cast<int>(double(width) * done / total);
    std::fprintf(stderr, "\rkdrender [%.*s%*s] %u/%u spp  %.1f s", filled, "##############################",
                 width - filled, "", done, total, elapsed);
    drawn_ = true;
  } else if (done == total || std::chrono::duration<double>(now - last_line_).count() >= 5.0) {
    // Plain lines at most every five seconds, so logs stay short.
    std::fprintf(stderr, "kdrender: %u/%u samples per pixel, %.1f s\n", done, total, elapsed);
    last_line_ = now;
  }
  std::fflush(stderr);
}

void ProgressReport::finish() {
  if (drawn_) std::fprintf(stderr, "\n");
  drawn_ = false;
}

}  // namespace kdrender
