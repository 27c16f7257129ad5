// Writing a file so that a reader, or a writer killed at any moment, leaves either the previous
// complete file or the new complete one under the target's name, never a torn one.
//
// The data goes to a temporary sibling named "STEM.tmp-PID-RANDOM.EXT" (the extension is kept so
// image libraries still pick the format by name), which commit() flushes to disk and renames over
// the target. A writer killed before commit() leaves its temporary behind; the next AtomicFile
// for the same target removes the temporaries whose writer process no longer exists, so they do
// not pile up in an output folder or a cache.
#pragma once

#include <cstddef>
#include <string>

namespace kdray {

class AtomicFile {
 public:
  // Chooses the temporary name and removes dead writers' temporaries of `target`.
  explicit AtomicFile(std::string target);
  // Removes the temporary unless commit() succeeded (a write that failed or threw).
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& target() const { return target_; }
  // Where the caller writes the data (it does not exist yet).
  const std::string& temporary_path() const { return temporary_; }
  // Flushes the finished temporary to disk and renames it over the target. Throws kdray::Error
  // naming the target.
  void commit();
  // Like commit(), but an existing target is left in place and the temporary removed (false): of
  // several writers of the same content, the first wins (a tree cache entry, for one).
  bool commit_unless_exists();

 private:
  void sync_folder() const;
  bool discard();  // removes the temporary; false

  std::string target_, temporary_;
  bool committed_ = false;
};

// Writes `size` bytes as the whole content of `path`, atomically. Throws kdray::Error.
void write_file_atomically(const std::string& path, const void* data, size_t size);

// Removes the temporaries of `target` left by writers whose process is gone; returns how many.
// AtomicFile does this itself; exposed for tests.
size_t remove_dead_writers_temporaries(const std::string& target);

}  // namespace kdray
