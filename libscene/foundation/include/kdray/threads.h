// The one way kdray's CPU work takes its thread count (--threads of kdbuild, kdtrace and
// kdrender --device host).
#pragma once

#include <functional>

namespace kdray {

// The number of threads `threads` stands for: itself, or all hardware threads for 0.
unsigned thread_count(unsigned threads);

// Runs `work` in an oneTBB arena of thread_count(threads) threads; its parallel loops use them.
// A count above the hardware's is honoured, as pbrt's and Cycles' thread options are: oneTBB
// would otherwise cap it at the hardware's, warning on stderr.
void run_with_threads(unsigned threads, const std::function<void()>& work);

}  // namespace kdray
