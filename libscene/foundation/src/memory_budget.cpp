#include <kdray/memory_budget.h>

#include <unistd.h>

namespace kdray {
namespace {

std::string readable(uint64_t bytes) {
  if (bytes < 1024) return std::to_string(bytes) + " bytes";
  if (bytes < (uint64_t(1) << 20)) return std::to_string(bytes >> 10) + " KiB";
  return std::to_string(bytes >> 20) + " MiB";
}

}  // namespace

uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page_size > 0 ? uint64_t(pages) * uint64_t(page_size) : 0;
}

uint64_t default_memory_budget() { return physical_memory_bytes() / 4 * 3; }

void check_memory_estimate(const std::string& path, const std::string& stage, uint64_t estimate, uint64_t budget) {
  if (budget == 0 || estimate <= budget) return;
  throw MemoryBudgetError(path, stage + " needs about " + readable(estimate) + ", more than the memory budget of " +
                                    readable(budget));
}

}  // namespace kdray
