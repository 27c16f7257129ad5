// Running a built tool as a child process with a time limit, capturing its output.
#pragma once

#include <string>
#include <vector>

namespace kdray::test {

struct ProcessResult {
  int exit_code = -1;      // valid when exited
  bool exited = false;     // false: killed by a signal (a crash) or by the time limit
  bool timed_out = false;
  int signal = 0;
  std::string out, err;
};

// Runs `argv` (argv[0] is the program path) with stdout/stderr captured, killing it after
// `timeout_seconds`.
ProcessResult run_process(const std::vector<std::string>& argv, double timeout_seconds = 60);

}  // namespace kdray::test
