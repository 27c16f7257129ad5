// The one clock kdray times its stages with: monotonic (steady_clock, so a change of the wall
// clock does not show up as a stage's time), read as seconds in a double.
#pragma once

#include <chrono>

namespace kdray {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace kdray
