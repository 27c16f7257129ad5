// Running the real tool chain on generated OBJ files: kdconvert, kdbuild and kdrender as
// subprocesses in a temporary directory, with their --json reports parsed.
#pragma once

#include <subprocess.h>
#include "test_corpus.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace kdray::test {

class ToolPipeline {
 public:
  ToolPipeline() : directory_(make_temp_dir("stability")) {}
  ~ToolPipeline() { std::filesystem::remove_all(directory_); }
  ToolPipeline(const ToolPipeline&) = delete;
  ToolPipeline& operator=(const ToolPipeline&) = delete;

  std::string path(const std::string& name) const { return (directory_ / name).string(); }

  // Runs `tool` with `arguments` and --json; throws with the output when it fails.
  nlohmann::json run_json(const std::string& tool, const std::string& arguments) const {
    const ToolRun run = run_command(shell_quoted(tool_path(tool)) + " " + arguments + " --json");
    if (run.exit_code != 0) {
      throw std::runtime_error(tool + " " + arguments + " exited " + std::to_string(run.exit_code) + ": " + run.out);
    }
    return nlohmann::json::parse(run.out);
  }

  // kdconvert OBJ -> <stem>.kdscene, kdbuild -> <stem>.kdtree; returns kdconvert's report.
  nlohmann::json convert_and_build(const std::string& obj, const std::string& stem) const {
    nlohmann::json converted = run_json("kdconvert", shell_quoted(obj) + " " + shell_quoted(scene(stem)));
    run_json("kdbuild", shell_quoted(scene(stem)) + " " + shell_quoted(tree(stem)) + " --quiet");
    return converted;
  }

  // kdrender of <stem> to `image` with `options`; returns its report.
  nlohmann::json render(const std::string& stem, const std::string& image, const std::string& options) const {
    return run_json("kdrender", shell_quoted(scene(stem)) + " " + shell_quoted(tree(stem)) + " -o " +
                                    shell_quoted(image) + " --quiet " + options);
  }

  std::string scene(const std::string& stem) const { return path(stem + ".kdscene"); }
  std::string tree(const std::string& stem) const { return path(stem + ".kdtree"); }

 private:
  std::filesystem::path directory_;
};

}  // namespace kdray::test
