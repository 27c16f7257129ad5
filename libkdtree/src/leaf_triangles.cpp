// The leaf-triangle entries a tree's leaves are ranges of (kernels/kd_types.h, KdLeafTriangle).
#include <kdray/kdtree.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace kdray {

TraversalArray<KdLeafTriangle> leaf_triangles_of(const Scene& scene, const uint32_t* triangles, size_t count) {
  TraversalArray<KdLeafTriangle> entries(count);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 16384), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) {
      KdLeafTriangle& entry = entries[i];
      entry.triangle = triangles[i];
      for (size_t corner = 0; corner < 3; ++corner) {
        const Vec3& p = scene.positions[scene.indices[3 * size_t{entry.triangle} + corner]];
        entry.corners[3 * corner + 0] = p.x;
        entry.corners[3 * corner + 1] = p.y;
        entry.corners[3 * corner + 2] = p.z;
      }
    }
  });
  return entries;
}

}  // namespace kdray
