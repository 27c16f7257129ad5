// The section container's writer: sections made piece by piece as they are written (a produce
// function, the next piece made while one is written) give the bytes the same sections give
// when handed over whole, whatever piece boundaries they cross or share, and read back intact.
#include <kdray/container_file.h>

#include "test_corpus.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

namespace kdray {
namespace {

constexpr char kMagic[8] = {'K', 'D', 'T', 'E', 'S', 'T', '0', '1'};

class ContainerWriter : public test::TempDirTest<> {
 protected:
  std::vector<char> bytes_of(const std::string& file) const {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }
};

TEST_F(ContainerWriter, MadeSectionsGiveTheBytesOfWholeOnes) {
  constexpr uint64_t kMiB = uint64_t{1} << 20;
  // Sizes that start and end inside 1 MiB pieces, span several, share one with the section
  // after them, and one that is empty.
  const std::vector<uint64_t> sizes = {3 * kMiB + 5, 5 * kMiB + 123, 100, 2 * kMiB + 7, 0, 4 * kMiB};
  std::vector<std::vector<char>> contents;
  for (size_t s = 0; s < sizes.size(); ++s) {
    std::vector<char> bytes(sizes[s]);
    for (uint64_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 131 + s * 7) >> 3);
    contents.push_back(std::move(bytes));
  }
  std::vector<SectionData> whole, made;
  for (size_t s = 0; s < sizes.size(); ++s) {
    const uint32_t id = static_cast<uint32_t>(s + 1);
    whole.push_back({id, contents[s].data(), sizes[s]});
    if (s % 2 == 0) {
      made.push_back(whole.back());
      continue;
    }
    const char* source = contents[s].data();
    made.push_back({id, nullptr, sizes[s], [source](uint64_t begin, uint64_t end, char* out) {
                      std::memcpy(out, source + begin, end - begin);
                    }});
  }
  made[4].produce = [](uint64_t, uint64_t, char*) { ADD_FAILURE() << "an empty section was made"; };
  write_container(path("whole.bin"), {kMagic, 1, 0, 42}, whole);
  write_container(path("made.bin"), {kMagic, 1, 0, 42}, made);
  EXPECT_EQ(bytes_of(path("whole.bin")), bytes_of(path("made.bin")));

  const MappedContainer read = map_container(path("made.bin"), kMagic, 1, "test", {});
  ASSERT_EQ(read.contents.sections.size(), sizes.size());
  for (size_t s = 0; s < sizes.size(); ++s)
    EXPECT_TRUE(std::equal(contents[s].begin(), contents[s].end(), read.bytes + read.contents.sections[s].offset)) << s;
}

TEST_F(ContainerWriter, AFailureWhileMakingLeavesNoFile) {
  const std::vector<char> bytes(6 << 20, 'x');
  const std::vector<SectionData> sections = {
      {1, nullptr, bytes.size(), [](uint64_t begin, uint64_t, char*) {
         if (begin > 0) throw std::runtime_error("cannot make this part");
       }}};
  EXPECT_THROW(write_container(path("failed.bin"), {kMagic, 1, 0, 0}, sections), std::runtime_error);
  EXPECT_TRUE(std::filesystem::is_empty(dir_));
}

}  // namespace
}  // namespace kdray
