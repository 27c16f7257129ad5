// Running a built tool through the shell from tests: exit code and captured stdout (append
// " 2>&1" to the command to capture stderr too).
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace kdray::test {

struct ToolRun {
  int exit_code = -1;  // -1 when the process did not exit normally (signal, sanitizer abort)
  std::string output;  // stdout; stderr goes to the test log
};

// `command` is passed to /bin/sh; quote paths with shell_quoted().
inline ToolRun run_command(const std::string& command) {
  ToolRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  std::array<char, 4096> buffer;
  size_t got;
  while ((got = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.output.append(buffer.data(), got);
  const int status = pclose(pipe);
  if (status != -1 && WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  return run;
}

inline std::string shell_quoted(const std::string& text) {
  std::string result = "'";
  for (char c : text) result += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return result + "'";
}

}  // namespace kdray::test
