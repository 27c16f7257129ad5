// One error type for everything a user can get wrong: a file and what is wrong with it.
#pragma once

#include <stdexcept>
#include <string>

namespace kdray {

// Thrown for bad input (damaged, missing or unsupported files, inconsistent arguments).
// what() reads "<file>: <problem>" so tools can print it as one line after "tool: error: ".
class Error : public std::runtime_error {
 public:
  Error(const std::string& file, const std::string& problem)
      : std::runtime_error(file.empty() ? problem : file + ": " + problem) {}
};

}  // namespace kdray
