// Per-vertex tangent frames for normal maps (formats/kdscene.md, "Tangents"), the same for
// every importer.
#pragma once

#include <kdray/scene.h>

namespace kdray {

// Whether a scene needs tangents: some material has a normal map and the mesh has UVs.
bool scene_needs_tangents(const Scene& scene);

// Gives every vertex a tangent when the scene needs them and drops them when it does not.
// Tangents the asset authored (w = +1 or -1) are kept; vertices whose w is 0, or all of them
// when scene.tangents is empty, get MikkTSpace-style ones: each triangle's dp/du and dp/dv
// (from its UVs) are projected into the plane of the vertex normal and summed, weighted by the
// corner angle, over the triangles around the vertex; the tangent is the normalised sum of the
// dp/du, w the side of cross(n, t) that the summed dp/dv lies on. Triangles of zero UV area
// do not contribute; a vertex left without a direction gets any unit tangent perpendicular to
// n. A vertex shared by triangles whose UVs are mirrored against each other (opposite signs of
// the UV area) is split in two, as MikkTSpace does, so that each copy has one handedness. The
// normal is the vertex normal, or the area-weighted one of the triangles around it in a
// scene without normals.
void complete_tangents(Scene& scene);

// The same tangents on the scene's vertices as they are, for a scene that has none on file (a
// file older than tangents, whose hashes and k-d tree describe its vertices, or a scene made in
// memory): nothing is split, so a vertex shared by mirrored triangles takes the handedness of
// most of the angle around it. Empty when the scene does not need tangents.
std::vector<Tangent> tangents_on_vertices(const Scene& scene);

}  // namespace kdray
