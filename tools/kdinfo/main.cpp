// kdinfo: what a kdray file holds and whether it is intact. The file kind is recognised by
// its magic number; each kind has one describe function (kKinds below).
#include "file_report.h"

#include <kdray/container_file.h>
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
};

const FileKind* kind_of(const std::string& path) {
  const std::string magic = kdray::file_magic(path);
  for (const FileKind& kind : kKinds)
    if (magic.size() == 8 && std::memcmp(magic.data(), kind.magic, 8) == 0) return &kind;
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Describes a kdray file (.kdscene) and checks that it is intact.\n"
               "Exit status: 0 intact, 1 damaged or unreadable, 2 bad arguments."};
  app.name("kdinfo");
  app.set_version_flag("--version", std::string("kdinfo ") + KDRAY_VERSION);
  std::string path;
  bool json = false;
  app.add_option("FILE", path, "The file to describe")->required();
  app.add_flag("--json", json, "Print the description as JSON on stdout")->group("Output");

  return kdray::tool::run(app, argc, argv, [&] {
    const FileKind* kind = kind_of(path);
    if (kind == nullptr) {
      if (!std::filesystem::exists(path)) throw kdray::Error(path, "no such file");
      throw kdray::Error(path, "not a kdray file (unknown magic number)");
    }
    const kdinfo::FileReport report = kind->describe(path);
    if (json)
      kdray::tool::print_json(report.json);
    else
      std::cout << report.text;
    return report.intact ? kdray::tool::kExitOk : kdray::tool::kExitFailure;
  });
}
