// The shading copy of the triangles' corners: each triangle's three, copied from the scene's
// positions, in triangle order.
#include <kdray/traverse.h>

#include <kernels/kd_scene_view.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace kdray {

TraversalArray<float> gather_triangle_vertices(const Scene& scene) {
  TraversalArray<float> vertices(scene.triangle_count() * KD_TRIANGLE_FLOATS);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, scene.triangle_count(), 16384),
                    [&](const tbb::blocked_range<size_t>& range) {
                      for (size_t triangle = range.begin(); triangle < range.end(); ++triangle) {
                        float* corners = vertices.data() + triangle * KD_TRIANGLE_FLOATS;
                        for (size_t corner = 0; corner < 3; ++corner) {
                          const Vec3& p = scene.positions[scene.indices[3 * triangle + corner]];
                          corners[3 * corner + 0] = p.x;
                          corners[3 * corner + 1] = p.y;
                          corners[3 * corner + 2] = p.z;
                        }
                      }
                    });
  return vertices;
}

}  // namespace kdray
