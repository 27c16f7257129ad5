// The differential oracle: every triangle tested against every ray in double precision, and
// the rule by which a k-d tree hit "agrees" with it.
#pragma once

#include <kdray/kdtree.h>
#include <kdray/scene.h>
#include <kdray/traverse.h>

#include <kernels/kd_types.h>

#include <double_hit.h>

#include <string>
#include <vector>

namespace kdray::test {

// Checks the tree's hit for `ray` against brute force. Returns "" when they agree, else what
// is wrong. Agreement: a miss is fine when no triangle is hit clearly (margin above its
// uncertainty, t clearly inside the ray's interval); a hit must be on a triangle the double
// test hits or nearly hits, at a t within t_tolerance of the double t (widened as the ray turns parallel to it), with no clear double
// hit closer than that.
std::string disagreement(const Scene& scene, const RayRecord& ray, const HitRecord& hit, double scene_magnitude);

// "o=(x,y,z) d=(x,y,z) [tmin,tmax]" with 9 significant digits, so a float ray round-trips.
std::string describe_ray(const RayRecord& ray);

// The largest finite coordinate of the scene.
double scene_magnitude(const Scene& scene);

// A t tolerance: the float spacing of the coordinates involved, in units of the ray's direction
// length, plus a few ulps of t itself (reached at `t`).
double t_tolerance(const RayRecord& ray, double scene_magnitude, double t);

// Checks every ray; returns the number that disagree and fills up to `max_reports` messages.
size_t count_disagreements(const Scene& scene, const std::vector<RayRecord>& rays, const std::vector<HitRecord>& hits,
                           std::vector<std::string>* reports, size_t max_reports = 5);

// Traces `rays` through `tree` and fails the running test where a hit disagrees with brute
// force (reporting the first few); returns the hits.
std::vector<HitRecord> trace_checked(const Scene& scene, const KdTree& tree, const std::vector<RayRecord>& rays,
                                     const TraceOptions& options = {});

}  // namespace kdray::test
