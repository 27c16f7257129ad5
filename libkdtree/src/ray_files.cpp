#include <kdray/atomic_file.h>
#include <kdray/error.h>
#include <kdray/ray_files.h>
#include <kdray/util.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace kdray {
namespace {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "ray and hit files are little-endian like the host");

template <typename Record>
std::vector<Record> read_records(const std::string& path, const char* what) {
  // O_NONBLOCK so a FIFO given by mistake is rejected below instead of waiting for a writer.
  const FileDescriptor file(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK));
  const int fd = file.get();
  if (fd < 0) throw Error(path, std::string("cannot open: ") + std::strerror(errno));
  struct stat status {};
  if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) throw Error(path, "not a regular file");
  const uint64_t size = uint64_t(status.st_size);
  if (size % sizeof(Record) != 0)
    throw Error(path, std::string("not a ") + what + " file: its size is not a multiple of " +
                          std::to_string(sizeof(Record)) + " bytes");
  std::vector<Record> records(size / sizeof(Record));
  char* bytes = reinterpret_cast<char*>(records.data());
  for (uint64_t done = 0; done < size;) {
    const ssize_t got = ::read(fd, bytes + done, size - done);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) throw Error(path, got < 0 ? std::string("cannot read: ") + std::strerror(errno) : "cannot read: shorter than its size");
    done += uint64_t(got);
  }
  return records;
}

}  // namespace

std::vector<RayRecord> read_rays(const std::string& path) { return read_records<RayRecord>(path, "ray"); }
std::vector<HitRecord> read_hits(const std::string& path) { return read_records<HitRecord>(path, "hit"); }

void write_rays(const std::string& path, const std::vector<RayRecord>& rays) {
  write_file_atomically(path, rays.data(), rays.size() * sizeof(RayRecord));
}
void write_hits(const std::string& path, const std::vector<HitRecord>& hits) {
  write_file_atomically(path, hits.data(), hits.size() * sizeof(HitRecord));
}

}  // namespace kdray
