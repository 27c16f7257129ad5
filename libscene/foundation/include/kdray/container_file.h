// Reading and writing the section container shared by .kdscene and .kdtree
// (formats/container.md). The writer is atomic (temporary file + rename); the reader
// checks magic, version, header and section sizes against the file size, and the payload
// checksum before the caller interprets a single byte.
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

struct SectionData {
  uint32_t id;
  const void* data;
  uint64_t size;
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

// Called once per section, in file order, with its id and size; returns where the
// section's bytes go (at least `size` bytes), or nullptr to skip an unknown section.
// May throw kdray::Error when the size is impossible for that section.
using SectionSink = std::function<void*(uint32_t id, uint64_t size)>;

struct ContainerContents {
  format::FileHeader header;
  std::vector<format::SectionEntry> sections;
};

// Reads a container, streaming each section straight into the memory the sink returns.
// Throws kdray::Error naming `path` for a missing file, wrong magic ("not a <what> file"),
// a newer version, truncation, sizes beyond the file, overlapping sections or a checksum
// mismatch. Data written through the sink must not be trusted unless this returns.
// `kind_name` is used in messages, e.g. "kdscene".
ContainerContents read_container(const std::string& path, const char (&magic)[8],
                                 uint32_t max_version, const char* kind_name,
                                 const SectionSink& sink);

// A container's bytes mapped read-only, checked as read_container checks them (the checksum
// included): section s's bytes are at bytes + s.offset. The mapping lives while any copy of
// `mapping` does, so arrays that view it can share it. The file's pages are the page cache's:
// nothing is copied or zero-filled, which is what makes a load cost about a read of the file.
// A file must not be truncated while mapped (writers replace files by rename, which does not).
struct MappedContainer {
  std::shared_ptr<const void> mapping;
  const char* bytes = nullptr;
  ContainerContents contents;
};
// `check_alongside` (optional) runs on the mapped container while the checksum is computed on
// another thread, so a reader's own pass over the sections costs no extra time: it may read any
// byte inside a section and must not act on one, since nothing is trusted until this returns.
// A checksum mismatch is the error thrown, whatever the check found; else the check's error.
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
