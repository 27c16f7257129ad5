// printf into a std::string, for the tools' human-readable reports.
#pragma once

#include <cstdarg>
#include <cstdio>
#include <string>

namespace kdray::tool {

inline std::string format(const char* pattern, ...) __attribute__((format(printf, 1, 2)));
inline std::string format(const char* pattern, ...) {
  char buffer[1024];
  va_list arguments;
  va_start(arguments, pattern);
  std::vsnprintf(buffer, sizeof buffer, pattern, arguments);
  va_end(arguments);
  return buffer;
}

}  // namespace kdray::tool
