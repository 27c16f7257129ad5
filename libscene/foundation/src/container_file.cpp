#include <kdray/atomic_file.h>
#include <kdray/container_file.h>
#include <kdray/error.h>
#include <kdray/util.h>

// The dispatching XXH3 (SSE2, AVX2 or AVX-512, chosen at run time) under the usual names: the
// checksum of a large file is what a load waits on, and the plain build is SSE2 only.
#include <xxh_x86dispatch.h>

#include <tbb/parallel_invoke.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <deque>
#include <exception>
#include <memory>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/uio.h>
#include <sys/stat.h>
#include <unistd.h>

namespace kdray {
namespace {

uint64_t align_up(uint64_t value, uint64_t alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

// Writes the pieces in order, however many calls that takes.
void write_all(int fd, std::vector<iovec>& pieces, const std::string& path) {
  size_t first = 0;
  while (first < pieces.size()) {
    const int count = static_cast<int>(std::min<size_t>(pieces.size() - first, IOV_MAX));
    ssize_t written = ::writev(fd, pieces.data() + first, count);
    if (written < 0) {
      if (errno == EINTR) continue;
      throw Error(path, std::string("cannot write: ") + std::strerror(errno));
    }
    for (; first < pieces.size() && static_cast<size_t>(written) >= pieces[first].iov_len; ++first)
      written -= static_cast<ssize_t>(pieces[first].iov_len);
    if (first < pieces.size()) {
      pieces[first].iov_base = static_cast<char*>(pieces[first].iov_base) + written;
      pieces[first].iov_len -= static_cast<size_t>(written);
    }
  }
}

// Reads exactly `size` bytes; false on a short read (the file is shorter than it claims).
bool read_all(int fd, void* data, uint64_t size, const std::string& path) {
  char* bytes = static_cast<char*>(data);
  while (size > 0) {
    ssize_t got = ::read(fd, bytes, std::min<uint64_t>(size, 1u << 30));
    if (got < 0) {
      if (errno == EINTR) continue;
      throw Error(path, std::string("cannot read: ") + std::strerror(errno));
    }
    if (got == 0) return false;
    bytes += got;
    size -= static_cast<uint64_t>(got);
  }
  return true;
}

struct OpenedContainer {
  std::unique_ptr<FileDescriptor> file;
  ContainerContents contents;
};

OpenedContainer open_and_validate(const std::string& path, const char (&magic)[8],
                                  uint32_t max_version, const char* kind_name) {
  // O_NONBLOCK: opening a FIFO (or a device) must not wait for a writer; such files are then
  // rejected as not regular. It has no effect on reading a regular file.
  int raw_fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (raw_fd < 0) throw Error(path, std::string("cannot open: ") + std::strerror(errno));
  OpenedContainer opened{std::make_unique<FileDescriptor>(raw_fd), {}};
  struct stat status {};
  if (::fstat(raw_fd, &status) != 0 || !S_ISREG(status.st_mode))
    throw Error(path, "not a regular file");
  const uint64_t file_size = static_cast<uint64_t>(status.st_size);

  format::FileHeader& header = opened.contents.header;
  if (file_size < 8) throw Error(path, std::string("not a ") + kind_name + " file (too short for the magic number)");
  if (!read_all(raw_fd, &header, std::min<uint64_t>(sizeof header, file_size), path))
    throw Error(path, "cannot read the header");
  if (std::memcmp(header.magic, magic, 8) != 0)
    throw Error(path, std::string("not a ") + kind_name + " file (wrong magic number)");
  if (file_size < sizeof header)
    throw Error(path, "truncated: the file ends inside the header (" + std::to_string(file_size) + " bytes)");
  if (header.version == 0 || header.version > max_version)
    throw Error(path, std::string(kind_name) + " format version " + std::to_string(header.version) +
                          " is not supported (this build reads versions up to " + std::to_string(max_version) + ")");
  if (header.header_size != sizeof header)
    throw Error(path, "bad header size " + std::to_string(header.header_size));
  if (header.payload_size != file_size - sizeof header) {
    if (header.payload_size > file_size - sizeof header)
      throw Error(path, "truncated: the header announces " + std::to_string(header.payload_size + sizeof header) +
                            " bytes but the file has " + std::to_string(file_size));
    throw Error(path, "trailing bytes: the header announces " + std::to_string(header.payload_size + sizeof header) +
                          " bytes but the file has " + std::to_string(file_size));
  }
  if (header.section_count > format::kMaxSections)
    throw Error(path, "implausible section count " + std::to_string(header.section_count));
  const uint64_t table_bytes = uint64_t(header.section_count) * sizeof(format::SectionEntry);
  if (table_bytes > header.payload_size) throw Error(path, "truncated: the section table does not fit in the file");

  auto& sections = opened.contents.sections;
  sections.resize(header.section_count);
  if (!read_all(raw_fd, sections.data(), table_bytes, path)) throw Error(path, "truncated section table");
  uint64_t expected_offset = align_up(sizeof header + table_bytes, format::kSectionAlignment);
  for (const auto& section : sections) {
    // Sections are laid out in table order at aligned offsets: anything else is damage.
    if (section.offset != expected_offset || section.offset > file_size || section.size > file_size - section.offset)
      throw Error(path, "section " + std::to_string(section.id) + " (offset " + std::to_string(section.offset) +
                            ", " + std::to_string(section.size) + " bytes) lies outside the file or overlaps another");
    expected_offset = align_up(section.offset + section.size, format::kSectionAlignment);
  }
  return opened;
}

}  // namespace

void write_container(const std::string& path, const ContainerHeaderInfo& info,
                     const std::vector<SectionData>& sections) {
  format::FileHeader header{};
  std::memcpy(header.magic, info.magic, 8);
  header.version = info.version;
  header.header_size = sizeof header;
  header.flags = info.flags;
  header.content_hash = info.content_hash;
  header.section_count = static_cast<uint32_t>(sections.size());

  std::vector<format::SectionEntry> table(sections.size());
  uint64_t offset = align_up(sizeof header + table.size() * sizeof(format::SectionEntry), format::kSectionAlignment);
  for (size_t i = 0; i < sections.size(); ++i) {
    table[i] = {sections[i].id, 0, offset, sections[i].size};
    offset = align_up(offset + sections[i].size, format::kSectionAlignment);
  }
  const uint64_t file_size = sections.empty() ? sizeof header + 0 : table.back().offset + table.back().size;
  header.payload_size = file_size - sizeof header;

  // The checksum covers everything after the header, padding included, in file order. It is
  // computed as the payload is written, each piece while it is still in cache, and the header
  // that records it is written last, over a placeholder. Pieces are 1 MiB. Whole 2 MiB pieces
  // at 2 MiB offsets make the page cache hold the file in 2 MiB folios, which a reader that maps
  // it gets as huge pages; but allocating those folios cost a large tree's build more than
  // writing its bytes (bench/LOG.md, "Tree build, sixth pass"), and a file read back after it
  // was reclaimed comes in small folios anyway. Readers that trace many rays copy the tree onto
  // huge pages of their own instead (copy_tree_for_rays).
  static const char kZeros[format::kSectionAlignment] = {};
  AtomicFile output(path);
  FileDescriptor file(::open(output.temporary_path().c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666));
  if (file.get() < 0) throw Error(path, std::string("cannot create: ") + std::strerror(errno));
  std::unique_ptr<XXH3_state_t, decltype(&XXH3_freeState)> state(XXH3_createState(), &XXH3_freeState);
  XXH3_64bits_reset(state.get());
  constexpr uint64_t kPiece = uint64_t{1} << 20;
  std::vector<iovec> piece;
  uint64_t position = 0;
  auto put = [&](const void* data, uint64_t size, bool hashed) {
    const char* bytes = static_cast<const char*>(data);
    while (size > 0) {
      const uint64_t part = std::min(size, kPiece - position % kPiece);
      if (hashed) XXH3_64bits_update(state.get(), bytes, part);
      piece.push_back({const_cast<char*>(bytes), part});
      bytes += part;
      size -= part;
      position += part;
      if (position % kPiece == 0) {
        write_all(file.get(), piece, path);
        piece.clear();
      }
    }
  };
  // A produced section's bytes are made a piece's part at a time into one of two buffers of
  // its own, at their offset in the piece: the next part is made while this one is hashed and
  // written (a write into pages the page cache has not held takes as long as making them). A
  // buffer is made into again two parts later, when the piece that viewed it has been written;
  // a section's last part may share its piece with what follows, so its buffers are kept.
  std::deque<std::vector<char>> made_buffers;
  auto put_made = [&](const SectionData& section) {
    std::vector<char>* made[2] = {&made_buffers.emplace_back(kPiece), &made_buffers.emplace_back(kPiece)};
    auto part_at = [&](uint64_t begin, uint64_t at) { return std::min(section.size - begin, kPiece - at % kPiece); };
    int buffer = 0;
    uint64_t begin = 0;
    if (section.size > 0) section.produce(0, part_at(0, position), made[0]->data() + position % kPiece);
    while (begin < section.size) {
      const uint64_t part = part_at(begin, position);
      char* out = made[buffer]->data() + position % kPiece;
      const uint64_t next = begin + part, next_position = position + part;
      tbb::task_group making;
      if (next < section.size)
        making.run([&, next, next_position, buffer] {
          section.produce(next, next + part_at(next, next_position),
                          made[1 - buffer]->data() + next_position % kPiece);
        });
      try {
        put(out, part, true);
      } catch (...) {
        making.wait();
        throw;
      }
      making.wait();
      begin = next;
      buffer = 1 - buffer;
    }
  };
  put(&header, sizeof header, false);
  put(table.data(), table.size() * sizeof(format::SectionEntry), true);
  for (size_t i = 0; i < sections.size(); ++i) {
    put(kZeros, table[i].offset - position, true);
    if (sections[i].produce)
      put_made(sections[i]);
    else
      put(sections[i].data, sections[i].size, true);
  }
  write_all(file.get(), piece, path);
  header.payload_checksum = XXH3_64bits_digest(state.get());
  if (::pwrite(file.get(), &header, sizeof header, 0) != static_cast<ssize_t>(sizeof header))
    throw Error(path, std::string("cannot write: ") + std::strerror(errno));
  if (::close(file.release()) != 0) throw Error(path, std::string("cannot close: ") + std::strerror(errno));
  output.commit();
}

ContainerContents peek_container(const std::string& path, const char (&magic)[8], uint32_t max_version,
                                 const char* kind_name) {
  return open_and_validate(path, magic, max_version, kind_name).contents;
}

MappedContainer map_container(const std::string& path, const char (&magic)[8], uint32_t max_version,
                              const char* kind_name, const std::function<void(const MappedContainer&)>& check_alongside) {
  OpenedContainer opened = open_and_validate(path, magic, max_version, kind_name);
  const format::FileHeader& header = opened.contents.header;
  const uint64_t file_size = sizeof header + header.payload_size;
  // MAP_POPULATE: the checksum reads every page next, so they are mapped in one call rather
  // than one fault per page.
  void* address = ::mmap(nullptr, file_size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, opened.file->get(), 0);
  if (address == MAP_FAILED) throw Error(path, std::string("cannot map: ") + std::strerror(errno));
  MappedContainer file;
  file.mapping = std::shared_ptr<const void>(address, [file_size](const void* start) {
    ::munmap(const_cast<void*>(start), file_size);
  });
  file.bytes = static_cast<const char*>(address);
  file.contents = std::move(opened.contents);
  // The table was read before the mapping: the same bytes, or the file changed in between.
  const auto& sections = file.contents.sections;
  if (!sections.empty() &&
      std::memcmp(file.bytes + sizeof header, sections.data(), sections.size() * sizeof(format::SectionEntry)) != 0)
    throw Error(path, "the file changed while it was read");
  bool intact = false;
  std::exception_ptr check_failure;
  tbb::parallel_invoke(
      [&] {
        // The streaming form: the one-shot XXH3_64bits of the library's dispatching build
        // (0.8.1) returns from its AVX-512 code without clearing the vector registers' upper
        // halves, and the thread's SSE code runs slower afterwards (a build on the reader's
        // worker thread took 20% longer).
        std::unique_ptr<XXH3_state_t, decltype(&XXH3_freeState)> state(XXH3_createState(), &XXH3_freeState);
        XXH3_64bits_reset(state.get());
        XXH3_64bits_update(state.get(), file.bytes + sizeof header, file_size - sizeof header);
        intact = XXH3_64bits_digest(state.get()) == header.payload_checksum;
      },
      [&] {
        if (!check_alongside) return;
        try {
          check_alongside(file);
        } catch (...) {
          check_failure = std::current_exception();
        }
      });
  if (!intact) throw Error(path, "checksum mismatch: the file is damaged");
  if (check_failure) std::rethrow_exception(check_failure);
  return file;
}

std::string file_magic(const std::string& path) {
  FileDescriptor file(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK));
  struct stat status {};
  char magic[8];
  if (file.get() < 0 || ::fstat(file.get(), &status) != 0 || !S_ISREG(status.st_mode) ||
      !read_all(file.get(), magic, 8, path))
    return {};
  return std::string(magic, 8);
}

}  // namespace kdray
