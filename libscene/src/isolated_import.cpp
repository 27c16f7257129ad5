// Runs an importer in a child process (see importers.h): Debian's Assimp can abort (failed
// internal assertions) or crash on malformed input, and that must end in an error message, not
// in the death of kdconvert. The child hands the scene back as a .kdscene in the temp folder,
// which is the scene model's own complete serialisation, checked on the way back in.
#include "importers.h"

#include <kdray/error.h>
#include <kdray/memory_budget.h>
#include <kdray/scene_file.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <new>
#include <random>

#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace kdray {
namespace {

// The child's exit status when the importer ran out of its memory budget (1: any other error).
constexpr int kExitOverMemoryBudget = 3;

void write_fully(int fd, const std::string& text) {
  for (size_t done = 0; done < text.size();) {
    const ssize_t written = ::write(fd, text.data() + done, text.size() - done);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) return;
    done += size_t(written);
  }
}

// A malformed file can make an importer loop forever (Assimp's PLY reader on a 25-byte file).
// The CPU time the child may use grows with the file: a few seconds for any small asset, and
// far more per megabyte than an importer takes on valid data.
constexpr uint64_t kImportCpuSecondsBase = 3;
constexpr uint64_t kImportCpuSecondsPerMegabyte = 2;

uint64_t cpu_seconds_for(const std::string& path) {
  std::error_code error;
  const uint64_t size = std::filesystem::file_size(path, error);
  return kImportCpuSecondsBase + (error ? 0 : kImportCpuSecondsPerMegabyte * ((size >> 20) + 1));
}

// The address space the process holds now, so that the child's limit adds the budget to it
// (a sanitizer's shadow mappings are part of it and must not count against the import).
uint64_t address_space_bytes() {
  std::FILE* statm = std::fopen("/proc/self/statm", "r");
  unsigned long long pages = 0;
  if (statm) {
    if (std::fscanf(statm, "%llu", &pages) != 1) pages = 0;
    std::fclose(statm);
  }
  return uint64_t(pages) * uint64_t(::sysconf(_SC_PAGESIZE));
}

void limit(int resource, uint64_t soft, uint64_t hard) {
  const struct rlimit value = {rlim_t(soft), rlim_t(hard)};
  ::setrlimit(resource, &value);
}

// What the child writes until it closes the pipe (it exits), or until `seconds` of wall time have
// passed (then `finished` is false). A child the CPU limit cannot stop because it is blocked,
// not working (a fork of a process whose other threads held a lock, as a sanitizer's allocator
// can be), would otherwise keep the tool waiting for ever.
std::string read_until_closed(int fd, uint64_t seconds, bool& finished) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(seconds);
  std::string text;
  char buffer[4096];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    struct pollfd wait_for {fd, POLLIN, 0};
    const int ready = left > 0 ? ::poll(&wait_for, 1, static_cast<int>(left)) : 0;
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) {
      finished = false;
      return text;
    }
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) {
      finished = true;
      return text;
    }
    text.append(buffer, size_t(got));
  }
}

}  // namespace

Scene import_in_child_process(const std::string& path, Scene (*importer)(const std::string&),
                              const char* importer_name, uint64_t max_memory) {
  const uint64_t cpu_seconds = cpu_seconds_for(path);
  std::random_device entropy;
  const std::string handover = (std::filesystem::temp_directory_path() /
                                ("kdray-import-" + std::to_string(::getpid()) + "-" + std::to_string(entropy()) + ".kdscene"))
                                   .string();
  int message_pipe[2];
  if (::pipe2(message_pipe, O_CLOEXEC) != 0) throw Error(path, std::string("cannot create a pipe: ") + std::strerror(errno));
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(message_pipe[0]);
    ::close(message_pipe[1]);
    throw Error(path, std::string("cannot start the importer process: ") + std::strerror(errno));
  }
  if (child == 0) {
    ::close(message_pipe[0]);
    // The child dies of its own faults: handlers the parent installed (a sanitizer's, a
    // fuzzer's) would otherwise report the parent's failure from inside the child.
    for (int fault : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGXCPU}) std::signal(fault, SIG_DFL);
    // SIGXCPU at the soft limit, SIGKILL a second later if something caught it.
    limit(RLIMIT_CPU, cpu_seconds, cpu_seconds + 1);
    if (max_memory > 0) {
      const uint64_t space = address_space_bytes() + max_memory;
      limit(RLIMIT_AS, space, space);
    }
    // The tool's error is one line: what the importer prints before it dies (an assertion's
    // text) would add lines the parent cannot attribute, so the child's stderr is discarded.
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null >= 0) ::dup2(null, STDERR_FILENO);
    int status = 0;
    try {
      write_scene(handover, importer(path));
    } catch (const std::bad_alloc&) {
      write_fully(message_pipe[1], path + ": importing it with " + importer_name +
                                       " needs more than the memory budget (" + std::to_string(max_memory >> 20) +
                                       " MiB)");
      status = kExitOverMemoryBudget;
    } catch (const std::exception& error) {
      // kdray::Error messages already name the file; anything else is said as it is.
      write_fully(message_pipe[1], dynamic_cast<const Error*>(&error) ? error.what() : path + ": " + error.what());
      status = 1;
    }
    ::_exit(status);  // no atexit handlers or static destructors: they belong to the parent
  }
  ::close(message_pipe[1]);
  // Wall time: three times the CPU allowance, so a machine whose cores are all busy still gives
  // a working importer its CPU time.
  const uint64_t wall_seconds = 3 * cpu_seconds;
  bool finished = true;
  const std::string message = read_until_closed(message_pipe[0], wall_seconds, finished);
  ::close(message_pipe[0]);
  if (!finished) ::kill(child, SIGKILL);
  int status = 0;
  struct rusage usage {};
  while (::wait4(child, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  const uint64_t cpu_used = uint64_t(usage.ru_utime.tv_sec) + uint64_t(usage.ru_stime.tv_sec);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    struct Remove {
      const std::string& file;
      ~Remove() { std::remove(file.c_str()); }
    } remove_handover{handover};
    return read_scene(handover);
  }
  std::remove(handover.c_str());
  if (WIFEXITED(status) && WEXITSTATUS(status) == kExitOverMemoryBudget && !message.empty())
    throw MemoryBudgetError("", message);
  if (WIFEXITED(status) && !message.empty()) throw Error("", message);
  if (!finished)
    throw Error(path, std::string(importer_name) + " did not finish within " + std::to_string(wall_seconds) +
                          " s; its process was stopped (the file is probably malformed)");
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    if (signal == SIGXCPU || (signal == SIGKILL && cpu_used >= cpu_seconds))
      throw Error(path, std::string(importer_name) + " did not finish within " + std::to_string(cpu_seconds) +
                            " s of CPU time (the limit for a file of this size); the file is probably malformed");
    throw Error(path, std::string(importer_name) + " failed on this file (its process ended with signal " +
                          std::to_string(signal) + ", " + ::strsignal(signal) +
                          (signal == SIGKILL ? ": out of memory?" : "") + "); the file is probably malformed");
  }
  throw Error(path, std::string(importer_name) + " failed on this file (exit status " +
                        std::to_string(WEXITSTATUS(status)) + ")");
}

}  // namespace kdray
