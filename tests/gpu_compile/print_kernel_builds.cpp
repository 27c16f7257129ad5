// print_kernel_builds SCENE.kdscene...: every OpenCL program kdray builds on a GPU for these
// scenes (kdray/kernel_builds.h), once each, as lines "NAME<TAB>ENTRY_FILE<TAB>OPTIONS"; NAME
// lists the scenes that build it. scripts/gpu-compile.sh compiles them for GPU targets.
#include <kdray/kernel_builds.h>
#include <kdray/scene_file.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <utility>
#include <vector>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: print_kernel_builds SCENE.kdscene...\n";
    return 2;
  }
  try {
    std::vector<std::pair<std::string, std::string>> order;  // (entry file, options), first seen first
    std::map<std::pair<std::string, std::string>, std::string> names;
    for (int i = 1; i < argc; ++i) {
      const std::string scene_name = std::filesystem::path(argv[i]).stem().string();
      for (const kdray::KernelBuild& build : kdray::gpu_kernel_builds(kdray::read_scene(argv[i]), {})) {
        const auto key = std::make_pair(build.entry_file, build.options);
        std::string& name = names[key];
        if (name.empty()) {
          order.push_back(key);
          name = build.name + ":" + scene_name;
        } else {
          name += "," + scene_name;
        }
      }
    }
    for (const auto& key : order) std::cout << names[key] << '\t' << key.first << '\t' << key.second << '\n';
    return 0;
  } catch (const std::exception& error) {
    std::cerr << "print_kernel_builds: error: " << error.what() << "\n";
    return 1;
  }
}
