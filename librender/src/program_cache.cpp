// Building OpenCL programs from the embedded kernels/ sources, with two caches: the programs
// this process already built, and compiled binaries on disk keyed by XXH3 of
// (source, options, device name, driver version), written atomically.
#include "opencl_runtime.h"

#include <kdray/atomic_file.h>
#include <kdray/clock.h>
#include <kdray/embedded_kernels.h>
#include <kdray/error.h>
#include <kdray/util.h>

#include <xxhash.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>


namespace kdray {
namespace fs = std::filesystem;

std::string program_cache_dir() {
  if (const char* dir = std::getenv("KDRAY_CACHE_DIR")) {
    return std::string(dir) == "off" ? std::string() : std::string(dir);
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/kdray";
  if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/kdray";
  return {};
}

namespace cl {
namespace {

const char* embedded_text(const std::string& name) {
  for (size_t i = 0; i < kernels::kEmbeddedFileCount; ++i) {
    if (name == kernels::kEmbeddedFiles[i].name) return kernels::kEmbeddedFiles[i].text;
  }
  return nullptr;
}

void expand_into(const std::string& name, std::set<std::string>& included, std::ostringstream& out) {
  const char* text = embedded_text(name);
  if (!text) throw std::runtime_error("kernel source " + name + " is not embedded in this binary");
  included.insert(name);
  std::istringstream lines(text);
  std::string line;
  int line_number = 0;
  out << "#line 1 \"" << name << "\"\n";
  while (std::getline(lines, line)) {
    ++line_number;
    const std::string directive = "#include \"";
    if (line.rfind(directive, 0) == 0) {
      std::string header = line.substr(directive.size(), line.find('"', directive.size()) - directive.size());
      if (!included.count(header)) expand_into(header, included, out);
      out << "#line " << line_number + 1 << " \"" << name << "\"\n";
      continue;
    }
    out << line << '\n';
  }
}

std::string build_log(cl_program program, cl_device_id device) {
  size_t size = 0;
  clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size);
  std::string log(size, '\0');
  clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr);
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

std::vector<unsigned char> read_cached_binary(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

// Best effort: a cache that cannot be written only costs the next run a compile.
void write_cached_binary(const std::string& dir, const std::string& path, cl_program program) {
  size_t size = 0;
  if (clGetProgramInfo(program, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, nullptr) != CL_SUCCESS || size == 0) return;
  std::vector<unsigned char> binary(size);
  unsigned char* pointer = binary.data();
  if (clGetProgramInfo(program, CL_PROGRAM_BINARIES, sizeof pointer, &pointer, nullptr) != CL_SUCCESS) return;
  std::error_code error;
  fs::create_directories(dir, error);
  try {
    write_file_atomically(path, binary.data(), size);
  } catch (const Error&) {
  }
}

cl_program program_from_binary(cl_context context, cl_device_id device, const std::vector<unsigned char>& binary,
                               const std::string& options) {
  const unsigned char* pointer = binary.data();
  size_t size = binary.size();
  cl_int binary_status = CL_SUCCESS, status = CL_SUCCESS;
  cl_program program = clCreateProgramWithBinary(context, 1, &device, &size, &pointer, &binary_status, &status);
  if (status != CL_SUCCESS || binary_status != CL_SUCCESS) return nullptr;
  if (clBuildProgram(program, 1, &device, options.c_str(), nullptr, nullptr) != CL_SUCCESS) {
    clReleaseProgram(program);
    return nullptr;
  }
  return program;
}

}  // namespace

std::string expand_kernel_source(const std::string& entry_file) {
  std::set<std::string> included;
  std::ostringstream out;
  expand_into(entry_file, included, out);
  return out.str();
}

ProgramBuild Runtime::program(const std::string& entry_file, const std::string& feature_options) {
  const std::string options =
      common_options_.empty() ? feature_options : feature_options + " " + common_options_;
  auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return seconds_since(start); };
  std::string source = expand_kernel_source(entry_file);
  std::string key_text = source + '\0' + options + '\0' + info_.platform + '\0' + info_.name + '\0' + info_.driver_version;
  std::string key = hash_hex(XXH3_64bits(key_text.data(), key_text.size()));

  std::lock_guard<std::mutex> lock(mutex_);
  if (auto found = programs_.find(key); found != programs_.end()) return {found->second.get(), elapsed(), "memory"};

  std::string dir = program_cache_dir();
  std::string cache_path = dir.empty() ? std::string() : dir + "/" + key + ".clbin";
  if (!cache_path.empty()) {
    std::vector<unsigned char> binary = read_cached_binary(cache_path);
    if (!binary.empty()) {
      if (cl_program program = program_from_binary(context_, device_, binary, options)) {
        programs_[key] = Program(program);
        return {program, elapsed(), "disk cache"};
      }
    }
  }

  const char* text = source.c_str();
  cl_int status = CL_SUCCESS;
  Program program(clCreateProgramWithSource(context_, 1, &text, nullptr, &status));
  check(status, "clCreateProgramWithSource");
  if (clBuildProgram(program.get(), 1, &device_, options.c_str(), nullptr, nullptr) != CL_SUCCESS) {
    throw std::runtime_error("OpenCL: building " + entry_file + " (" + options + ") failed on " + info_.name +
                             ":\n" + build_log(program.get(), device_));
  }
  if (!cache_path.empty()) write_cached_binary(dir, cache_path, program.get());
  cl_program handle = program.get();
  programs_[key] = std::move(program);
  return {handle, elapsed(), "compiled"};
}

}  // namespace cl
}  // namespace kdray
