#include <kdray/threads.h>

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <memory>

namespace kdray {

unsigned thread_count(unsigned threads) {
  return threads != 0 ? threads : static_cast<unsigned>(tbb::info::default_concurrency());
}

void run_with_threads(unsigned threads, const std::function<void()>& work) {
  const int count = static_cast<int>(thread_count(threads));
  // Raised for this call only; of several live global_controls oneTBB obeys the smallest.
  std::unique_ptr<tbb::global_control> cap;
  if (count > tbb::info::default_concurrency())
    cap = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, count);
  tbb::task_arena arena(count);
  arena.execute(work);
}

}  // namespace kdray
