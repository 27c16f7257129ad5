// Small helpers that every library and tool needs, defined once: hexadecimal hashes,
// lower-cased file extensions, the sRGB transfer function and an owned file descriptor.
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <unistd.h>

namespace kdray {

// A 64-bit hash as every file, report and cache name spells it: 16 lower-case hex digits.
inline std::string hash_hex(uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

// The hash that hash_hex spelled, or nothing when `text` is not exactly 16 lower-case hex
// digits: the one parser of hashes in file names and metadata, as strict as the writer.
inline std::optional<uint64_t> parse_hash_hex(const std::string& text) {
  if (text.size() != 16) return std::nullopt;
  uint64_t hash = 0;
  for (const char c : text) {
    if (c >= '0' && c <= '9') hash = hash << 4 | uint64_t(c - '0');
    else if (c >= 'a' && c <= 'f') hash = hash << 4 | uint64_t(c - 'a' + 10);
    else return std::nullopt;
  }
  return hash;
}

// The extension of `path` with its dot, lower-cased: ".obj" for "Model.OBJ", "" when none.
inline std::string lowercase_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// The sRGB transfer function (IEC 61966-2-1) on [0, 1]: linear to encoded clamps its input
// first (NaN counts as 0), encoded to linear expects [0, 1].
inline float linear_to_srgb(float linear) {
  const float c = std::isfinite(linear) ? std::clamp(linear, 0.0f, 1.0f) : 0.0f;
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

inline float srgb_to_linear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// A POSIX file descriptor closed when it goes out of scope (negative: none).
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_;
};

}  // namespace kdray
