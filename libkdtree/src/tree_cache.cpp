#include <kdray/tree_cache.h>

#include <kdray/atomic_file.h>
#include <kdray/container_file.h>
#include <kdray/error.h>
#include <kdray/scene_file.h>
#include <kdray/util.h>

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <linux/fs.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace kdray {
namespace {

namespace fs = std::filesystem;

constexpr const char* kTreeExtension = ".kdtree";
constexpr const char* kScenesExtension = ".scenes";

// Copies `source` into the new file `destination`: a reflink (FICLONE) where the file system
// shares blocks between files, else the kernel copies the bytes. Never a hard link. False when
// the source does not exist (a concurrent eviction removed it).
bool clone_or_copy(const std::string& source, const std::string& destination) {
  FileDescriptor in(::open(source.c_str(), O_RDONLY | O_CLOEXEC));
  if (in.get() < 0) {
    if (errno == ENOENT) return false;
    throw Error(source, std::string("cannot open: ") + std::strerror(errno));
  }
  FileDescriptor out(::open(destination.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666));
  if (out.get() < 0) throw Error(destination, std::string("cannot create: ") + std::strerror(errno));
  if (::ioctl(out.get(), FICLONE, in.get()) == 0) return true;
  struct stat status {};
  if (::fstat(in.get(), &status) != 0) throw Error(source, std::string("cannot read: ") + std::strerror(errno));
  for (off_t left = status.st_size; left > 0;) {
    const ssize_t copied = ::copy_file_range(in.get(), nullptr, out.get(), nullptr, size_t(left), 0);
    if (copied < 0 && errno == EINTR) continue;
    if (copied <= 0) {
      if (copied == 0) throw Error(source, "cannot copy: the file shrank while being copied");
      throw Error(destination, std::string("cannot copy: ") + std::strerror(errno));
    }
    left -= copied;
  }
  return true;
}

// The key of a file name "KEY.kdtree" (16 lowercase hex digits), or nothing.
std::optional<uint64_t> key_of(const std::string& name) {
  const std::string extension = kTreeExtension;
  if (name.size() != 16 + extension.size() || name.compare(16, std::string::npos, extension) != 0) return std::nullopt;
  return parse_hash_hex(name.substr(0, 16));
}

std::vector<std::string> read_lines(const std::string& path) {
  std::vector<std::string> lines;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

std::string absolute(const std::string& path) {
  std::error_code error;
  const fs::path full = fs::absolute(path, error);
  return error ? path : full.lexically_normal().string();
}

bool older(const std::timespec& a, const std::timespec& b) {
  return a.tv_sec != b.tv_sec ? a.tv_sec < b.tv_sec : a.tv_nsec < b.tv_nsec;
}

// The tree of an entry read from `path`, checked to be the tree of `key`. Throws kdray::Error.
KdTree read_entry(const std::string& path, uint64_t key) {
  KdTree tree = read_tree(path);
  if (tree.key != key)
    throw Error(path, "holds the tree of key " + hash_hex(tree.key) + ", not " + hash_hex(key));
  return tree;
}

}  // namespace

TreeCache::TreeCache(std::string folder, CacheWarning warn) : folder_(std::move(folder)), warn_(std::move(warn)) {
  std::error_code error;
  fs::create_directories(folder_, error);
  if (error || !fs::is_directory(folder_))
    throw Error(folder_, "cannot use as a tree cache: " + (error ? error.message() : std::string("not a folder")));
}

std::string TreeCache::tree_path(uint64_t key) const { return (fs::path(folder_) / (hash_hex(key) + kTreeExtension)).string(); }

std::string TreeCache::scenes_path(uint64_t key) const {
  return (fs::path(folder_) / (hash_hex(key) + kScenesExtension)).string();
}

std::optional<KdTree> TreeCache::load(uint64_t key, const std::string& scene_path) {
  const std::string path = tree_path(key);
  if (!fs::exists(path)) return std::nullopt;
  try {
    KdTree tree = read_entry(path, key);
    mark_used(key, scene_path);
    return tree;
  } catch (const Error& error) {
    if (fs::exists(path)) remove_damaged(key, error.what());
    return std::nullopt;
  }
}

std::optional<KdTree> TreeCache::copy_out(uint64_t key, const std::string& output, const std::string& scene_path) {
  const std::string path = tree_path(key);
  AtomicFile copy(output);
  if (!clone_or_copy(path, copy.temporary_path())) return std::nullopt;
  // The copy has the entry's bytes: verifying it verifies the entry, in one read.
  KdTree tree;
  try {
    tree = read_entry(copy.temporary_path(), key);
  } catch (const Error& error) {
    remove_damaged(key, error.what());
    return std::nullopt;
  }
  copy.commit();
  mark_used(key, scene_path);
  return tree;
}

KdTree TreeCache::build(uint64_t key, const Scene& scene, const std::string& scene_path,
                        const BuildSettings& settings, const BuildControl& control) {
  AtomicFile entry(tree_path(key));
  const TreeSummary built = build_tree_file(scene, entry.temporary_path(), settings, control);
  if (built.key != key)
    throw Error(scene_path, "the geometry hash the scene records (" + hash_hex(scene.geometry_hash) +
                                ") is not the hash of its triangles (" + hash_hex(built.geometry_hash) + ")");
  // Mapped before the commit: a concurrent builder's entry, should it win, has the same bytes,
  // and the mapping outlives the temporary's rename or removal.
  KdTree tree = read_tree(entry.temporary_path());
  entry.commit_unless_exists();
  mark_used(key, scene_path);
  return tree;
}

void TreeCache::mark_used(uint64_t key, const std::string& scene_path) {
  const std::string path = tree_path(key);
  const std::timespec times[2] = {{0, UTIME_OMIT}, {0, UTIME_NOW}};
  ::utimensat(AT_FDCWD, path.c_str(), times, 0);  // an entry evicted meanwhile has no last use to keep
  // Two processes adding different scenes at once may keep only one of them: the list is a
  // record for people (kdinfo), the key alone decides hits.
  std::vector<std::string> scenes = read_lines(scenes_path(key));
  const std::string scene = absolute(scene_path);
  if (std::find(scenes.begin(), scenes.end(), scene) != scenes.end()) return;
  std::string text;
  for (const std::string& line : scenes) text += line + "\n";
  text += scene + "\n";
  write_file_atomically(scenes_path(key), text.data(), text.size());
}

void TreeCache::remove_damaged(uint64_t key, const std::string& problem) {
  if (warn_) warn_(tree_path(key) + ": damaged cache entry removed, the tree is built again (" + problem + ")");
  ::unlink(tree_path(key).c_str());
  ::unlink(scenes_path(key).c_str());
}

std::vector<CacheEntry> TreeCache::entries() const {
  std::vector<CacheEntry> list;
  std::error_code error;
  for (fs::directory_iterator it(folder_, error), end; !error && it != end; it.increment(error)) {
    const std::optional<uint64_t> key = key_of(it->path().filename().string());
    struct stat status {};
    if (!key || ::stat(it->path().c_str(), &status) != 0 || !S_ISREG(status.st_mode)) continue;
    CacheEntry entry;
    entry.key = *key;
    entry.tree_path = it->path().string();
    entry.last_use = status.st_mtim;
    entry.bytes = uint64_t(status.st_size);
    const std::string scenes = scenes_path(*key);
    if (::stat(scenes.c_str(), &status) == 0) entry.bytes += uint64_t(status.st_size);
    entry.scenes = read_lines(scenes);
    list.push_back(std::move(entry));
  }
  std::sort(list.begin(), list.end(), [](const CacheEntry& a, const CacheEntry& b) {
    return older(b.last_use, a.last_use) || (!older(a.last_use, b.last_use) && a.key < b.key);
  });
  return list;
}

std::vector<CacheEntry> TreeCache::evict(uint64_t max_bytes, uint64_t keep) {
  std::vector<CacheEntry> list = entries();
  uint64_t total = 0;
  for (const CacheEntry& entry : list) total += entry.bytes;
  std::vector<CacheEntry> removed;
  for (auto it = list.rbegin(); it != list.rend() && total > max_bytes; ++it) {
    if (it->key == keep) continue;
    ::unlink(it->tree_path.c_str());
    ::unlink(scenes_path(it->key).c_str());
    total -= it->bytes;
    removed.push_back(*it);
  }
  return removed;
}

CachedTree cached_tree(TreeCache& cache, const Scene& scene, const std::string& scene_path,
                       const BuildSettings& settings, const BuildControl& control, const std::string& output) {
  const uint64_t key = tree_key(scene.geometry_hash, settings.resolved(scene.triangle_count()));
  std::optional<KdTree> found = output.empty() ? cache.load(key, scene_path) : cache.copy_out(key, output, scene_path);
  if (found) return {std::move(*found), true, cache.tree_path(key)};

  KdTree tree = cache.build(key, scene, scene_path, settings, control);
  // Copied from the entry, so that the output shares its blocks where the file system can.
  if (!output.empty() && !cache.copy_out(key, output, scene_path)) write_tree(output, tree);
  return {std::move(tree), false, cache.tree_path(key)};
}

SceneAndTree read_scene_and_tree(const std::string& scene_path, const std::string& tree_path,
                                 const std::string& cache_folder, const CacheWarning& warn) {
  SceneAndTree read;
  if (cache_folder.empty()) {
    // Two independent files: read at once, each with its checksum beside its own checks.
    tbb::parallel_invoke([&] { read.scene = read_scene(scene_path); }, [&] { read.tree = read_tree(tree_path); });
    check_tree_matches_scene(read.tree, tree_path, geometry_of(read.scene), scene_path);
    return read;
  }
  read.scene = read_scene(scene_path);
  TreeCache cache(cache_folder, warn);
  read.tree = cached_tree(cache, read.scene, scene_path, BuildSettings{}).tree;
  return read;
}

KdTree read_tree_for_scene(const std::string& scene_path, const std::string& tree_path) {
  SceneGeometry geometry;
  KdTree tree;
  tbb::parallel_invoke([&] { geometry = read_scene_geometry(scene_path); }, [&] { tree = read_tree(tree_path); });
  check_tree_matches_scene(tree, tree_path, geometry, scene_path);
  return tree;
}

}  // namespace kdray
