// kdinfo: what a kdray file holds and whether it is intact. The file kind is recognised by
// its magic number; each kind has one describe function (kKinds below).
#include "file_report.h"

#include <kdray/container_file.h>
#include <kdray/error.h>
#include <kdray/format.h>

#include <tool_main.h>

#include <cstring>
#include <filesystem>
#include <iostream>

namespace {

struct FileKind {
  const char* magic;  // 8 bytes, from kdray/format.h
  kdinfo::FileReport (*describe)(const std::string& path);
};

// One entry per file kind kdinfo understands.
const FileKind kKinds[] = {
    {kdray::format::kSceneMagic, kdinfo::describe_scene_file},
    {kdray::format::kTreeMagic, kdinfo::describe_tree_file},
};

const FileKind* kind_of(const std::string& path) {
  const std::string magic = kdray::file_magic(path);
  for (const FileKind& kind : kKinds)
    if (magic.size() == 8 && std::memcmp(magic.data(), kind.magic, 8) == 0) return &kind;
  return nullptr;
}

}  // namespace

kdinfo::FileReport describe(const std::string& path) {
  if (std::filesystem::is_directory(path)) return kdinfo::describe_cache(path);
  const FileKind* kind = kind_of(path);
  if (kind == nullptr) {
    if (!std::filesystem::exists(path)) throw kdray::Error(path, "no such file");
    throw kdray::Error(path, "not a kdray file (unknown magic number)");
  }
  return kind->describe(path);
}

bool is_kind(const kdinfo::FileReport& report, const char* kind) { return report.json.at("kind") == kind; }

int main(int argc, char** argv) {
  CLI::App app{"Describes kdray files (.kdscene, .kdtree) and checks that they are intact.\n"
               "Given a scene and a tree, also says whether the tree was built for that scene.\n"
               "Given a tree cache folder (kdbuild --cache), lists its entries."};
  kdray::tool::OutputFlags output;
  kdray::tool::add_contract(app, "kdinfo", output, "Print the description as JSON on stdout",
                            "Exit status: 0 intact (and matching); 1 missing, damaged, unreadable or stale (one line "
                            "on stderr says why); 2 bad command line.");
  std::vector<std::string> paths;
  app.add_option("FILE", paths, "The file to describe, a .kdscene and a .kdtree to check together, or a tree cache folder")
      ->required()
      ->expected(1, 2);

  return kdray::tool::run(app, argc, argv, [&] {
    std::vector<kdinfo::FileReport> reports;
    for (const std::string& path : paths) reports.push_back(describe(path));
    if (reports.size() == 2) {
      if (is_kind(reports[0], "kdtree")) std::swap(reports[0], reports[1]);
      if (!is_kind(reports[0], "kdscene") || !is_kind(reports[1], "kdtree"))
        throw kdray::Error(paths[1], "two files must be one .kdscene and one .kdtree");
      reports.push_back(kdinfo::describe_match(reports[0], reports[1]));
    }
    bool all_good = true;
    nlohmann::json documents = nlohmann::json::array();
    for (const kdinfo::FileReport& report : reports) {
      all_good = all_good && report.intact;
      documents.push_back(report.json);
      if (!report.problem.empty()) kdray::tool::print_error("kdinfo", report.problem);
      if (!output.json && !output.quiet) std::cout << report.text << (&report != &reports.back() ? "\n" : "");
    }
    if (output.json) {
      if (reports.size() == 1)
        kdray::tool::print_json(documents[0]);
      else
        kdray::tool::print_json({{"scene", documents[0]}, {"tree", documents[1]}, {"match", documents[2]["match"]}});
    }
    return all_good ? kdray::tool::kExitOk : kdray::tool::kExitFailure;
  });
}
