// How much memory a stage of the pipeline (import, build, render) may use, and the check that
// refuses a stage whose estimate exceeds it, before it starts, instead of letting the kernel
// kill the process halfway.
#pragma once

#include <kdray/error.h>

#include <cstdint>
#include <string>

namespace kdray {

uint64_t physical_memory_bytes();

// Three quarters of the machine's memory: the rest is left to the system and other processes.
uint64_t default_memory_budget();

// A stage refused (or stopped) because it needs more memory than its budget; the tools name the
// option that sets the budget.
class MemoryBudgetError : public Error {
 public:
  using Error::Error;
};

// Throws MemoryBudgetError naming `path`: "<stage> needs about X MiB, more than the memory budget
// of Y MiB" when `estimate` exceeds `budget` (bytes; 0: no limit).
void check_memory_estimate(const std::string& path, const std::string& stage, uint64_t estimate, uint64_t budget);

}  // namespace kdray
