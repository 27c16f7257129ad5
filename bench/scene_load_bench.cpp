// bench/scene.sh's load timing: one operation per process, so each run starts as a tool does
// (fresh heap, file in the page cache). "load" is read_scene (validate, checksum, copy into
// the scene arrays, check every index); "read" is a plain read of the same bytes into one
// buffer. Prints the seconds taken.
#include <kdray/scene_file.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace {

bool plain_read(const char* path) {
  const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
  struct stat status {};
  if (fd < 0 || ::fstat(fd, &status) != 0) return false;
  std::unique_ptr<char[]> bytes(new char[size_t(status.st_size)]);
  ssize_t total = 0;
  while (total < status.st_size) {
    const ssize_t got = ::read(fd, bytes.get() + total, size_t(status.st_size - total));
    if (got <= 0) break;
    total += got;
  }
  ::close(fd);
  return total == status.st_size;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 || (std::strcmp(argv[2], "load") != 0 && std::strcmp(argv[2], "read") != 0)) {
    std::fprintf(stderr, "usage: scene_load_bench FILE.kdscene load|read\n");
    return 2;
  }
  const auto start = std::chrono::steady_clock::now();
  if (std::strcmp(argv[2], "load") == 0) {
    const kdray::Scene scene = kdray::read_scene(argv[1]);
    if (scene.indices.empty()) return 1;
  } else if (!plain_read(argv[1])) {
    return 1;
  }
  std::printf("%.6f\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return 0;
}
