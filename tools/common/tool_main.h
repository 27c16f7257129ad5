// The command-line contract every kdray tool shares, kept here and nowhere else:
//   - exit status: 0 ok; 1 failure (a missing, unreadable or damaged input file included: the
//     command line was fine, the data was not); 2 usage (the command line itself is malformed or
//     inconsistent); 3 only from kdcompare: the images were compared and a threshold was missed;
//   - errors on stderr as one line "<tool>: error: <file>: <what>", warnings as "<tool>: warning: ";
//   - --help (grouped, with defaults), --version, --json (machine-readable output on stdout,
//     keys from the vocabulary in README.md) and --quiet (nothing but errors and warnings);
//   - progress on stderr only when stderr is a terminal (progress.h).
// Libraries throw kdray::Error describing the data; only the tools speak of flags.
#pragma once

#include <kdray/error.h>
#include <kdray/memory_budget.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <exception>
#include <iostream>
#include <new>
#include <string>

namespace kdray::tool {

enum ExitCode : int { kExitOk = 0, kExitFailure = 1, kExitUsage = 2, kExitAboveThreshold = 3 };

constexpr const char* kExitStatusHelp =
    "Exit status: 0 ok; 1 failure (including a missing, unreadable or damaged input file); "
    "2 bad command line.";

// A command line that parses but asks for something inconsistent (exit 2). Tools throw it from
// their body; CLI::ValidationError thrown there is treated the same way.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline void print_error(const std::string& tool_name, const std::string& message) {
  std::fprintf(stderr, "%s: error: %s\n", tool_name.c_str(), message.c_str());
}

inline void print_warning(const std::string& tool_name, const std::string& message) {
  std::fprintf(stderr, "%s: warning: %s\n", tool_name.c_str(), message.c_str());
}

// The flags every tool has besides --help and --version.
struct OutputFlags {
  bool json = false;
  bool quiet = false;
};

// Names the tool, adds --version, --json and --quiet, and puts the exit codes under --help
// (`exit_help` replaces the common line for a tool with codes of its own).
inline void add_contract(CLI::App& app, const std::string& tool_name, OutputFlags& flags, const std::string& json_help,
                         const std::string& exit_help = kExitStatusHelp) {
  app.name(tool_name);
  app.set_version_flag("--version", tool_name + " " + KDRAY_VERSION);
  app.add_flag("--json", flags.json, json_help)->group("Output");
  app.add_flag("-q,--quiet", flags.quiet, "Print nothing but errors and warnings (the exit status tells the result)")
      ->group("Output");
  app.footer(exit_help);
}

// Parses the command line with `app` and runs `body`, mapping every way a tool can fail to
// one line on stderr and the documented exit code. `body` returns the exit code.
template <typename Body>
int run(CLI::App& app, int argc, char** argv, Body&& body) {
  const std::string tool_name = app.get_name();
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
  } catch (const UsageError& error) {
    print_error(tool_name, std::string(error.what()) + " (see --help)");
    return kExitUsage;
  } catch (const CLI::ValidationError& error) {
    print_error(tool_name, std::string(error.what()) + " (see --help)");
    return kExitUsage;
  } catch (const kdray::MemoryBudgetError& error) {
    print_error(tool_name, std::string(error.what()) + " (--max-memory)");
  } catch (const kdray::Error& error) {
    print_error(tool_name, error.what());
  } catch (const std::bad_alloc&) {
    print_error(tool_name, "out of memory");
  } catch (const std::exception& error) {
    print_error(tool_name, error.what());
  }
  return kExitFailure;
}

// --max-memory SIZE (bytes, or with a unit: 512M, 4G; 0: no limit), shared by the tools whose
// stages check their memory estimate against it (kdray/memory_budget.h).
inline void add_max_memory_option(CLI::App& app, uint64_t& bytes) {
  bytes = kdray::default_memory_budget();
  app.add_option("--max-memory", bytes, "Refuse a stage whose memory estimate exceeds SIZE (0: no limit)")
      ->transform(CLI::AsSizeValue(false))
      ->default_str(std::to_string(bytes >> 20) + "M (3/4 of this machine's memory)")
      ->group("Run");
}

inline void print_json(const nlohmann::json& document) { std::cout << document.dump(2) << std::endl; }

}  // namespace kdray::tool
