// kdinfo's listing of a tree cache folder (kdbuild --cache): its entries, most recently used first.
#include "file_report.h"

#include <kdray/container_file.h>
#include <kdray/tree_cache.h>

#include <ctime>

namespace kdinfo {
namespace {

// UTC, to the second, as ISO 8601.
std::string utc_time(const std::timespec& time) {
  std::tm parts{};
  gmtime_r(&time.tv_sec, &parts);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &parts);
  return text;
}

}  // namespace

FileReport describe_cache(const std::string& folder) {
  const kdray::TreeCache cache(folder);
  const std::vector<kdray::CacheEntry> entries = cache.entries();
  FileReport report;
  uint64_t total = 0;
  nlohmann::json list = nlohmann::json::array();
  std::string lines;
  for (const kdray::CacheEntry& entry : entries) {
    total += entry.bytes;
    const std::string key = kdray::hash_hex(entry.key), last_use = utc_time(entry.last_use);
    list.push_back({{"key", key}, {"tree", entry.tree_path}, {"bytes", entry.bytes}, {"last_use", last_use},
                    {"scenes", entry.scenes}});
    lines += format("%s  %10llu  %s\n", key.c_str(), static_cast<unsigned long long>(entry.bytes), last_use.c_str());
    for (const std::string& scene : entry.scenes) lines += "  " + scene + "\n";
  }
  report.json = {{"file", folder}, {"kind", "tree cache"}, {"entries", list}, {"total_bytes", total}};
  report.text = format("%s: tree cache, %zu entries, %llu bytes (most recently used first)\n", folder.c_str(),
                       entries.size(), static_cast<unsigned long long>(total));
  if (!entries.empty()) report.text += "key               bytes       last use (UTC)\n" + lines;
  report.intact = true;
  return report;
}

}  // namespace kdinfo
