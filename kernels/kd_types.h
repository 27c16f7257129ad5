/* Structs shared between the host and the device, byte for byte. No float3 in buffers:
 * it is 16 bytes on OpenCL devices and 12 on the host. */
#ifndef KD_TYPES_H
#define KD_TYPES_H

#include "kd_compat.h"

/* One k-d tree node, 8 bytes (formats/kdtree.md).
 *   inner: payload = bits of the split position (float32); header = far_child << 2 | axis (0,1,2).
 *          The near ("below") child is the next node in the array.
 *   leaf:  payload = its first entry of the leaf-triangle array (KdLeafTriangle);
 *          header = count << 2 | 3. */
typedef struct KdNode {
  kd_u32 payload;
  kd_u32 header;
} KdNode;
KD_STATIC_ASSERT(sizeof(KdNode) == 8 && KD_OFFSETOF(KdNode, header) == 4,
                 "KdNode: 8 bytes on disk and on the device, payload then header");

/* The deepest tree any builder writes and read_tree accepts (kdray::BuildSettings::kMaxDepthLimit);
 * a traversal stack of this size never overflows, which is the "full stack" variant. */
#define KD_MAX_TREE_DEPTH 64

#define KD_LEAF_TAG 3u
#define KD_MAX_CHILD_INDEX ((1u << 30) - 1u)

KD_INLINE int kd_node_is_leaf(KdNode node) { return (node.header & 3u) == KD_LEAF_TAG; }
KD_INLINE kd_u32 kd_node_axis(KdNode node) { return node.header & 3u; }
KD_INLINE float kd_node_split(KdNode node) { return kd_as_float(node.payload); }
KD_INLINE kd_u32 kd_node_far_child(KdNode node) { return node.header >> 2; }
KD_INLINE kd_u32 kd_leaf_first(KdNode node) { return node.payload; }
KD_INLINE kd_u32 kd_leaf_count(KdNode node) { return node.header >> 2; }

/* One entry of a leaf's triangle list (formats/kdtree.md): the corners a, b, c of the triangle
 * (x, y, z each), copied from the scene's positions, then its index in the scene. A leaf is a
 * range of these, so the triangles it holds are one contiguous read, and a triangle in several
 * leaves is copied into each. 40 bytes. */
typedef struct KdLeafTriangle {
  float corners[9];
  kd_u32 triangle;
} KdLeafTriangle;
KD_STATIC_ASSERT(sizeof(KdLeafTriangle) == 40 && KD_OFFSETOF(KdLeafTriangle, triangle) == 36,
                 "KdLeafTriangle: 40 bytes on disk and on the device, corners then index");

/* One record of a ray file (formats/rays.md): little-endian float32, 32 bytes. */
typedef struct RayRecord {
  float ox, oy, oz;
  float dx, dy, dz;
  float tmin, tmax;
} RayRecord;
KD_STATIC_ASSERT(sizeof(RayRecord) == 32 && KD_OFFSETOF(RayRecord, dx) == 12 && KD_OFFSETOF(RayRecord, tmin) == 24,
                 "RayRecord: 32 bytes, members where the other side reads them");

/* One record of a hit file: t = +inf and triangle = KD_NO_HIT on a miss; u, v barycentrics
 * of vertices 1 and 2. 16 bytes. */
typedef struct HitRecord {
  float t;
  kd_u32 triangle;
  float u, v;
} HitRecord;
KD_STATIC_ASSERT(sizeof(HitRecord) == 16 && KD_OFFSETOF(HitRecord, triangle) == 4 && KD_OFFSETOF(HitRecord, u) == 8,
                 "HitRecord: 16 bytes, members where the other side reads them");

#define KD_NO_HIT 0xFFFFFFFFu

#endif /* KD_TYPES_H */
