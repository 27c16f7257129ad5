// The one header that pins the on-disk layout shared by .kdscene and .kdtree files:
// magic numbers, format versions, section identifiers and the fixed file header.
// The written specifications are formats/kdscene.md, formats/kdtree.md and formats/rays.md.
#pragma once

#include <cstdint>

namespace kdray::format {

// Both containers share one layout (formats/container.md): a 64-byte FileHeader,
// a table of SectionEntry records, then the section payloads, all little-endian.
struct FileHeader {
  char magic[8];             // kSceneMagic or kTreeMagic
  uint32_t version;          // format version of this file kind
  uint32_t header_size;      // sizeof(FileHeader), for forward compatibility checks
  uint64_t flags;            // which optional sections exist (kind-specific bits)
  uint64_t content_hash;     // .kdscene: hash of the scene content; .kdtree: geometry hash of the scene it was built from
  uint64_t payload_size;     // bytes after the header: section table + section data
  uint64_t payload_checksum; // XXH3-64 of those payload_size bytes
  uint32_t section_count;    // entries in the section table
  uint32_t reserved0;
  uint64_t reserved1;
};
static_assert(sizeof(FileHeader) == 64, "FileHeader is 64 bytes on disk");

struct SectionEntry {
  uint32_t id;        // a k*Section constant of the file kind
  uint32_t reserved;  // 0
  uint64_t offset;    // from the start of the file; 16-byte aligned
  uint64_t size;      // bytes
};
static_assert(sizeof(SectionEntry) == 24, "SectionEntry is 24 bytes on disk");

constexpr uint64_t kSectionAlignment = 16;
constexpr uint32_t kMaxSections = 64;

// ---- .kdscene -------------------------------------------------------------------------
constexpr char kSceneMagic[8] = {'K', 'D', 'S', 'C', 'E', 'N', 'E', '\0'};
// Version 2 added punctual lights (kSceneLights), version 3 the metallic-roughness material and
// its texture and alpha fields, version 4 the geometry hash in the scene info, version 5 the
// per-vertex tangents (kSceneTangents), version 6 each camera's aspect ratio and projection;
// version 1 to 5 files are still read.
constexpr uint32_t kSceneVersion = 6;
constexpr uint32_t kSceneGeometryHashVersion = 4;  // the first version whose scene info records it
constexpr uint32_t kSceneCameraAspectVersion = 6;  // the first version whose cameras record them

enum SceneSection : uint32_t {
  kScenePositions = 1,       // float32 x,y,z per vertex
  kSceneIndices = 2,         // uint32 v0,v1,v2 per triangle
  kSceneMaterialIds = 3,     // uint32 per triangle
  kSceneNormals = 4,         // optional: float32 x,y,z per vertex
  kSceneUVs = 5,             // optional: float32 u,v per vertex
  kSceneMaterials = 6,       // cereal portable binary: std::vector<Material>
  kSceneCameras = 7,         // cereal portable binary: std::vector<Camera>
  kSceneTextures = 8,        // optional: cereal portable binary: std::vector<Texture>
  kSceneEmissive = 9,        // optional: uint32 triangle index per emissive triangle
  kSceneInfo = 10,           // cereal portable binary: SceneInfo (source file, import statistics)
  kSceneLights = 11,         // optional (version 2): cereal portable binary: std::vector<Light>
  kSceneTangents = 12,       // optional (version 5): float32 x,y,z,w per vertex
};

enum SceneFlags : uint64_t {
  kSceneHasNormals = 1u << 0,
  kSceneHasUVs = 1u << 1,
  kSceneHasTextures = 1u << 2,
  kSceneHasEmissive = 1u << 3,
  kSceneHasLights = 1u << 4,
  kSceneHasTangents = 1u << 5,
};

// ---- .kdtree --------------------------------------------------------------------------
constexpr char kTreeMagic[8] = {'K', 'D', 'T', 'R', 'E', 'E', '\0', '\0'};
// Version 6 lets a leaf's header name its block's layout, paged or grouped (four triangles'
// corners by axis), and records the layout in the build settings. Version 5 stores no node for
// an empty leaf: its parent's header marks that child empty. Version 4 stores each leaf as one
// block of its triangles' indices, corner numbers and distinct corners (kTreeLeafBlocks);
// version 3 stored each leaf triangle's corners with its index (kTreeLeafTriangles); version 2
// keyed a tree by its scene's geometry hash and build settings (kTreeKey), version 1 by the
// scene's content hash. Readers refuse versions 1 to 5 ("rebuild").
constexpr uint32_t kTreeVersion = 6;

enum TreeSection : uint32_t {
  kTreeNodes = 1,            // KdNode (kernels/kd_types.h), 8 bytes each, root first
  kTreeLeafIndices = 2,      // versions 1 and 2 only: uint32 triangle indices, leaves were ranges of them
  kTreeParameters = 3,       // cereal portable binary: BuildSettings
  kTreeStatistics = 4,       // cereal portable binary: TreeStats
  kTreeBounds = 5,           // float32 min x,y,z, max x,y,z of the root voxel
  kTreeKey = 6,              // uint64 tree key (from version 2): geometry hash, settings, version
  kTreeLeafTriangles = 7,    // version 3 only: 40-byte records of a leaf triangle's corners and index
  kTreeLeafBlocks = 8,       // uint32 words: one block per non-empty leaf (kernels/kd_types.h)
};

}  // namespace kdray::format
