// The readers under test take a path, so each input is written to a file first, in a folder of
// the fuzzer's own (in /dev/shm when present: no disk traffic per execution). The extension
// matters to the importers, which pick a parser by it.
#pragma once

#include <kdray/error.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace kdray::fuzz {

inline const std::string& scratch_folder() {
  static const std::string folder = [] {
    const char* base = ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : (std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp");
    std::string path = std::string(base) + "/kdray-fuzz-" + std::to_string(::getpid());
    ::mkdir(path.c_str(), 0700);
    // Removed at exit; a crashed fuzzer leaves it, which is what one wants when reproducing.
    static std::string to_remove;
    to_remove = path;
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(to_remove, ignored);
    });
    return path;
  }();
  return folder;
}

// Writes the input to scratch_folder()/input<extension> and returns that path.
inline std::string input_file(const uint8_t* data, size_t size, const std::string& extension) {
  const std::string path = scratch_folder() + "/input" + extension;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) std::abort();
  for (size_t done = 0; done < size;) {
    const ssize_t written = ::write(fd, data + done, size - done);
    if (written <= 0) std::abort();
    done += size_t(written);
  }
  ::close(fd);
  return path;
}

// Runs `read`, accepting the one way a reader may reject input: a kdray::Error.
template <typename Read>
void expect_clean(Read&& read) {
  try {
    read();
  } catch (const kdray::Error&) {
  }
}

}  // namespace kdray::fuzz
