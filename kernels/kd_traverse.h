/* k-d tree traversal shared by the CPU reference (libkdtree) and the OpenCL kernels.
 * CONTRACT (implemented by the libkdtree work; callers rely on these names):
 *
 *   typedef struct KdSceneView {
 *     KD_GLOBAL const KdNode* nodes;          root at index 0
 *     KD_GLOBAL const kd_u32* leaf_triangles; leaves are ranges of this array
 *     KD_GLOBAL const kd_u32* indices;        3 per triangle
 *     KD_GLOBAL const float* positions;       3 floats per vertex
 *     float bounds_min[3], bounds_max[3];     root voxel
 *   } KdSceneView;
 *
 *   HitRecord kd_intersect_closest(const KdSceneView* scene, RayRecord ray);
 *       closest hit with tmin < t < tmax (t=+inf, triangle=KD_NO_HIT on a miss)
 *   int kd_intersect_any(const KdSceneView* scene, RayRecord ray);
 *       1 if any triangle is hit with tmin < t < tmax (shadow rays)
 *
 * Short stack with restart; KD_SHORT_STACK_SIZE (default below) is a compile-time constant.
 */
#ifndef KD_TRAVERSE_H
#define KD_TRAVERSE_H

#include "kd_compat.h"
#include "kd_types.h"

#ifndef KD_SHORT_STACK_SIZE
#define KD_SHORT_STACK_SIZE 8
#endif

#endif /* KD_TRAVERSE_H */
