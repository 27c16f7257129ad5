// The one way tests run a built tool: a child process with a time limit, stdout and stderr
// captured separately.
#pragma once

#include <string>
#include <vector>

namespace kdray::test {

struct ToolRun {
  int exit_code = -1;      // valid when exited
  bool exited = false;     // false: killed by a signal (a crash) or by the time limit
  bool timed_out = false;
  int signal = 0;
  std::string out, err;
};

// Runs `argv` (argv[0] is the program path) with stdout/stderr captured, killing it after
// `timeout_seconds`.
ToolRun run_process(const std::vector<std::string>& argv, double timeout_seconds = 600);

// Runs `command` through /bin/sh (for redirections and environment settings); quote paths
// with shell_quoted().
ToolRun run_command(const std::string& command, double timeout_seconds = 600);

std::string shell_quoted(const std::string& text);

}  // namespace kdray::test
