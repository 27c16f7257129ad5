#include <kdray/atomic_file.h>
#include <kdray/error.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include <fcntl.h>
#include <unistd.h>

namespace kdray {
namespace {

namespace fs = std::filesystem;

struct TemporaryPattern {
  std::string prefix;     // "STEM.tmp-"
  std::string extension;  // ".EXT" or empty
};

TemporaryPattern pattern_for(const fs::path& target) {
  return {target.stem().string() + ".tmp-", target.extension().string()};
}

// The writer's pid in a temporary name "PREFIX<pid>-<8 hex>EXTENSION", or 0 if the name is not one.
pid_t writer_of(const std::string& name, const TemporaryPattern& pattern) {
  if (name.size() <= pattern.prefix.size() + pattern.extension.size() || name.compare(0, pattern.prefix.size(), pattern.prefix) != 0 ||
      name.compare(name.size() - pattern.extension.size(), pattern.extension.size(), pattern.extension) != 0)
    return 0;
  const std::string middle =
      name.substr(pattern.prefix.size(), name.size() - pattern.prefix.size() - pattern.extension.size());
  const size_t dash = middle.find('-');
  if (dash == 0 || dash == std::string::npos || dash > 9 || middle.size() != dash + 9) return 0;
  pid_t pid = 0;
  for (size_t i = 0; i < dash; ++i) {
    if (middle[i] < '0' || middle[i] > '9') return 0;
    pid = pid * 10 + (middle[i] - '0');
  }
  for (size_t i = dash + 1; i < middle.size(); ++i)
    if (!std::isxdigit(static_cast<unsigned char>(middle[i]))) return 0;
  return pid;
}

bool process_is_gone(pid_t pid) { return ::kill(pid, 0) != 0 && errno == ESRCH; }

void fsync_path(const std::string& path, int flags, const std::string& target) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) throw Error(target, std::string("cannot reopen the finished temporary file: ") + std::strerror(errno));
  const bool synced = ::fsync(fd) == 0;
  const int saved = errno;
  ::close(fd);
  if (!synced) throw Error(target, std::string("cannot flush: ") + std::strerror(saved));
}

}  // namespace

size_t remove_dead_writers_temporaries(const std::string& target) {
  const fs::path target_path(target);
  const TemporaryPattern pattern = pattern_for(target_path);
  const fs::path folder = target_path.has_parent_path() ? target_path.parent_path() : fs::path(".");
  std::error_code error;
  size_t removed = 0;
  for (fs::directory_iterator entry(folder, error), end; !error && entry != end; entry.increment(error)) {
    const pid_t pid = writer_of(entry->path().filename().string(), pattern);
    // Another live process (this one included) may still be writing: only the dead are cleared.
    if (pid > 0 && process_is_gone(pid) && fs::remove(entry->path(), error)) ++removed;
  }
  return removed;
}

AtomicFile::AtomicFile(std::string target) : target_(std::move(target)) {
  remove_dead_writers_temporaries(target_);
  const fs::path path(target_);
  const TemporaryPattern pattern = pattern_for(path);
  std::random_device entropy;
  char tag[24];
  std::snprintf(tag, sizeof tag, "%d-%08x", int(::getpid()), unsigned(entropy()));
  temporary_ = (path.parent_path() / (pattern.prefix + tag + pattern.extension)).string();
}

AtomicFile::~AtomicFile() {
  if (!committed_) ::unlink(temporary_.c_str());
}

void AtomicFile::commit() {
  fsync_path(temporary_, O_RDONLY, target_);
  if (::rename(temporary_.c_str(), target_.c_str()) != 0)
    throw Error(target_, std::string("cannot move the finished file into place: ") + std::strerror(errno));
  committed_ = true;
  sync_folder();
}

bool AtomicFile::commit_unless_exists() {
  fsync_path(temporary_, O_RDONLY, target_);
  if (::renameat2(AT_FDCWD, temporary_.c_str(), AT_FDCWD, target_.c_str(), RENAME_NOREPLACE) != 0) {
    if (errno == EEXIST) return discard();
    if (errno != EINVAL && errno != ENOSYS)
      throw Error(target_, std::string("cannot move the finished file into place: ") + std::strerror(errno));
    // A file system without RENAME_NOREPLACE: link() also refuses an existing name.
    if (::link(temporary_.c_str(), target_.c_str()) != 0) {
      if (errno == EEXIST) return discard();
      throw Error(target_, std::string("cannot move the finished file into place: ") + std::strerror(errno));
    }
    ::unlink(temporary_.c_str());
  }
  committed_ = true;
  sync_folder();
  return true;
}

bool AtomicFile::discard() {
  ::unlink(temporary_.c_str());
  return false;
}

// The rename itself survives a power cut only once the folder is flushed too; best effort,
// since the data is complete and in place either way.
void AtomicFile::sync_folder() const {
  const fs::path folder = fs::path(target_).has_parent_path() ? fs::path(target_).parent_path() : fs::path(".");
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

void write_file_atomically(const std::string& path, const void* data, size_t size) {
  AtomicFile file(path);
  const int fd = ::open(file.temporary_path().c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw Error(path, std::string("cannot create: ") + std::strerror(errno));
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t written = ::write(fd, bytes, size);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) {
      const int saved = errno;
      ::close(fd);
      throw Error(path, std::string("cannot write: ") + std::strerror(written < 0 ? saved : ENOSPC));
    }
    bytes += written;
    size -= size_t(written);
  }
  if (::close(fd) != 0) throw Error(path, std::string("cannot write: ") + std::strerror(errno));
  file.commit();
}

}  // namespace kdray
