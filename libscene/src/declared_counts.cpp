#include "declared_counts.h"

#include <kdray/error.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace kdray {
namespace {

// Headers are short; anything beyond this is not looked at.
constexpr size_t kHeaderBytes = 4096;

void check(const std::string& path, const std::string& element, const std::string& count_text, uint64_t file_size) {
  // Counts are compared as text-parsed 64-bit values so an overflowing count is still caught.
  uint64_t count = 0;
  for (char c : count_text) {
    if (c < '0' || c > '9') return;  // not a count: leave it to the loader
    if (count > (UINT64_MAX - 9) / 10) {
      count = UINT64_MAX;
      break;
    }
    count = count * 10 + uint64_t(c - '0');
  }
  if (count > file_size)
    throw Error(path, "the header announces " + count_text + " " + element + " but the file has only " +
                          std::to_string(file_size) + " bytes");
}

void check_off(const std::string& path, std::istringstream& header, uint64_t file_size) {
  std::string line;
  std::getline(header, line);  // OFF, COFF, NOFF, ... possibly followed by the counts
  std::istringstream first(line);
  std::string keyword, vertices, faces;
  first >> keyword >> vertices >> faces;
  while (vertices.empty() && std::getline(header, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream counts(line);
    counts >> vertices >> faces;
  }
  check(path, "vertices", vertices, file_size);
  check(path, "faces", faces, file_size);
}

void check_ply(const std::string& path, std::istringstream& header, uint64_t file_size) {
  std::string line;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string keyword, element, count;
    words >> keyword >> element >> count;
    if (keyword == "end_header") return;
    if (keyword == "element") check(path, element + " elements", count, file_size);
  }
}

}  // namespace

void check_declared_counts(const std::string& path) {
  std::error_code error;
  const uint64_t file_size = std::filesystem::file_size(path, error);
  if (error) return;
  std::ifstream file(path, std::ios::binary);
  std::string text(kHeaderBytes, '\0');
  file.read(text.data(), text.size());
  text.resize(static_cast<size_t>(file.gcount()));
  std::istringstream header(text);
  if (text.compare(0, 3, "ply") == 0) check_ply(path, header, file_size);
  const size_t off = text.find("OFF");
  if (off != std::string::npos && off <= 4 && text.find_first_of("\n\r") > off) check_off(path, header, file_size);
}

}  // namespace kdray
