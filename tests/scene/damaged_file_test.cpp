// Damaged and hostile .kdscene files: every one is rejected with kdray::Error naming the file,
// never a crash, a huge allocation or a scene the renderer cannot trust.
#include <kdray/container_file.h>
#include <kdray/error.h>
#include <kdray/scene_file.h>

#include "scene_test_util.h"
#include "test_corpus.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

namespace kdray {
namespace {

class DamagedSceneFile : public test::TempDirTest<> {
 protected:
  void SetUp() override {
    original_path_ = path("original.kdscene");
    write_scene(original_path_, test::make_quad_scene(true, true, true));
    std::ifstream file(original_path_, std::ios::binary);
    bytes_.assign(std::istreambuf_iterator<char>(file), {});
  }


  void write_bytes(const std::string& target, const std::vector<char>& bytes) const {
    std::ofstream file(target, std::ios::binary | std::ios::trunc);
    file.write(bytes.data(), std::streamsize(bytes.size()));
  }

  // Expects read_scene to throw kdray::Error whose message names the file; returns the message.
  static std::string expect_rejected(const std::string& target) {
    try {
      read_scene(target);
    } catch (const Error& error) {
      EXPECT_EQ(std::string(error.what()).rfind(target + ": ", 0), 0u) << error.what();
      return error.what();
    } catch (const std::exception& other) {
      ADD_FAILURE() << "not a kdray::Error: " << other.what();
      return {};
    }
    ADD_FAILURE() << target << " was accepted";
    return {};
  }

  // expect_rejected, and the same rejection from read_scene_geometry, which checks the file the
  // same way apart from the arrays' elements.
  static std::string expect_both_reject(const std::string& target) {
    const std::string message = expect_rejected(target);
    try {
      read_scene_geometry(target);
      ADD_FAILURE() << target << " was accepted by read_scene_geometry";
    } catch (const Error& error) {
      EXPECT_EQ(error.what(), message);
    }
    return message;
  }

  std::string original_path_;
  std::vector<char> bytes_;
};

TEST_F(DamagedSceneFile, EveryTruncationIsRejected) {
  const std::string target = path("truncated.kdscene");
  for (size_t length = 0; length < bytes_.size(); ++length) {
    write_bytes(target, std::vector<char>(bytes_.begin(), bytes_.begin() + long(length)));
    SCOPED_TRACE("length " + std::to_string(length));
    const std::string message = expect_both_reject(target);
    const char* expected = length < 8 ? "too short" : "truncated";
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
}

TEST_F(DamagedSceneFile, RandomByteFlipsAreRejected) {
  const std::string target = path("flipped.kdscene");
  std::mt19937 random(20261122);
  std::uniform_int_distribution<size_t> position(0, bytes_.size() - 1);
  std::uniform_int_distribution<int> mask(1, 255);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<char> damaged = bytes_;
    const size_t at = position(random);
    damaged[at] = char(damaged[at] ^ mask(random));
    write_bytes(target, damaged);
    SCOPED_TRACE("byte " + std::to_string(at));
    expect_both_reject(target);
  }
}

TEST_F(DamagedSceneFile, EachHeaderFieldHasItsOwnMessage) {
  auto damaged_at = [&](size_t offset, char value) {
    std::vector<char> damaged = bytes_;
    damaged[offset] = value;
    write_bytes(path("header.kdscene"), damaged);
    return expect_both_reject(path("header.kdscene"));
  };
  EXPECT_NE(damaged_at(0, 'X').find("not a kdscene file"), std::string::npos);
  const uint32_t newer = format::kSceneVersion + 1;
  EXPECT_NE(damaged_at(8, char(newer)).find("version " + std::to_string(newer) + " is not supported"), std::string::npos);
  EXPECT_NE(damaged_at(24, char(bytes_[24] ^ 1)).find("content hash"), std::string::npos);
  EXPECT_NE(damaged_at(52, 1).find("reserved"), std::string::npos);
  EXPECT_NE(damaged_at(40, char(bytes_[40] ^ 1)).find("checksum mismatch"), std::string::npos);
  std::vector<char> longer = bytes_;
  longer.push_back(0);
  write_bytes(path("longer.kdscene"), longer);
  EXPECT_NE(expect_both_reject(path("longer.kdscene")).find("trailing bytes"), std::string::npos);
}

// Files with a valid checksum whose content is inconsistent: what a buggy or hostile writer
// could produce. Built with the container writer directly.
class HostileSceneFile : public DamagedSceneFile {
 protected:
  struct Parts {
    std::vector<Vec3> positions{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    std::vector<uint32_t> indices{0, 1, 2};
    std::vector<uint32_t> material_ids{0};
    std::string materials, cameras, info;
    uint64_t flags = 0;
  };

  Parts valid_parts() const {
    Scene scene;
    scene.materials.resize(1);
    scene.cameras.resize(1);
    Parts parts;
    parts.materials = blob_of(format::kSceneMaterials, scene);
    parts.cameras = blob_of(format::kSceneCameras, scene);
    parts.info = blob_of(format::kSceneInfo, scene);
    return parts;
  }

  // The encoded bytes of one structured section, taken from a file written by write_scene.
  std::string blob_of(uint32_t id, Scene scene) const {
    scene.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    scene.indices = {0, 1, 2};
    scene.material_ids = {0};
    const std::string source = path("source.kdscene");
    write_scene(source, scene);
    std::string blob;
    const ContainerContents contents = peek_container(source, format::kSceneMagic, format::kSceneVersion, "kdscene");
    std::ifstream file(source, std::ios::binary);
    for (const auto& section : contents.sections) {
      if (section.id != id) continue;
      blob.resize(section.size);
      file.seekg(long(section.offset));
      file.read(blob.data(), long(section.size));
    }
    return blob;
  }

  std::string write(const Parts& parts) const {
    const std::string target = path("hostile.kdscene");
    std::vector<SectionData> sections = {
        {format::kScenePositions, parts.positions.data(), parts.positions.size() * sizeof(Vec3)},
        {format::kSceneIndices, parts.indices.data(), parts.indices.size() * sizeof(uint32_t)},
        {format::kSceneMaterialIds, parts.material_ids.data(), parts.material_ids.size() * sizeof(uint32_t)},
        {format::kSceneMaterials, parts.materials.data(), parts.materials.size()},
        {format::kSceneCameras, parts.cameras.data(), parts.cameras.size()},
        {format::kSceneInfo, parts.info.data(), parts.info.size()},
    };
    write_container(target, {format::kSceneMagic, format::kSceneVersion, parts.flags, 0}, sections);
    return target;
  }

  std::string rejection_of(const Parts& parts) { return expect_rejected(write(parts)); }
};

TEST_F(HostileSceneFile, ValidPartsAreAcceptedApartFromTheHash) {
  // The hash in these hand-made headers is 0, so even valid parts fail only on the hash.
  EXPECT_NE(rejection_of(valid_parts()).find("content hash"), std::string::npos);
}

TEST_F(HostileSceneFile, IndexBeyondTheVerticesIsRejected) {
  Parts parts = valid_parts();
  parts.indices[2] = 3;
  EXPECT_NE(rejection_of(parts).find("refers to vertex 3 of 3"), std::string::npos);
}

TEST_F(HostileSceneFile, MaterialIdBeyondTheMaterialsIsRejected) {
  Parts parts = valid_parts();
  parts.material_ids[0] = 1;
  EXPECT_NE(rejection_of(parts).find("has material 1 of 1"), std::string::npos);
}

TEST_F(HostileSceneFile, MaterialIdCountMustMatchTheTriangles) {
  Parts parts = valid_parts();
  parts.material_ids.push_back(0);
  EXPECT_NE(rejection_of(parts).find("2 material ids for 1 triangles"), std::string::npos);
}

TEST_F(HostileSceneFile, SectionSizesMustBeWholeElements) {
  Parts parts = valid_parts();
  parts.indices.push_back(0);  // 16 bytes: not a whole triangle
  EXPECT_NE(rejection_of(parts).find("not a multiple of 12"), std::string::npos);
}

TEST_F(HostileSceneFile, HugeCountInAStructuredSectionIsRejectedWithoutAllocating) {
  Parts parts = valid_parts();
  // After the endianness byte comes the material count: claim 2^62 materials.
  const uint64_t huge = uint64_t(1) << 62;
  parts.materials.replace(1, 8, reinterpret_cast<const char*>(&huge), 8);
  EXPECT_NE(rejection_of(parts).find("exceeds its section"), std::string::npos);
}

TEST_F(HostileSceneFile, TruncatedStructuredSectionIsRejected) {
  Parts parts = valid_parts();
  parts.cameras.pop_back();
  EXPECT_NE(rejection_of(parts).find("malformed cameras section"), std::string::npos);
}

TEST_F(HostileSceneFile, FlagsMustMatchTheSections) {
  Parts parts = valid_parts();
  parts.flags = format::kSceneHasNormals;
  EXPECT_NE(rejection_of(parts).find("flags disagree"), std::string::npos);
  parts.flags = uint64_t(1) << 40;
  EXPECT_NE(rejection_of(parts).find("unknown flag bits"), std::string::npos);
}

}  // namespace
}  // namespace kdray
