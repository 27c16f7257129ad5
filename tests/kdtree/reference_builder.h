// The O(N log^2 N) oracle for the event builder: the same candidates, cost and termination
// (libkdtree/src/build_common.h), but every node sorts its own events from scratch.
#pragma once

#include <kdray/kdtree.h>
#include <kdray/scene.h>

namespace kdray::test {

KdTree build_kdtree_by_resorting(const Scene& scene, const BuildSettings& settings);

}  // namespace kdray::test
