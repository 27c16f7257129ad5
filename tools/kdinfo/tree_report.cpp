// kdinfo's description of a .kdtree file, and of whether a tree matches a scene.
#include "file_report.h"

#include <kdray/container_file.h>
#include <kdray/error.h>
#include <kdray/kdtree.h>

#include <scene_json.h>
#include <tree_json.h>

namespace kdinfo {
namespace {

using nlohmann::json;

json tree_json(const kdray::KdTree& tree) {
  json j = kdray::tool::tree_stats_json(tree);
  j["key"] = kdray::hash_hex(tree.key);
  j["bounds"] = kdray::tool::bounds_json(tree.bounds);
  return j;
}

std::string tree_text(const json& j) {
  const json& s = j["build_settings"];
  const json& b = j["bounds"];
  std::string text;
  if (j["key"] != kdray::hash_hex(0)) text += format("key        %s\n", j["key"].get<std::string>().c_str());
  text += format("triangles  %llu\n", j["triangles"].get<unsigned long long>());
  text += format("bounds     (%g, %g, %g) .. (%g, %g, %g)\n", b["min"][0].get<double>(), b["min"][1].get<double>(),
                 b["min"][2].get<double>(), b["max"][0].get<double>(), b["max"][1].get<double>(),
                 b["max"][2].get<double>());
  text += format("settings   K_T %g, K_I %g, empty bonus %g, max depth %u%s, perfect splits %s\n",
                 s["kt"].get<double>(), s["ki"].get<double>(), s["empty_bonus"].get<double>(),
                 s["max_depth"].get<unsigned>(), s["max_depth"].get<unsigned>() == 0 ? " (automatic)" : "",
                 s["perfect_splits"].get<bool>() ? "on" : "off");
  if (s["binned_above"].get<unsigned>() == 0)
    text += "splits     exact sweep everywhere\n";
  else
    text += format("splits     %u bins per axis above %u triangles, exact sweep below\n", s["bins"].get<unsigned>(),
                   s["binned_above"].get<unsigned>());
  text += format("blocks     %s\n", s["leaf_layout"].get<std::string>().c_str());
  text += format("SAH cost   %.4g\n", j["sah_cost"].get<double>());
  text += format("nodes      %llu inner, %llu leaves (%llu empty)\n", j["inner_nodes"].get<unsigned long long>(),
                 j["leaves"].get<unsigned long long>(), j["empty_leaves"].get<unsigned long long>());
  text += format("depth      max %u, mean leaf %.2f\n", j["max_leaf_depth"].get<unsigned>(),
                 j["mean_leaf_depth"].get<double>());
  text += format("leaves     %.2f triangles per non-empty leaf, %.2f references per triangle\n",
                 j["mean_triangles_per_leaf"].get<double>(), j["references_per_triangle"].get<double>());
  return text;
}

}  // namespace

FileReport describe_tree_file(const std::string& path) {
  const kdray::ContainerContents header =
      kdray::peek_container(path, kdray::format::kTreeMagic, kdray::format::kTreeVersion, "kdtree");
  FileReport report;
  // Version 2 trees record their scene's geometry hash, version 1 trees its content hash.
  const bool geometry = header.header.version >= 2;
  const std::string hash = kdray::hash_hex(header.header.content_hash);
  report.json = {{"file", path},
                 {"kind", "kdtree"},
                 {"format_version", header.header.version},
                 {"file_size", header.header.payload_size + sizeof(kdray::format::FileHeader)},
                 {geometry ? "geometry_hash" : "scene_hash", hash}};
  report.text = format("%s: kdtree version %u\n%s %s (the scene it was built from)\n", path.c_str(),
                       header.header.version, geometry ? "geometry  " : "scene hash", hash.c_str());
  add_verified_details(
      report, "checksum and structure", [&] { return kdray::read_tree(path); }, tree_json, tree_text);
  return report;
}

FileReport describe_match(const FileReport& scene, const FileReport& tree) {
  FileReport report;
  // A version 2 tree names its scene's geometry hash (known once the scene was read whole), a
  // version 1 tree the scene's content hash.
  const bool geometry = tree.json.contains("geometry_hash");
  const std::string what = geometry ? "geometry" : "scene";
  const std::string tree_scene_hash = tree.json.at(geometry ? "geometry_hash" : "scene_hash");
  const std::string scene_hash = scene.json.value(geometry ? "geometry_hash" : "content_hash", std::string());
  const bool same_hash = scene_hash.empty() || scene_hash == tree_scene_hash;
  // The recorded hash covers the triangles, so a matching hash with intact files means the
  // tree's triangle references fit the scene; a damaged file cannot be vouched for.
  report.intact = same_hash && scene.intact && tree.intact;
  report.json = {{"scene", scene.json.at("file")}, {"tree", tree.json.at("file")}, {"match", report.intact}};
  if (!same_hash) {
    report.problem = tree.json.at("file").get<std::string>() + ": stale tree: built for " + what + " " +
                     tree_scene_hash + ", not for " + scene.json.at("file").get<std::string>() + ": rebuild with kdbuild";
    report.text = format("match      NO: stale tree: built for %s %s, but %s has %s: rebuild with kdbuild\n",
                         what.c_str(), tree_scene_hash.c_str(), scene.json.at("file").get<std::string>().c_str(),
                         scene_hash.c_str());
  } else if (!report.intact)
    report.text = "match      unknown: a file is damaged\n";
  else
    report.text = "match      yes: the tree was built for this scene\n";
  return report;
}

}  // namespace kdinfo
