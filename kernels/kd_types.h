/* Structs shared between the host and the device, byte for byte. No float3 in buffers:
 * it is 16 bytes on OpenCL devices and 12 on the host. */
#ifndef KD_TYPES_H
#define KD_TYPES_H

#include "kd_compat.h"

/* One k-d tree node, 8 bytes (formats/kdtree.md).
 *   inner: payload = bits of the split position (float32);
 *          header = far_child << 4 | above_empty << 3 | below_empty << 2 | axis (0,1,2).
 *          A child with no triangles is no node: its bit in the parent says so, and the
 *          traversal skips it without a load. The below child, when it is a node, is the next
 *          node in the array; the above child, when it is a node, is far_child (0 when it is not).
 *   leaf:  payload = the first word of its block in the leaf-block array (below);
 *          header = count << 3 | grouped << 2 | 3, count = its triangles (0 only for the root
 *          of an empty scene), grouped = its block's layout (below). */
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
#define KD_BELOW_EMPTY 4u
#define KD_ABOVE_EMPTY 8u
#define KD_CHILD_SHIFT 4u
#define KD_MAX_CHILD_INDEX ((1u << 28) - 1u)
#define KD_LEAF_GROUPED 4u
#define KD_LEAF_COUNT_SHIFT 3u
#define KD_MAX_LEAF_COUNT ((1u << 29) - 1u)

KD_INLINE int kd_node_is_leaf(KdNode node) { return (node.header & 3u) == KD_LEAF_TAG; }
KD_INLINE kd_u32 kd_node_axis(KdNode node) { return node.header & 3u; }
KD_INLINE float kd_node_split(KdNode node) { return kd_as_float(node.payload); }
KD_INLINE kd_u32 kd_node_far_child(KdNode node) { return node.header >> KD_CHILD_SHIFT; }
/* Of an inner node: whether its below (above) child holds no triangles and so is no node. */
KD_INLINE int kd_node_below_empty(KdNode node) { return (node.header & KD_BELOW_EMPTY) != 0u; }
KD_INLINE int kd_node_above_empty(KdNode node) { return (node.header & KD_ABOVE_EMPTY) != 0u; }
/* Of an inner node at node_index: its below (above = 0) or above (above = 1) child's index, and
 * whether that child is empty (then it is no node, and the index means nothing). */
KD_INLINE kd_u32 kd_node_child(KdNode node, kd_u32 node_index, kd_u32 above) {
  return above ? kd_node_far_child(node) : node_index + 1u;
}
KD_INLINE kd_u32 kd_node_child_empty(KdNode node, kd_u32 above) { return (node.header >> (2u + above)) & 1u; }
KD_INLINE kd_u32 kd_leaf_first(KdNode node) { return node.payload; }
KD_INLINE kd_u32 kd_leaf_count(KdNode node) { return node.header >> KD_LEAF_COUNT_SHIFT; }
KD_INLINE int kd_leaf_grouped(KdNode node) { return (node.header & KD_LEAF_GROUPED) != 0u; }
KD_INLINE KdNode kd_leaf_node(kd_u32 first_word, kd_u32 count, int grouped) {
  KdNode node;
  node.payload = first_word;
  node.header = count << KD_LEAF_COUNT_SHIFT | (grouped ? KD_LEAF_GROUPED : 0u) | KD_LEAF_TAG;
  return node;
}

/* A leaf's block of 32-bit words in the leaf-block array (formats/kdtree.md), its first word
 * where the leaf's node points, in one of two layouts that the leaf's header names.
 *
 * Paged (grouped bit 0), for a leaf of count triangles:
 *   words [0, count):          each triangle's index in the scene;
 *   words [count, 2 count):    each triangle's corners a, b, c as three numbers of 10 bits,
 *                              a | b << 10 | c << 20 (bits 30 and 31 zero);
 *   words [2 count, ...):      the corners, x, y, z each (float32), copied from the scene's
 *                              positions: those of the leaf's triangles, each distinct corner
 *                              (bit pattern) once.
 * Corner number k of triangle i is corner KD_LEAF_PAGE_CORNERS * (i / KD_LEAF_PAGE_TRIANGLES) + k:
 * each run of KD_LEAF_PAGE_TRIANGLES triangles numbers the corners of a page of its own (at most
 * 3 x 256 = 768 distinct ones, so 10 bits always suffice); every page but the last is padded to
 * KD_LEAF_PAGE_CORNERS corners. Leaves of at most 256 triangles, nearly all, have one page. A
 * leaf's triangles share most of their corners (a mesh's neighbours do), so a block is about
 * half the bytes of three corners per triangle, and a leaf is one contiguous read.
 *
 * Grouped (grouped bit 1): the triangles four at a time, KD_LEAF_GROUP_WORDS words a group, the
 * last group filled up with copies of its first triangle:
 *   words [0, 4):              the four triangles' indices in the scene;
 *   word 4 + 12 k + 4 j + l:   coordinate j (x, y, z) of corner k (a, b, c) of triangle l.
 * A coordinate of one corner of the four is one four-wide load, at an offset the ray's axis
 * order picks, where the paged layout takes four loads and three shuffles after decoding the
 * corner numbers; each triangle has its corners in full, about twice the paged bytes. */
#define KD_LEAF_GROUP_WORDS 40u
#define KD_LEAF_CORNER_BITS 10u
#define KD_LEAF_CORNER_MASK ((1u << KD_LEAF_CORNER_BITS) - 1u)
#define KD_LEAF_PAGE_TRIANGLES 256u
#define KD_LEAF_PAGE_CORNERS 1024u

/* The scene index of triangle i of a leaf whose block starts at `block`, in either layout. */
KD_INLINE kd_u32 kd_leaf_index(KD_GLOBAL const kd_u32* block, int grouped, kd_u32 i) {
  return grouped ? block[KD_LEAF_GROUP_WORDS * (i / 4u) + i % 4u] : block[i];
}

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
