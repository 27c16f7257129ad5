// The command-line contract every kdray tool shares (GUIDE section 8):
//   errors on stderr as "<tool>: error: <file>: <what>", exit 0 ok, 1 failure, 2 usage;
//   --json prints machine-readable output on stdout instead of the human summary.
#pragma once

#include <kdray/error.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <exception>
#include <iostream>
#include <new>
#include <string>

namespace kdray::tool {

enum ExitCode : int { kExitOk = 0, kExitFailure = 1, kExitUsage = 2 };

inline void print_error(const char* tool_name, const std::string& message) {
  std::fprintf(stderr, "%s: error: %s\n", tool_name, message.c_str());
}

// Parses the command line with `app` and runs `body`, mapping every way a tool can fail to
// one line on stderr and the documented exit code. `body` returns the exit code.
template <typename Body>
int run(CLI::App& app, int argc, char** argv, Body&& body) {
  const char* tool_name = app.get_name().c_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return kExitOk;
  } catch (const CLI::CallForVersion&) {
    std::cout << app.version() << "\n";
    return kExitOk;
  } catch (const CLI::ParseError& error) {
    print_error(tool_name, std::string(error.what()) + " (see --help)");
    return kExitUsage;
  }
  try {
    return body();
  } catch (const kdray::Error& error) {
    print_error(tool_name, error.what());
  } catch (const std::bad_alloc&) {
    print_error(tool_name, "out of memory");
  } catch (const std::exception& error) {
    print_error(tool_name, error.what());
  }
  return kExitFailure;
}

inline void print_json(const nlohmann::json& document) { std::cout << document.dump(2) << std::endl; }

}  // namespace kdray::tool
