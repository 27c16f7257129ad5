#include <kdray/module.h>

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace kdray {
namespace {

std::string module_path(const char* file_name, const char* override_variable) {
  if (const char* override_path = std::getenv(override_variable)) return override_path;
  std::error_code error;
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    for (const char* up : {"..", "../.."}) {
      const std::filesystem::path candidate = executable.parent_path() / up / "lib" / "kdray" / file_name;
      if (std::filesystem::exists(candidate, error)) return candidate.lexically_normal().string();
    }
  }
  return file_name;  // leaves the search to dlopen (LD_LIBRARY_PATH), whose error names the file
}

}  // namespace

void* load_module_symbol(const char* file_name, const char* override_variable, const char* symbol,
                         std::string& problem) {
  const std::string path = module_path(file_name, override_variable);
  void* module = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (module == nullptr) {
    problem = ::dlerror();
    return nullptr;
  }
  void* address = ::dlsym(module, symbol);
  if (address == nullptr) problem = path + " has no " + symbol;
  return address;
}

}  // namespace kdray
