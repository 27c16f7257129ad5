// Runs an importer in a child process (see importers.h): Debian's Assimp can abort (failed
// internal assertions) or crash on malformed input, and that must end in an error message, not
// in the death of kdconvert. The child hands the scene back as a .kdscene in the temp folder,
// which is the scene model's own complete serialisation, checked on the way back in.
#include "importers.h"

#include <kdray/error.h>
#include <kdray/scene_file.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace kdray {
namespace {

void write_fully(int fd, const std::string& text) {
  for (size_t done = 0; done < text.size();) {
    const ssize_t written = ::write(fd, text.data() + done, text.size() - done);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) return;
    done += size_t(written);
  }
}

std::string read_until_closed(int fd) {
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return text;
    text.append(buffer, size_t(got));
  }
}

}  // namespace

Scene import_in_child_process(const std::string& path, Scene (*importer)(const std::string&),
                              const char* importer_name) {
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
    for (int fault : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) std::signal(fault, SIG_DFL);
    // The tool's error is one line: what the importer prints before it dies (an assertion's
    // text) would add lines the parent cannot attribute, so the child's stderr is discarded.
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null >= 0) ::dup2(null, STDERR_FILENO);
    int status = 0;
    try {
      write_scene(handover, importer(path));
    } catch (const std::exception& error) {
      // kdray::Error messages already name the file; anything else is said as it is.
      write_fully(message_pipe[1], dynamic_cast<const Error*>(&error) ? error.what() : path + ": " + error.what());
      status = 1;
    }
    ::_exit(status);  // no atexit handlers or static destructors: they belong to the parent
  }
  ::close(message_pipe[1]);
  const std::string message = read_until_closed(message_pipe[0]);
  ::close(message_pipe[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    struct Remove {
      const std::string& file;
      ~Remove() { std::remove(file.c_str()); }
    } remove_handover{handover};
    return read_scene(handover);
  }
  std::remove(handover.c_str());
  if (WIFEXITED(status) && !message.empty()) throw Error("", message);
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    throw Error(path, std::string(importer_name) + " failed on this file (its process ended with signal " +
                          std::to_string(signal) + ", " + ::strsignal(signal) +
                          (signal == SIGKILL ? ": out of memory?" : "") + "); the file is probably malformed");
  }
  throw Error(path, std::string(importer_name) + " failed on this file (exit status " +
                        std::to_string(WEXITSTATUS(status)) + ")");
}

}  // namespace kdray
