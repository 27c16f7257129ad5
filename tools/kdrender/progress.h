// kdrender's progress report on stderr: a redrawn bar on a terminal, plain lines otherwise.
#pragma once

#include <chrono>
#include <cstdint>

namespace kdrender {

class ProgressReport {
 public:
  explicit ProgressReport(bool enabled);
  void update(uint32_t done, uint32_t total);
  void finish();

 private:
  bool enabled_ = false;
  bool terminal_ = false;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_line_;
};

}  // namespace kdrender
