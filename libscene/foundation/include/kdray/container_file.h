// Reading and writing the section container shared by .kdscene and .kdtree
// (formats/container.md). The writer is atomic (temporary file + rename); the reader maps the
// file and checks magic, version, header and section sizes against the file size, and the
// payload checksum before the caller uses a single byte.
#pragma once

#include <kdray/util.h>

#include <kdray/format.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace kdray {

// A section's `size` bytes: at `data`, or, where `produce` is set instead, made as the file is
// written: produce(begin, end, out) writes the section's bytes [begin, end) to out, a piece of at
// most 1 MiB at a time. A large section made from other data is then never held whole in memory
// beside the file it goes to.
struct SectionData {
  uint32_t id;
  const void* data;
  uint64_t size;
  std::function<void(uint64_t begin, uint64_t end, char* out)> produce = {};
};

struct ContainerHeaderInfo {
  const char* magic;          // 8 bytes
  uint32_t version;
  uint64_t flags;
  uint64_t content_hash;
};

// Writes header, section table and sections to `path` through a temporary file in the
// same directory that is flushed and renamed into place. Throws kdray::Error.
void write_container(const std::string& path, const ContainerHeaderInfo& header,
                     const std::vector<SectionData>& sections);

// The header and section table of a container, checked against the file size.
struct ContainerContents {
  format::FileHeader header;
  std::vector<format::SectionEntry> sections;
};

// A container's bytes mapped read-only and checked (magic, version, sizes, the checksum):
// section s's bytes are at bytes + s.offset. The mapping lives while any copy of `mapping`
// does, so arrays that view it can share it. The file's pages are the page cache's: nothing is
// copied or zero-filled, which is what makes a load cost about a read of the file. A file must
// not be truncated while mapped (writers replace files by rename, which does not).
struct MappedContainer {
  std::shared_ptr<const void> mapping;
  const char* bytes = nullptr;
  ContainerContents contents;
};
// `check_alongside` (optional) runs on the mapped container while the checksum is computed on
// another thread, so a reader's own pass over the sections costs no extra time: it may read any
// byte inside a section and must not act on one, since nothing is trusted until this returns.
// A checksum mismatch is the error thrown, whatever the check found; else check_alongside's error.
MappedContainer map_container(const std::string& path, const char (&magic)[8], uint32_t max_version,
                              const char* kind_name,
                              const std::function<void(const MappedContainer&)>& check_alongside = {});

// Reads only the header and section table (validated against the file size, no checksum):
// cheap identification for kdinfo and for stale-tree checks before a full load.
ContainerContents peek_container(const std::string& path, const char (&magic)[8],
                                 uint32_t max_version, const char* kind_name);

// 8-byte magic of the file at `path`, or an empty string if it cannot be read.
std::string file_magic(const std::string& path);

}  // namespace kdray
