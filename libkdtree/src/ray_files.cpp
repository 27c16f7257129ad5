#include <kdray/error.h>
#include <kdray/ray_files.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include <unistd.h>

namespace kdray {
namespace {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "ray and hit files are little-endian like the host");

template <typename Record>
std::vector<Record> read_records(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw Error(path, std::string("cannot open: ") + std::strerror(errno));
  const std::streamoff size = in.tellg();
  if (size < 0 || size % static_cast<std::streamoff>(sizeof(Record)) != 0)
    throw Error(path, std::string("not a ") + what + " file: its size is not a multiple of " +
                          std::to_string(sizeof(Record)) + " bytes");
  std::vector<Record> records(static_cast<size_t>(size) / sizeof(Record));
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(records.data()), size)) throw Error(path, "cannot read");
  return records;
}

void write_atomically(const std::string& path, const void* data, size_t size) {
  std::string temporary = path + ".tmp-XXXXXX";
  const int fd = ::mkstemp(temporary.data());
  if (fd < 0) throw Error(path, std::string("cannot create: ") + std::strerror(errno));
  const char* bytes = static_cast<const char*>(data);
  size_t left = size;
  bool ok = true;
  while (ok && left > 0) {
    const ssize_t written = ::write(fd, bytes, left);
    if (written < 0 && errno == EINTR) continue;
    ok = written > 0;
    if (ok) {
      bytes += written;
      left -= static_cast<size_t>(written);
    }
  }
  const int saved_errno = errno;
  ok = ok && ::fsync(fd) == 0;
  ::close(fd);
  if (!ok || std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int error = ok ? errno : saved_errno;
    ::unlink(temporary.c_str());
    throw Error(path, std::string("cannot write: ") + std::strerror(error));
  }
}

}  // namespace

std::vector<RayRecord> read_rays(const std::string& path) { return read_records<RayRecord>(path, "ray"); }
std::vector<HitRecord> read_hits(const std::string& path) { return read_records<HitRecord>(path, "hit"); }

void write_rays(const std::string& path, const std::vector<RayRecord>& rays) {
  write_atomically(path, rays.data(), rays.size() * sizeof(RayRecord));
}
void write_hits(const std::string& path, const std::vector<HitRecord>& hits) {
  write_atomically(path, hits.data(), hits.size() * sizeof(HitRecord));
}

}  // namespace kdray
