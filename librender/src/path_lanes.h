// The host's path tracer 8 paths at a time in AVX2 lanes (for any scene whose arrays the gathers
// reach, apply() below), with up to kGroups groups of eight paths in flight per thread. Each step
// traces the closest hits of all live paths, then shades them a group at a time with
// pt_path_shade's parts: the hit point and its smooth normal, emission with MIS, Russian roulette,
// next-event estimation (the light kind picked in lanes; the triangle lights in lanes; the
// environment's and punctual lights' samples lane by lane, their shadow rays in lanes) and the
// BSDF sample, for every material but alpha-tested ones and textured emitters (Lambertian, glTF
// metallic-roughness, rough conductor, mirror, glass; textures looked up lane by lane). Those, and
// a ray that leaves the scene towards an environment, are shaded by pt_path_shade lane by lane,
// and their paths stay in their lanes. Then the shadow rays of all groups are traced; a path that
// ends is added to the film and its lane takes the next path, and the live paths are moved into
// the lowest groups. A step's rays are traced as packets of eight (kdray::trace_packet) in an order
// sorted by their origin's cell and direction's cell (RayOrder): paths' later rays run apart, and
// one at a time a packet of eight arbitrary ones pays for the union of their nodes, but among a
// couple of thousand rays sorted so, eight neighbours run close together. Paths take their first
// segment eight at a time before they take a lane (FirstSegments): the camera rays and shadow
// rays of eight samples in a row run close together already, and are traced as one packet each.
// The shading in lanes calls the device code's lane functions (kernels/kd_lane.h) with 8-float
// lanes (lane8.h), so each lane computes what pt_path_shade computes for its path, bit for bit;
// a packet's hits are one ray at a time's; and the film is the scalar path tracer's and the
// kernel's (tests/render/cpu_integrator.h compares them). A path's start is computed in lanes for
// the eight paths begun together (begin_in_lanes); the film sums stay scalar, lane by lane.
//
// Compiled into the x86-64-v3 build of render_host_pixels.cpp, inside its namespace after the
// device code, whose functions it calls.
#pragma once

#include "lane8.h"

namespace path_lanes {

using namespace lane8;

// Whether the lanes render this pass: when no float array is longer than the gathers' 32-bit signed
// indices reach (`gathered_floats`: the longest, in floats or indices).
inline bool apply(size_t gathered_floats) { return gathered_floats <= size_t{0x7fffffff}; }

// The state of the lanes' paths (PtPath's), one array element per lane: what shading reads in
// lanes as arrays of 8, the rest (pixel, sample, first-hit AOVs) in a PtPath per lane.
struct Paths {
  alignas(32) float ox[kLanes], oy[kLanes], oz[kLanes], dx[kLanes], dy[kLanes], dz[kLanes];
  alignas(32) float tx[kLanes], ty[kLanes], tz[kLanes];  // throughput
  alignas(32) float rx[kLanes], ry[kLanes], rz[kLanes];  // radiance
  alignas(32) float sox[kLanes], soy[kLanes], soz[kLanes], ssx[kLanes], ssy[kLanes], ssz[kLanes];
  alignas(32) float scx[kLanes], scy[kLanes], scz[kLanes];
  alignas(32) float bsdf_pdf[kLanes];
  alignas(32) int32_t bounce[kLanes];
  alignas(32) uint32_t sample_hash[kLanes], sample[kLanes];  // the path's, as in its PtPath
  PtPath path[kLanes];  // what is read one lane at a time: pixel, sample, its hash, first-hit AOVs
  int alive = 0, shadow = 0;  // bit per lane
};

// The words shade() gathers of a HitRecord: t, triangle, u and v.
static_assert(sizeof(HitRecord) == 16 && KD_OFFSETOF(HitRecord, t) == 0 && KD_OFFSETOF(HitRecord, triangle) == 4 &&
                  KD_OFFSETOF(HitRecord, u) == 8 && KD_OFFSETOF(HitRecord, v) == 12,
              "HitRecord: 4 words t, triangle, u, v");
// A PtMaterial's words (4-byte members only, kernels/pt_types.h), and the word of a member.
constexpr int kMaterialWords = sizeof(PtMaterial) / 4;
#define PATH_LANES_MATERIAL_WORD(member) (KD_OFFSETOF(PtMaterial, member) / 4)

// The lanes' float3 from, and to, its coordinates' arrays.
inline Float8x3 load3(const float* x, const float* y, const float* z) { return {load(x), load(y), load(z)}; }
inline void store3(float* x, float* y, float* z, Float8x3 v) {
  store(x, v.x);
  store(y, v.y);
  store(z, v.z);
}
// The same, in the lanes of the mask only.
inline void store3(Mask8 lanes, float* x, float* y, float* z, Float8x3 v) {
  store3(x, y, z, kd_select(lanes, v, load3(x, y, z)));
}
// Three consecutive floats of each lane's record (`words` floats each, numbered by `record`) from
// float `first` on, in the lanes of the mask.
inline Float8x3 gather3(const float* base, Int8 record, int words, int first, Mask8 lanes) {
  const Int8 index = record * words;
  return {gather(base + first, index, lanes), gather(base + first + 1, index, lanes),
          gather(base + first + 2, index, lanes)};
}

// pt_bits_to_unit of each lane's bits.
inline Float8 bits_to_unit(UintVector bits) {
  return Float8((FloatVector)_mm256_cvtepi32_ps((__m256i)(bits >> 8))) * (1.0f / 16777216.0f);
}

// The 8x8 matrix of floats in `rows` transposed in place: row r becomes word r of every row.
inline void transpose(__m256 rows[kLanes]) {
  __m256 pair[kLanes], quad[kLanes];
  for (int r = 0; r < kLanes; r += 2) {
    pair[r] = _mm256_unpacklo_ps(rows[r], rows[r + 1]);
    pair[r + 1] = _mm256_unpackhi_ps(rows[r], rows[r + 1]);
  }
  for (int r = 0; r < kLanes; r += 4) {
    quad[r] = _mm256_shuffle_ps(pair[r], pair[r + 2], 0x44);
    quad[r + 1] = _mm256_shuffle_ps(pair[r], pair[r + 2], 0xee);
    quad[r + 2] = _mm256_shuffle_ps(pair[r + 1], pair[r + 3], 0x44);
    quad[r + 3] = _mm256_shuffle_ps(pair[r + 1], pair[r + 3], 0xee);
  }
  // word w: the low halves of quad[w] and quad[w + 4] for w < 4, their high halves for w + 4
  for (int w = 0; w < 4; ++w) {
    rows[w] = _mm256_permute2f128_ps(quad[w], quad[w + 4], 0x20);
    rows[w + 4] = _mm256_permute2f128_ps(quad[w], quad[w + 4], 0x31);
  }
}

// The words of the 8 lanes' hits (t, triangle, u, v), in the lanes of the mask (0 in the others):
// two records a load, turned into lanes by a transpose in each half.
inline void hit_lanes(const HitRecord* hits, Mask8 lanes, Float8* t, Int8* triangle, Float8* u, Float8* v) {
  const float* words = reinterpret_cast<const float*>(hits);
  // records l and l + 4 in one register
  __m256 row[4];
  for (int l = 0; l < 4; ++l) {
    const __m256 low = _mm256_castps128_ps256(_mm_loadu_ps(words + 4 * l));
    row[l] = _mm256_insertf128_ps(low, _mm_loadu_ps(words + 4 * (l + 4)), 1);
  }
  const __m256 t_triangle01 = _mm256_unpacklo_ps(row[0], row[1]), u_v01 = _mm256_unpackhi_ps(row[0], row[1]);
  const __m256 t_triangle23 = _mm256_unpacklo_ps(row[2], row[3]), u_v23 = _mm256_unpackhi_ps(row[2], row[3]);
  auto in_lanes = [&](__m256 x) { return (FloatVector)_mm256_and_ps(x, (__m256)lanes.m); };
  *t = Float8(in_lanes(_mm256_shuffle_ps(t_triangle01, t_triangle23, 0x44)));
  *triangle = Int8((IntVector)in_lanes(_mm256_shuffle_ps(t_triangle01, t_triangle23, 0xee)));
  *u = Float8(in_lanes(_mm256_shuffle_ps(u_v01, u_v23, 0x44)));
  *v = Float8(in_lanes(_mm256_shuffle_ps(u_v01, u_v23, 0xee)));
}

// The three corners (pt_corner) of each lane's triangle, in the lanes of the mask (0 in the
// others): each lane's first 8 floats read in one load and turned into lanes by a transpose, the
// ninth gathered. Nine gathers, a load per lane each, cost more than the loads and shuffles.
inline void triangle_corners(const float* triangle_vertices, Int8 triangle, Mask8 lanes, Float8x3* p0, Float8x3* p1,
                             Float8x3* p2) {
  static_assert(KD_TRIANGLE_FLOATS == 9, "a triangle: three corners of three floats");
  alignas(32) int32_t record[kLanes];
  store(record, triangle * (int32_t)KD_TRIANGLE_FLOATS);
  const int reading = bits(lanes);
  __m256 word[kLanes];  // each lane's first 8 floats, then word w of every lane
  for (int l = 0; l < kLanes; ++l)
    word[l] = reading >> l & 1 ? _mm256_loadu_ps(triangle_vertices + record[l]) : _mm256_setzero_ps();
  transpose(word);
  auto lanes_of_word = [&](int w) { return Float8((FloatVector)word[w]); };
  *p0 = {lanes_of_word(0), lanes_of_word(1), lanes_of_word(2)};
  *p1 = {lanes_of_word(3), lanes_of_word(4), lanes_of_word(5)};
  *p2 = {lanes_of_word(6), lanes_of_word(7), gather(triangle_vertices + 8, load(record), lanes)};
}

// The lane's float3 of a lanes' float3.
inline float3 lane(const Float8x3& v, int l) { return KD_FLOAT3(v.x[l], v.y[l], v.z[l]); }

// Lane l's shadow ray, if pt_next_event_any or pt_path_shade has set one up in its PtPath.
inline void take_shadow_ray(Paths& ps, int l) {
  const PtPath& path = ps.path[l];
  if (!path.shadow_pending) return;
  ps.shadow |= 1 << l;
  ps.sox[l] = path.shadow_origin.x, ps.soy[l] = path.shadow_origin.y, ps.soz[l] = path.shadow_origin.z;
  ps.ssx[l] = path.shadow_span.x, ps.ssy[l] = path.shadow_span.y, ps.ssz[l] = path.shadow_span.z;
  ps.scx[l] = path.shadow_contribution.x, ps.scy[l] = path.shadow_contribution.y;
  ps.scz[l] = path.shadow_contribution.z;
}

// pt_path_shade itself for the lanes set in `lanes`, one after another: the lanes' state copied
// into their PtPath, shaded, and copied back by shaded_lane_by_lane once shade() has stored its own.
inline void shade_lane_by_lane(Paths& ps, int lanes, const PtSceneData* scene, const PtRenderParams* params,
                               const HitRecord* hits) {
  for (int l = 0; l < kLanes; ++l) {
    if (!(lanes >> l & 1)) continue;
    PtPath& path = ps.path[l];
    path.origin = KD_FLOAT3(ps.ox[l], ps.oy[l], ps.oz[l]);
    path.direction = KD_FLOAT3(ps.dx[l], ps.dy[l], ps.dz[l]);
    path.throughput = KD_FLOAT3(ps.tx[l], ps.ty[l], ps.tz[l]);
    path.radiance = KD_FLOAT3(ps.rx[l], ps.ry[l], ps.rz[l]);
    path.bsdf_pdf = ps.bsdf_pdf[l];
    path.bounce = (uint32_t)ps.bounce[l];
    path.alive = 1;
    pt_path_shade(&path, scene, params, hits[l]);
  }
}
inline void shaded_lane_by_lane(Paths& ps, int lanes) {
  for (int l = 0; l < kLanes; ++l) {
    if (!(lanes >> l & 1)) continue;
    const PtPath& path = ps.path[l];
    ps.ox[l] = path.origin.x, ps.oy[l] = path.origin.y, ps.oz[l] = path.origin.z;
    ps.dx[l] = path.direction.x, ps.dy[l] = path.direction.y, ps.dz[l] = path.direction.z;
    ps.tx[l] = path.throughput.x, ps.ty[l] = path.throughput.y, ps.tz[l] = path.throughput.z;
    ps.rx[l] = path.radiance.x, ps.ry[l] = path.radiance.y, ps.rz[l] = path.radiance.z;
    ps.bsdf_pdf[l] = path.bsdf_pdf;
    ps.bounce[l] = (int32_t)path.bounce;
    ps.alive = (ps.alive & ~(1 << l)) | (path.alive ? 1 << l : 0);
    take_shadow_ray(ps, l);
  }
}

// The BSDFs of the surfaces the lanes shade: the lanes of each kind (Lambertian where no kind's
// mask is set), their colour and what the kinds read of their materials.
struct LaneBsdf {
  Mask8 metal_rough, conductor, mirror, glass;  // the lanes of each kind; Lambertian where none
  Mask8 entering;                               // wo on the front side (glass: from outside)
  Float8x3 color;
  Float8 roughness = 0.0f, ior = 0.0f, metallic = 0.0f;
  Mask8 delta() const { return mirror | glass; }
};

// pt_apply_textures for the lanes set in `lanes`, one after another: each lane's material and
// hit (triangle, barycentrics u and v, geometric normal ng and its facing form), its BSDF's colour,
// roughness and metallic and its shading normal n textured in place.
inline void apply_textures_lane_by_lane(int lanes, const PtSceneData* scene, Int8 material, Int8 triangle, Float8 u,
                                        Float8 v, Float8x3 ng, Float8x3 ng_facing, LaneBsdf* bsdf, Float8x3* n) {
  alignas(32) float cx[kLanes], cy[kLanes], cz[kLanes], nx[kLanes], ny[kLanes], nz[kLanes];
  alignas(32) float roughness[kLanes], metallic[kLanes];
  store3(cx, cy, cz, bsdf->color);
  store3(nx, ny, nz, *n);
  store(roughness, bsdf->roughness);
  store(metallic, bsdf->metallic);
  for (int l = 0; l < kLanes; ++l) {
    if (!(lanes >> l & 1)) continue;
    PtMaterial m = scene->materials[material.v[l]];
    float3 color = KD_FLOAT3(cx[l], cy[l], cz[l]), normal = KD_FLOAT3(nx[l], ny[l], nz[l]);
    pt_apply_textures(&m, &color, &normal, lane(ng, l), lane(ng_facing, l), scene->uvs, scene->tangents,
                      scene->textures, scene->texels, scene->indices + 3 * triangle.v[l], u[l], v[l]);
    cx[l] = color.x, cy[l] = color.y, cz[l] = color.z, nx[l] = normal.x, ny[l] = normal.y, nz[l] = normal.z;
    roughness[l] = m.roughness, metallic[l] = m.metallic;
  }
  bsdf->color = load3(cx, cy, cz);
  *n = load3(nx, ny, nz);
  bsdf->roughness = load(roughness);
  bsdf->metallic = load(metallic);
}

// pt_bsdf_eval for the lanes' BSDFs: f * cos(wi), and the pdf of sampling wi (the delta lobes'
// lanes take no part: next-event estimation skips them).
inline Float8x3 bsdf_eval(const LaneBsdf& m, Float8x3 n, Float8x3 wo, Float8x3 wi, Float8* pdf) {
  const Float8 cos_i = kd_dot(n, wi);
  *pdf = kd_select(cos_i <= 0.0f, Float8(0.0f), cos_i * PT_INV_PI);
  Float8x3 f_cos = kd_select(cos_i <= 0.0f, Float8x3{}, m.color * (cos_i * PT_INV_PI));
  if (kd_any(m.metal_rough)) {
    Float8 lobe_pdf;
    const Float8x3 lobe = pt_metal_rough_eval(m.roughness, m.ior, m.metallic, m.color, n, wo, wi, &lobe_pdf);
    *pdf = kd_select(m.metal_rough, lobe_pdf, *pdf);
    f_cos = kd_select(m.metal_rough, lobe, f_cos);
  }
  if (kd_any(m.conductor)) {
    Float8 lobe_pdf;
    const Float8x3 lobe = pt_ggx_eval(m.color, m.roughness, n, wo, wi, &lobe_pdf);
    *pdf = kd_select(m.conductor, lobe_pdf, *pdf);
    f_cos = kd_select(m.conductor, lobe, f_cos);
  }
  return f_cos;
}

// pt_bsdf_sample for the lanes' BSDFs: the direction, with its pdf and weight, and the lanes whose
// direction passes through the surface.
inline Float8x3 bsdf_sample(const LaneBsdf& m, Float8x3 n, Float8x3 wo, Float8 u1, Float8 u2, Float8 u_lobe,
                            Float8* pdf, Float8x3* weight, Mask8* transmits) {
  Float8x3 wi = pt_sample_cosine(n, u1, u2);
  *pdf = fmax(kd_dot(n, wi), 0.0f) * PT_INV_PI;
  *weight = kd_select(*pdf > 0.0f, m.color, Float8x3{});
  *transmits = Mask8{};
  // a glossy lobe's lanes: the sample's pdf and weight f * cos / pdf from the lobe's evaluation
  auto take_glossy = [&](Mask8 lanes, Float8x3 f_cos, Float8 lobe_pdf) {
    *pdf = kd_select(lanes, lobe_pdf, *pdf);
    *weight = kd_select(lanes, kd_select(lobe_pdf > 0.0f, f_cos / lobe_pdf, Float8x3{}), *weight);
  };
  Float8 lobe_pdf;
  if (kd_any(m.metal_rough)) {
    const Mask8 ggx = m.metal_rough & (u_lobe < pt_gltf_ggx_probability(m.metallic, m.ior, m.color, kd_dot(n, wo)));
    if (kd_any(ggx)) wi = kd_select(ggx, pt_ggx_sample_wi(m.roughness, n, wo, u1, u2), wi);
    const Float8x3 f_cos = pt_metal_rough_eval(m.roughness, m.ior, m.metallic, m.color, n, wo, wi, &lobe_pdf);
    take_glossy(m.metal_rough, f_cos, lobe_pdf);
  }
  if (kd_any(m.conductor)) {
    wi = kd_select(m.conductor, pt_ggx_sample_wi(m.roughness, n, wo, u1, u2), wi);
    const Float8x3 f_cos = pt_ggx_eval(m.color, m.roughness, n, wo, wi, &lobe_pdf);
    take_glossy(m.conductor, f_cos, lobe_pdf);
  }
  if (kd_any(m.mirror)) {
    wi = kd_select(m.mirror, 2.0f * kd_dot(wo, n) * n - wo, wi);
    *weight = kd_select(m.mirror, m.color, *weight);
  }
  if (kd_any(m.glass)) {
    Float8 eta, cos_i, cos_t;
    const Float8 reflectance = pt_glass_reflectance(m.ior, m.entering, n, wo, &eta, &cos_i, &cos_t);
    const Mask8 reflects = m.glass & (u1 < reflectance);
    *transmits = m.glass & !reflects;
    wi = kd_select(reflects, 2.0f * cos_i * n - wo, wi);
    *weight = kd_select(reflects, Float8x3{1.0f, 1.0f, 1.0f}, *weight);
    if (kd_any(*transmits)) {
      wi = kd_select(*transmits, pt_glass_refraction(eta, cos_i, cos_t, n, wo), wi);
      // radiance is scaled by (eta_i/eta_t)^2 across the boundary
      *weight = kd_select(*transmits, m.color * (eta * eta), *weight);
    }
  }
  *pdf = kd_select(m.delta(), Float8(0.0f), *pdf);
  return wi;
}

// pt_pick_light for the lanes of `lanes`: the triangles picked, and each lane's u made its
// position inside its entry's cdf interval. Each lane starts from the guide's range and bisects
// step for step as pt_pick_light does (so it ends on the same entry whatever the cdf holds), the
// entries read by gathers: the search lane by lane mispredicted its branch about every other step.
inline Int8 pick_lights(const PtLight* lights, const uint32_t* guide, uint32_t count, Mask8 lanes, Float8* u) {
  static_assert(sizeof(PtLight) == 8 && KD_OFFSETOF(PtLight, triangle) == 0 && KD_OFFSETOF(PtLight, cdf) == 4,
                "PtLight: 2 words triangle, cdf");
  const float* cdf = reinterpret_cast<const float*>(lights) + 1;
  IntVector lo = IntVector{}, hi = IntVector{} + (int32_t)(count - 1);
  // A guide of one cell spans the whole cdf (both searches return the same entry from any range
  // that holds it), so only a larger one is read.
  const uint32_t cells = pt_cdf_guide_size(count);
  if (cells > 1) {
    // pt_cdf_guide_cell lane by lane: u * G is exact, and u >= 0 truncates alike signed or not
    const Int8 cell = kd_lane_to_int(*u * Float8((float)cells));
    const Int8 k = Int8(cell.v < (int32_t)cells ? cell.v : IntVector{} + (int32_t)(cells - 1));
    const int32_t* words = reinterpret_cast<const int32_t*>(guide);
    lo = gather(words, k, lanes).v;
    hi = gather(words, k + 1, lanes).v;
  }
  for (;;) {
    const Mask8 searching = lanes & Mask8{lo < hi};
    if (!kd_any(searching)) break;
    const IntVector mid = (IntVector)((UintVector)(lo + hi) >> 1);
    const IntVector below = (*u < gather(cdf, Int8(mid * 2), searching)).m;
    hi = searching.m & below ? mid : hi;
    lo = searching.m & ~below ? mid + 1 : lo;
  }
  const Mask8 past_first = lanes & Mask8{lo > 0};
  const Float8 below = gather(cdf, Int8((lo - 1) * 2), past_first);  // 0 in the first entry's lanes
  const Float8 width = gather(cdf, Int8(lo * 2), lanes) - below;
  *u = kd_select(width > 0.0f, fmin((*u - below) / width, 0x1.fffffep-1f), Float8(0.0f));
  return gather(reinterpret_cast<const int32_t*>(lights), Int8(lo * 2), lanes);
}

// pt_next_event for the lanes of `active`, shading point p (normal n, facing geometric normal
// ng_facing, BSDF m seen from wo, throughput beta), with the bounce's light-pick and light values:
// the shadow rays into ps.
inline void next_event_on_triangles(Paths& ps, const PtSceneData* scene, const PtRenderParams* params, Mask8 active,
                                    Float8 light_pick, Float8 light_v, Float8x3 p, Float8x3 n, Float8x3 ng_facing,
                                    Float8x3 wo, const LaneBsdf& m, Float8x3 beta) {
  Float8 light_u_picked = light_pick;
  const Int8 light = pick_lights(scene->lights, scene->light_guide, params->light_count, active, &light_u_picked);
  Mask8 ok = active;
  Float8x3 q0, q1, q2;
  triangle_corners(scene->triangle_vertices, light, ok, &q0, &q1, &q2);
  const Float8x3 scaled_normal = kd_cross(q1 - q0, q2 - q0);
  const Float8 twice_area = kd_length(scaled_normal);
  const Float8x3 light_normal = scaled_normal / twice_area;
  Float8x3 a, b, c;
  const Float8 solid_angle = pt_spherical_solid_angle(p, q0, q1, q2, &a, &b, &c);
  const Mask8 spherical = solid_angle > 0.0f;
  Float8x3 wi = {};
  Float8 dist2 = 0.0f;
  if (kd_any(spherical)) {
    wi = pt_sample_spherical_triangle(a, b, c, solid_angle, light_u_picked, light_v);
    const Float8 distance = kd_dot(q0 - p, light_normal) / kd_dot(wi, light_normal);
    ok = ok & ((!spherical) | ((distance > 0.0f) & (distance < INFINITY)));
    dist2 = distance * distance;
  }
  if (kd_any(ok & !spherical)) {
    Float8 b1, b2;
    pt_sample_triangle(light_u_picked, light_v, &b1, &b2);
    const Float8x3 to_light = q0 + b1 * (q1 - q0) + b2 * (q2 - q0) - p;
    const Float8 area_dist2 = kd_dot(to_light, to_light);
    ok = ok & (spherical | (area_dist2 > 0.0f));
    wi = kd_select(spherical, wi, to_light * kd_rsqrt(area_dist2));
    dist2 = kd_select(spherical, dist2, area_dist2);
  }
  const Float8 cos_light = -kd_dot(light_normal, wi);
  ok = ok & !(cos_light <= 0.0f);
  Float8 pdf;
  const Float8x3 f_cos = bsdf_eval(m, n, wo, wi, &pdf);
  ok = ok & !(pdf <= 0.0f) & !(kd_dot(wi, ng_facing) <= 0.0f);
  if (!kd_any(ok)) return;
  ps.shadow |= bits(ok);
  const Int8 light_material = gather(reinterpret_cast<const int32_t*>(scene->material_ids), light, ok);
  const Float8x3 emission = gather3(reinterpret_cast<const float*>(scene->materials), light_material, kMaterialWords,
                                    PATH_LANES_MATERIAL_WORD(emission), ok);
  const Float8 pick_per_area = params->select_triangles * pt_luminance(emission) * params->light_area_pdf_scale;
  const Float8 light_pdf = pt_triangle_light_pdf(pick_per_area, 0.5f * twice_area, solid_angle, dist2, cos_light);
  const Float8 weight = pt_mis_light(params, light_pdf, pdf);
  const Float8x3 shadow_origin = pt_offset_origin(p, ng_facing);
  const Float8x3 target = pt_offset_origin(p + sqrt(dist2) * wi, light_normal);
  store3(ok, ps.sox, ps.soy, ps.soz, shadow_origin);
  store3(ok, ps.ssx, ps.ssy, ps.ssz, target - shadow_origin);
  store3(ok, ps.scx, ps.scy, ps.scz, beta * f_cos * emission * (weight / light_pdf));
}

// The rest of pt_next_event_any for the lanes of `others`, whose light kind number u (past the
// triangle lights' share) picks the environment or a punctual light: the light samples lane by
// lane (pt_sample_other_light, with the environment's pair of values u_env0, u_env1), then
// pt_shadow_towards in lanes.
inline void next_event_on_other_lights(Paths& ps, const PtSceneData* scene, const PtRenderParams* params, Mask8 others,
                                       Float8 u, Float8 u_env0, Float8 u_env1, Float8x3 p, Float8x3 n,
                                       Float8x3 ng_facing, Float8x3 wo, const LaneBsdf& m, Float8x3 beta) {
  alignas(32) float wx[kLanes] = {}, wy[kLanes] = {}, wz[kLanes] = {}, distance[kLanes] = {};
  alignas(32) float vx[kLanes] = {}, vy[kLanes] = {}, vz[kLanes] = {}, light_pdf[kLanes] = {};
  int drawn = 0;
  const int sampling = bits(others);
  for (int l = 0; l < kLanes; ++l) {
    PtLightSample ls;
    if (!(sampling >> l & 1)) continue;
    if (!pt_sample_other_light(&ls, scene, params, lane(p, l), u[l], KD_FLOAT2(u_env0[l], u_env1[l]))) continue;
    drawn |= 1 << l;
    wx[l] = ls.wi.x, wy[l] = ls.wi.y, wz[l] = ls.wi.z, distance[l] = ls.distance;
    vx[l] = ls.value.x, vy[l] = ls.value.y, vz[l] = ls.value.z, light_pdf[l] = ls.pdf;
  }
  const Float8x3 wi = load3(wx, wy, wz), value = load3(vx, vy, vz);
  Mask8 ok = lanes_of(drawn) & !(kd_dot(wi, ng_facing) <= 0.0f) & !(pt_max3(value) <= 0.0f);
  if (!kd_any(ok)) return;
  Float8 bsdf_pdf;
  const Float8x3 f_cos = bsdf_eval(m, n, wo, wi, &bsdf_pdf);
  ok = ok & !(pt_max3(f_cos) <= 0.0f);
  if (!kd_any(ok)) return;
  const Float8 pdf = load(light_pdf);
  const Float8 weight = kd_select(pdf > 0.0f, pt_mis_light(params, pdf, bsdf_pdf), Float8(1.0f));
  store3(ok, ps.sox, ps.soy, ps.soz, pt_offset_origin(p, ng_facing));
  store3(ok, ps.ssx, ps.ssy, ps.ssz, wi * load(distance));
  store3(ok, ps.scx, ps.scy, ps.scz, beta * f_cos * value * weight);
  ps.shadow |= bits(ok);
}

// pt_next_event_any for the lanes set in `lanes`, one after another (any light: the environment,
// punctual lights, textured emission): the shading point as next_event_on_triangles takes it,
// with the bounce, each lane's material number and BSDF (its textured values).
inline void next_event_lane_by_lane(Paths& ps, int lanes, const PtSceneData* scene, const PtRenderParams* params,
                                    Int8 material, Int8 bounce, Float8x3 p, Float8x3 n, Float8x3 ng_facing,
                                    Float8x3 wo, const LaneBsdf& bsdf, Float8x3 beta) {
  const int metal_rough = bits(bsdf.metal_rough);
  for (int l = 0; l < kLanes; ++l) {
    if (!(lanes >> l & 1)) continue;
    PtPath& path = ps.path[l];
    path.bounce = (uint32_t)bounce.v[l];
    path.throughput = lane(beta, l);
    path.shadow_pending = 0;
    const PtBounceSamples samples = pt_path_samples(&path, params);
    PtMaterial m = scene->materials[material.v[l]];
    if (metal_rough >> l & 1) m.roughness = bsdf.roughness[l], m.metallic = bsdf.metallic[l];  // as textured
    pt_next_event_any(&path, scene, params, &samples, &m, lane(bsdf.color, l), lane(p, l), lane(n, l),
                      lane(ng_facing, l), lane(wo, l));
    take_shadow_ray(ps, l);
  }
}

// pt_path_shade for the live lanes, each with its hit: in lanes, but lane by lane for alpha-tested
// surfaces, textured emitters and rays that leave the scene towards an environment. The lanes
// still alive after it, and those with a shadow ray to trace, are left in ps.alive and ps.shadow.
inline void shade(Paths& ps, const PtSceneData* scene, const PtRenderParams* params, const HitRecord* hits) {
  ps.shadow = 0;
  const Mask8 alive = lanes_of(ps.alive);
  Float8 t, u, v;
  Int8 tri;
  hit_lanes(hits, alive, &t, &tri, &u, &v);
  Mask8 active = alive & (tri != (int32_t)KD_NO_HIT);
  // a ray that leaves the scene sees the environment, lane by lane
  int by_lane = PT_USES(params, PT_FEATURE_ENVIRONMENT) ? bits(alive & !active) : 0;
  const Int8 material = gather(reinterpret_cast<const int32_t*>(scene->material_ids), tri, active);
  const float* material_floats = reinterpret_cast<const float*>(scene->materials);
  const int32_t* material_words = reinterpret_cast<const int32_t*>(scene->materials);
  const Int8 words = material * kMaterialWords;  // each lane's PtMaterial
  const Int8 type = gather(material_words + PATH_LANES_MATERIAL_WORD(type), words, active);
  // every kind of material (an unknown type is Lambertian in lanes as in pt_bsdf_sample), if it is
  // opaque (pt_alpha_passes lets no ray through) and has no emission texture (pt_textured_emission)
  Mask8 in_lanes = active;
  if (PT_USES(params, PT_FEATURE_ALPHA)) {
    in_lanes = in_lanes & (gather(material_floats + PATH_LANES_MATERIAL_WORD(alpha_cutoff), words, active) == 0.0f);
  }
  if (PT_USES(params, PT_FEATURE_EMISSIVE_TEXTURE)) {
    in_lanes = in_lanes & !(gather(material_words + PATH_LANES_MATERIAL_WORD(emissive_texture), words, active) >= 0);
  }
  by_lane |= bits(active & !in_lanes);
  shade_lane_by_lane(ps, by_lane, scene, params, hits);
  active = active & in_lanes;
  if (!kd_any(active)) {
    ps.alive = 0;
    shaded_lane_by_lane(ps, by_lane);
    return;
  }
  Float8x3 p0, p1, p2;
  triangle_corners(scene->triangle_vertices, tri, active, &p0, &p1, &p2);
  const Float8 w0 = 1.0f - u - v;
  const Float8x3 p = w0 * p0 + u * p1 + v * p2;
  const Float8x3 origin = load3(ps.ox, ps.oy, ps.oz);
  const Float8x3 wo = -load3(ps.dx, ps.dy, ps.dz);
  const Float8x3 ng = kd_normalize(kd_cross(p1 - p0, p2 - p0));
  const Mask8 front = kd_dot(ng, wo) > 0.0f;
  const Float8x3 ng_facing = kd_select(front, ng, -ng);
  Float8x3 n = ng_facing;
  if (PT_USES(params, PT_FEATURE_NORMALS)) {
    const int32_t* indices = reinterpret_cast<const int32_t*>(scene->indices);
    const Int8 corner = tri * 3;
    const Float8x3 ns = w0 * gather3(scene->normals, gather(indices, corner, active), 3, 0, active) +
                        u * gather3(scene->normals, gather(indices, corner + 1, active), 3, 0, active) +
                        v * gather3(scene->normals, gather(indices, corner + 2, active), 3, 0, active);
    const Float8x3 unit = kd_normalize(ns);
    n = kd_select(kd_dot(ns, ns) > 0.0f, kd_select(kd_dot(unit, ng_facing) < 0.0f, -unit, unit), ng_facing);
  }
  LaneBsdf bsdf;
  bsdf.color = gather3(material_floats, material, kMaterialWords, PATH_LANES_MATERIAL_WORD(base_color), active);
  bsdf.metal_rough = active & (type == (int32_t)PT_METALLIC_ROUGHNESS);
  bsdf.conductor = active & (type == (int32_t)PT_ROUGH_CONDUCTOR);
  bsdf.mirror = active & (type == (int32_t)PT_MIRROR);
  bsdf.glass = active & (type == (int32_t)PT_DIELECTRIC);
  bsdf.entering = front;
  const Mask8 rough = bsdf.metal_rough | bsdf.conductor, refracting = bsdf.metal_rough | bsdf.glass;
  if (kd_any(rough)) bsdf.roughness = gather(material_floats + PATH_LANES_MATERIAL_WORD(roughness), words, rough);
  if (kd_any(refracting)) bsdf.ior = gather(material_floats + PATH_LANES_MATERIAL_WORD(ior), words, refracting);
  if (kd_any(bsdf.metal_rough)) {
    bsdf.metallic = gather(material_floats + PATH_LANES_MATERIAL_WORD(metallic), words, bsdf.metal_rough);
  }
  if (PT_USES(params, PT_FEATURE_TEXTURES)) {
    Mask8 textured = {};
    for (size_t texture : {PATH_LANES_MATERIAL_WORD(texture), PATH_LANES_MATERIAL_WORD(metal_rough_texture),
                           PATH_LANES_MATERIAL_WORD(normal_texture)})
      textured = textured | (gather(material_words + texture, words, active) >= 0);
    textured = textured & active;
    if (kd_any(textured)) {
      apply_textures_lane_by_lane(bits(textured), scene, material, tri, u, v, ng, ng_facing, &bsdf, &n);
    }
  }
  const Int8 bounce = load(ps.bounce);
  const int first_hits = bits(active & (bounce == 0));
  for (int l = 0; l < kLanes; ++l)
    if (first_hits >> l & 1) {
      ps.path[l].albedo = lane(bsdf.color, l);
      ps.path[l].normal = KD_FLOAT3(n.x[l], n.y[l], n.z[l]);
      ps.path[l].depth = t[l];
    }
  Float8x3 beta = load3(ps.tx, ps.ty, ps.tz);
  Float8x3 radiance = load3(ps.rx, ps.ry, ps.rz);
  const Float8 bsdf_pdf = load(ps.bsdf_pdf);
  const Mask8 emissive = active & (type == (int32_t)PT_EMISSIVE) & front;
  if (PT_USES(params, PT_FEATURE_EMISSION) && kd_any(emissive)) {
    const Float8x3 emission =
        gather3(material_floats, material, kMaterialWords, PATH_LANES_MATERIAL_WORD(emission), emissive);
    Float8 weight = 1.0f;
    const Mask8 mis = emissive & (bsdf_pdf > 0.0f);
    if (kd_any(mis)) {
      Float8x3 a, b, c;
      const Float8 solid_angle = pt_spherical_solid_angle(origin, p0, p1, p2, &a, &b, &c);
      const Float8 pick_per_area = params->select_triangles * pt_luminance(emission) * params->light_area_pdf_scale;
      const Float8 light_pdf = pt_triangle_light_pdf(pick_per_area, 0.5f * kd_length(kd_cross(p1 - p0, p2 - p0)),
                                                     solid_angle, t * t, kd_dot(ng, wo));
      weight = kd_select(mis, pt_mis_bsdf(params, bsdf_pdf, light_pdf), weight);
    }
    radiance = kd_select(emissive, radiance + beta * emission * weight, radiance);
  }
  active = active & (bounce <= (int32_t)(params->max_bounces < 0x7fffffffu ? params->max_bounces : 0x7fffffffu));
  // the bounce's sample values (pt_path_samples), a value of the 8 paths at a time
  const UintVector sample_hash = (UintVector)load(ps.sample_hash).v;
  const UintVector first_dimension = (UintVector)(bounce * (int32_t)PT_DIMS_PER_BOUNCE + (int32_t)PT_BOUNCE_DIMS(0)).v;
  UintVector reversed_index = (UintVector)load(ps.sample).v;
  PT_LANES_REVERSE_BITS(reversed_index);
  auto value = [&](uint32_t dimension) {
    UintVector bits;
    PT_HASHED_BITS_IN_LANES(bits, params->sampler, sample_hash, reversed_index, first_dimension + dimension);
    return bits_to_unit(bits);
  };
  // the two values of the pair of dimensions that starts at even `dimension` (sharing its hashes)
  auto pair = [&](uint32_t dimension, Float8* first, Float8* second) {
    UintVector bits0, bits1;
    PT_HASHED_BITS2_IN_LANES(bits0, bits1, params->sampler, sample_hash, reversed_index, first_dimension + dimension);
    *first = bits_to_unit(bits0), *second = bits_to_unit(bits1);
  };
  Float8 bsdf_u, bsdf_v;
  pair(PT_DIM_BSDF_U, &bsdf_u, &bsdf_v);
  const Mask8 roulette_lanes = active & (bounce >= (int32_t)PT_ROULETTE_START);
  if (kd_any(roulette_lanes)) {
    const Float8 survive = fmin(sqrt(pt_max3(beta)), 1.0f);
    active = active & !(roulette_lanes & (value(PT_DIM_ROULETTE) >= survive));
    beta = kd_select(roulette_lanes, beta / survive, beta);
  }
  // next-event estimation (pt_next_event_any) where the BSDF has no delta lobe: in lanes, but for
  // textured emitters
  const Mask8 lit = active & !bsdf.delta();
  if (PT_USES(params, PT_FEATURE_EMISSIVE_TEXTURE)) {
    next_event_lane_by_lane(ps, bits(lit), scene, params, material, bounce, p, n, ng_facing, wo, bsdf, beta);
  } else {
    const Float8 u = params->select_triangles < 1.0f ? value(PT_DIM_LIGHT_TYPE) : Float8(0.0f);
    const Mask8 triangles = lit & (u < params->select_triangles);
    if (kd_any(triangles)) {
      Float8 light_pick, light_v;
      pair(PT_DIM_LIGHT_PICK, &light_pick, &light_v);
      next_event_on_triangles(ps, scene, params, triangles, light_pick, light_v, p, n, ng_facing, wo, bsdf, beta);
    }
    const Mask8 others = lit & !triangles;
    if (kd_any(others)) {
      Float8 env_u, env_v;
      pair(PT_DIM_ENV_U, &env_u, &env_v);
      next_event_on_other_lights(ps, scene, params, others, u - params->select_triangles, env_u, env_v, p, n,
                                 ng_facing, wo, bsdf, beta);
    }
  }
  // the BSDF sample (the glTF material's lobe value drawn only where a lane has it)
  Float8 pdf;
  Float8x3 weight;
  const Float8 u_lobe = kd_any(bsdf.metal_rough & active) ? value(PT_DIM_LOBE) : Float8(0.0f);
  Mask8 transmits;
  const Float8x3 wi = bsdf_sample(bsdf, n, wo, bsdf_u, bsdf_v, u_lobe, &pdf, &weight, &transmits);
  const Float8 side = kd_dot(wi, ng_facing);
  // a sample that leaves on the wrong side of the surface ends the path
  active = active & !((pt_max3(weight) <= 0.0f) | (transmits & (side >= 0.0f)) | ((!transmits) & (side <= 0.0f)));
  store3(ps.tx, ps.ty, ps.tz, kd_select(active, beta * weight, beta));
  store3(ps.rx, ps.ry, ps.rz, radiance);
  store(ps.bsdf_pdf, pdf);
  store3(ps.ox, ps.oy, ps.oz, pt_offset_origin(p, kd_select(transmits, -ng_facing, ng_facing)));
  store3(ps.dx, ps.dy, ps.dz, wi);
  store(ps.bounce, kd_select(active, bounce + 1, bounce));  // an ended path's, as pt_path_shade leaves it
  ps.alive = bits(active);
  shaded_lane_by_lane(ps, by_lane);
}

// pt_path_begin into lane l.
inline void begin(Paths& ps, int l, const PtRenderParams* params, uint32_t pixel, uint32_t sample) {
  PtPath& path = ps.path[l];
  pt_path_begin(&path, params, pixel, sample);
  ps.ox[l] = path.origin.x, ps.oy[l] = path.origin.y, ps.oz[l] = path.origin.z;
  ps.dx[l] = path.direction.x, ps.dy[l] = path.direction.y, ps.dz[l] = path.direction.z;
  ps.tx[l] = ps.ty[l] = ps.tz[l] = 1.0f;
  ps.rx[l] = ps.ry[l] = ps.rz[l] = 0.0f;
  ps.bsdf_pdf[l] = 0.0f;
  ps.bounce[l] = 0;
  ps.sample_hash[l] = path.sample_hash;
  ps.sample[l] = path.sample;
  ps.alive |= 1 << l;
}

// pt_path_begin into lanes [0, count) of paths that have none, sample `samples[l]` of pixel
// `pixels[l]`: the sample hashes, the camera's two values and the camera rays of all of them in
// lanes (each lane with pt_path_begin's operations); an orthographic camera lane by lane.
inline void begin_in_lanes(Paths& ps, int count, const PtRenderParams* params, const uint32_t* pixels,
                           const uint32_t* samples) {
  if (PT_USES(params, PT_FEATURE_ORTHOGRAPHIC)) {
    for (int l = 0; l < count; ++l) begin(ps, l, params, pixels[l], samples[l]);
    return;
  }
  alignas(32) uint32_t pixel[kLanes] = {}, sample[kLanes] = {};
  alignas(32) float x[kLanes] = {}, y[kLanes] = {};
  for (int l = 0; l < count; ++l) {
    pixel[l] = pixels[l], sample[l] = samples[l];
    x[l] = (float)(pixels[l] % params->width), y[l] = (float)(pixels[l] / params->width);
  }
  const UintVector pixel_lanes = (UintVector)load(pixel).v, sample_lanes = (UintVector)load(sample).v;
  UintVector sample_hash;
  PT_SAMPLE_HASH_STEPS(sample_hash, params->sampler, params->seed, pixel_lanes, sample_lanes);
  UintVector reversed_index = sample_lanes;
  PT_LANES_REVERSE_BITS(reversed_index);
  UintVector camera_x, camera_y;
  PT_HASHED_BITS2_IN_LANES(camera_x, camera_y, params->sampler, sample_hash, reversed_index,
                           PT_LANES_SPLAT(PT_DIM_CAMERA_X));
  Float8 sx, sy;
  pt_film_point(params, load(x) + bits_to_unit(camera_x), load(y) + bits_to_unit(camera_y), &sx, &sy);
  store3(ps.dx, ps.dy, ps.dz, pt_perspective_direction(params, sx, sy));
  store3(ps.ox, ps.oy, ps.oz, Float8x3{params->cam_origin[0], params->cam_origin[1], params->cam_origin[2]});
  store3(ps.tx, ps.ty, ps.tz, Float8x3{1.0f, 1.0f, 1.0f});
  store3(ps.rx, ps.ry, ps.rz, Float8x3{0.0f, 0.0f, 0.0f});
  store(ps.bsdf_pdf, Float8(0.0f));
  store(ps.bounce, Int8(0));
  store(reinterpret_cast<int32_t*>(ps.sample_hash), Int8((IntVector)sample_hash));
  store(reinterpret_cast<int32_t*>(ps.sample), Int8((IntVector)sample_lanes));
  for (int l = 0; l < count; ++l) {
    PtPath& path = ps.path[l];
    pt_path_start(&path, pixels[l], samples[l], ps.sample_hash[l]);
    path.origin = KD_FLOAT3(ps.ox[l], ps.oy[l], ps.oz[l]);
    path.direction = KD_FLOAT3(ps.dx[l], ps.dy[l], ps.dz[l]);
  }
  ps.alive |= count >= kLanes ? 0xff : (1 << count) - 1;
}

// pt_path_accumulate of lane l's path, into its pixel's film sums.
inline void accumulate(Paths& ps, int l, const PtRenderParams* params, int64_t* film, uint32_t* nonfinite) {
  PtPath& path = ps.path[l];
  path.radiance = KD_FLOAT3(ps.rx[l], ps.ry[l], ps.rz[l]);
  long sums[PT_MAX_FILM_CHANNELS] = {};
  pt_path_accumulate(&path, params, sums, nonfinite);
  for (uint32_t c = 0; c < params->film_channels; ++c) film[(size_t)path.pixel * params->film_channels + c] += sums[c];
}

// Lane `to` of `into` takes over the path in lane `from` of `paths` (which loses it).
inline void move_path(Paths& into, int to, Paths& paths, int from) {
  for (auto member : {&Paths::ox, &Paths::oy, &Paths::oz, &Paths::dx, &Paths::dy, &Paths::dz, &Paths::tx, &Paths::ty,
                      &Paths::tz, &Paths::rx, &Paths::ry, &Paths::rz, &Paths::bsdf_pdf})
    (into.*member)[to] = (paths.*member)[from];
  into.bounce[to] = paths.bounce[from];
  into.sample_hash[to] = paths.sample_hash[from];
  into.sample[to] = paths.sample[from];
  into.path[to] = paths.path[from];
  into.alive |= 1 << to;
  paths.alive &= ~(1 << from);
}

// Lane l's shadow ray is not occluded: its light sample's contribution joins the radiance.
inline void add_light_sample(Paths& ps, int l) {
  ps.rx[l] += ps.scx[l], ps.ry[l] += ps.scy[l], ps.rz[l] += ps.scz[l];
}

// The shadow rays of the lanes in ps.shadow, traced one at a time (pt_path_occluded), or with
// `packet` (the tree's arrays) as one packet (kdray::trace_packet_any) where no surface is
// alpha-tested: a light sample's contribution is added where its ray is not occluded.
inline void trace_shadow_rays(Paths& ps, const PtSceneData* scene, const PtRenderParams* params,
                              const kdray::TraversalArrays* packet) {
  if (packet && !PT_USES(params, PT_FEATURE_ALPHA)) {
    RayRecord rays[kLanes];
    int lane_of[kLanes], count = 0;
    for (int lanes = ps.shadow; lanes; lanes &= lanes - 1) {
      const int l = __builtin_ctz(lanes);
      rays[count] = RayRecord{ps.sox[l], ps.soy[l], ps.soz[l], ps.ssx[l], ps.ssy[l], ps.ssz[l], 0.0f, 1.0f};
      lane_of[count++] = l;
    }
    uint8_t occluded[kLanes];
    kdray::trace_packet_any(*packet, rays, count, occluded);
    for (int i = 0; i < count; ++i) {
      const int l = lane_of[i];
      if (!occluded[i]) add_light_sample(ps, l);
    }
    return;
  }
  for (int lanes = ps.shadow; lanes; lanes &= lanes - 1) {
    const int l = __builtin_ctz(lanes);
    PtPath& path = ps.path[l];  // what pt_path_occluded reads of it
    path.shadow_origin = KD_FLOAT3(ps.sox[l], ps.soy[l], ps.soz[l]);
    path.shadow_span = KD_FLOAT3(ps.ssx[l], ps.ssy[l], ps.ssz[l]);
    path.bounce = (uint32_t)ps.bounce[l];
    if (!pt_path_occluded(scene, &path, params)) add_light_sample(ps, l);
  }
}

// The samples of pixels [begin_pixel, end_pixel) in order, and their paths' first segments
// eight at a time: the eight samples begun together, their camera rays traced as one packet
// (kdray::trace_packet), shaded in lanes and their shadow rays traced as one packet. Those rays
// run close together, so a packet traces them 2-3 times as fast as one at a time (bench/LOG.md,
// "Packets of eight rays"); the later rays of the paths run apart and are traced one at a time.
struct FirstSegments {
  Paths paths{};  // the paths that go on after their first segment: paths.alive
  uint32_t next_pixel, end_pixel, next_sample = 0;
  uint64_t rays = 0;

  // Takes the next (up to) eight samples through their first segment; false when none is left.
  __attribute__((noinline)) bool next(const PtSceneData* scene, const PtRenderParams* params,
                                      const kdray::TraversalArrays& arrays, int64_t* film, uint32_t* nonfinite) {
    uint32_t pixels[kLanes], samples[kLanes];
    int count = 0;
    for (; count < kLanes && next_pixel != end_pixel; ++count) {
      pixels[count] = next_pixel, samples[count] = params->sample_offset + next_sample;
      if (++next_sample == params->sample_count) next_sample = 0, ++next_pixel;
    }
    if (count == 0) return false;
    begin_in_lanes(paths, count, params, pixels, samples);
    // pt_ray of each lane's camera ray, the lanes' words transposed into records
    static_assert(sizeof(RayRecord) == 8 * sizeof(float), "a ray: 8 floats");
    __m256 words[kLanes] = {_mm256_load_ps(paths.ox), _mm256_load_ps(paths.oy), _mm256_load_ps(paths.oz),
                            _mm256_load_ps(paths.dx), _mm256_load_ps(paths.dy), _mm256_load_ps(paths.dz),
                            _mm256_setzero_ps(),      _mm256_set1_ps(INFINITY)};
    transpose(words);
    RayRecord camera[kLanes];
    for (int l = 0; l < kLanes; ++l) _mm256_storeu_ps(reinterpret_cast<float*>(&camera[l]), words[l]);
    HitRecord hits[kLanes] = {};
    kdray::trace_packet(arrays, camera, count, hits);
    rays += (uint64_t)count;
    const int begun = paths.alive;
    shade(paths, scene, params, hits);
    rays += (uint64_t)__builtin_popcount(paths.shadow);
    trace_shadow_rays(paths, scene, params, &arrays);
    for (int ended = begun & ~paths.alive; ended; ended &= ended - 1)
      accumulate(paths, __builtin_ctz(ended), params, film, nonfinite);
    return true;
  }
};

// Where a ray goes in the order its batch is traced in (19 bits): its origin's cell in a 16 x 16 x
// 16 grid over the scene's bounds in Morton order, then its direction's octant and a 4 x 4 cell of
// |x| and |y| over |x| + |y| + |z|. Rays of a batch sorted by it run close together in runs of
// eight, so that a packet pays for a node's step and a triangle's test once for all of them.
// (Direction first, or a finer grid, made the packets slower: bench/LOG.md.)
struct RayOrder {
  FloatVector lo[3], scale[3];

  explicit RayOrder(const PtSceneData* scene) {
    for (int k = 0; k < 3; ++k) {
      const float extent = scene->kd.bounds_max[k] - scene->kd.bounds_min[k];
      lo[k] = FloatVector{} + scene->kd.bounds_min[k];
      scale[k] = FloatVector{} + (extent > 0.0f ? 16.0f / extent : 0.0f);
    }
  }
  // x's cell of `cells` (x in [0, cells)); NaN in cell 0.
  static IntVector cell(FloatVector x, float cells) {
    const __m256 at_least_0 = _mm256_max_ps((__m256)x, _mm256_setzero_ps());  // NaN: 0
    return (IntVector)_mm256_cvttps_epi32(_mm256_min_ps(at_least_0, _mm256_set1_ps(cells - 0.5f)));
  }
  // 4 bits b3 b2 b1 b0 spread to b3 0 0 b2 0 0 b1 0 0 b0.
  static IntVector spread(IntVector v) {
    v = (v | v << 4) & 0x0C3;
    return (v | v << 2) & 0x249;
  }
  // The keys of 8 rays.
  IntVector keys(FloatVector ox, FloatVector oy, FloatVector oz, FloatVector dx, FloatVector dy, FloatVector dz) const {
    const FloatVector ax = (FloatVector)((IntVector)dx & 0x7fffffff), ay = (FloatVector)((IntVector)dy & 0x7fffffff),
                      az = (FloatVector)((IntVector)dz & 0x7fffffff);
    const FloatVector to_cells = 4.0f / (ax + ay + az);
    const IntVector octant = ((dx < 0.0f) & 1) | ((dy < 0.0f) & 2) | ((dz < 0.0f) & 4);
    const IntVector direction = octant << 4 | cell(ax * to_cells, 4.0f) << 2 | cell(ay * to_cells, 4.0f);
    const IntVector origin = spread(cell((ox - lo[0]) * scale[0], 16.0f)) |
                             spread(cell((oy - lo[1]) * scale[1], 16.0f)) << 1 |
                             spread(cell((oz - lo[2]) * scale[2], 16.0f)) << 2;
    return origin << 7 | direction;
  }
};

// A thread's paths in flight: kGroups groups of eight lanes, shaded a group at a time; each
// step's closest rays, and then its shadow rays, are traced together as packets of eight in
// RayOrder. Fewer sort into less coherent packets, more outgrow the L2 cache (bench/LOG.md,
// "Paths' rays sorted into packets").
constexpr int kGroups = 256;
constexpr int kBatchRays = kGroups * kLanes;

struct Batch {
  Paths groups[kGroups];
  HitRecord hits[kBatchRays];  // by lane, group after group (shade() reads a lane without a path too)
  RayRecord rays[kBatchRays];
  uint32_t keys[kBatchRays];
  uint16_t slot[kBatchRays];   // each ray's lane, as 8 x group + lane
  uint16_t order[kBatchRays], scratch[kBatchRays];
  int count = 0;  // rays gathered
};

// Appends to the batch the rays of group g's lanes in `lanes` (origins o, directions d, tmin 0,
// tmax), with their keys and slots.
inline void add_rays(Batch& batch, const RayOrder& order, int g, int lanes, const float* ox, const float* oy,
                     const float* oz, const float* dx, const float* dy, const float* dz, float tmax) {
  if (!lanes) return;
  __m256 words[kLanes] = {_mm256_loadu_ps(ox), _mm256_loadu_ps(oy), _mm256_loadu_ps(oz),
                          _mm256_loadu_ps(dx), _mm256_loadu_ps(dy), _mm256_loadu_ps(dz),
                          _mm256_setzero_ps(),  _mm256_set1_ps(tmax)};
  alignas(32) int32_t keys[kLanes];
  store(keys, Int8(order.keys((FloatVector)words[0], (FloatVector)words[1], (FloatVector)words[2],
                              (FloatVector)words[3], (FloatVector)words[4], (FloatVector)words[5])));
  transpose(words);
  for (; lanes; lanes &= lanes - 1) {
    const int l = __builtin_ctz(lanes);
    _mm256_storeu_ps(reinterpret_cast<float*>(&batch.rays[batch.count]), words[l]);
    batch.keys[batch.count] = (uint32_t)keys[l];
    batch.slot[batch.count++] = (uint16_t)(g * kLanes + l);
  }
}

// batch.order[0, count): the rays' indices sorted by key (19 bits), stable: a counting sort on the
// low 10 bits, then on the high 9.
inline void sort_rays(Batch& batch) {
  const int n = batch.count;
  uint32_t start[1024];
  std::memset(start, 0, sizeof start);
  for (int i = 0; i < n; ++i) ++start[batch.keys[i] & 1023u];
  for (uint32_t b = 0, sum = 0; b < 1024; ++b) sum += std::exchange(start[b], sum);
  for (int i = 0; i < n; ++i) batch.scratch[start[batch.keys[i] & 1023u]++] = (uint16_t)i;
  std::memset(start, 0, 512 * sizeof start[0]);
  for (int i = 0; i < n; ++i) ++start[batch.keys[i] >> 10];
  for (uint32_t b = 0, sum = 0; b < 512; ++b) sum += std::exchange(start[b], sum);
  for (int i = 0; i < n; ++i) {
    const uint16_t ray = batch.scratch[i];
    batch.order[start[batch.keys[ray] >> 10]++] = ray;
  }
}

// Sorts the batch's rays (sort_rays) and hands them to trace(packet, n, ray) eight at a time in
// that order: packet[j] is the batch's ray number ray[j], j < n.
template <typename TracePacket>
inline void trace_sorted(Batch& batch, const TracePacket& trace) {
  sort_rays(batch);
  for (int i = 0; i < batch.count; i += kLanes) {
    const int n = std::min(kLanes, batch.count - i);
    RayRecord packet[kLanes];
    for (int j = 0; j < n; ++j) packet[j] = batch.rays[batch.order[i + j]];
    trace(packet, n, batch.order + i);
  }
}

// Moves the live paths of groups [0, used) into the lowest lanes they can take, so that every group
// but the last is full and shading takes as few groups as there are paths for; returns the groups
// that hold them.
inline int compact(Paths* groups, int used) {
  int low = 0, high = used - 1;
  for (;;) {
    while (low < high && groups[low].alive == 0xff) ++low;
    while (high > low && groups[high].alive == 0) --high;
    if (low >= high) return groups[low].alive ? low + 1 : low;
    while (groups[low].alive != 0xff && groups[high].alive)
      move_path(groups[low], __builtin_ctz(~groups[low].alive), groups[high], __builtin_ctz(groups[high].alive));
  }
}

// pt_render_pixel for pixels [begin_pixel, end_pixel): the rays traced. Each path's arithmetic is
// the same whichever lane takes it and whatever packet traces its rays (a packet's hits are one
// ray at a time's), and the film's sums are integers, so the film does not depend on which lane
// took which path.
inline uint64_t render(const PtSceneData* scene, const PtRenderParams* params, uint32_t begin_pixel, uint32_t end_pixel,
                       int64_t* film, uint32_t* nonfinite) {
  if (params->sample_count == 0) return 0;
  const kdray::TraversalArrays arrays{scene->kd.nodes, scene->kd.leaf_blocks,
                                      {scene->kd.bounds_min[0], scene->kd.bounds_min[1], scene->kd.bounds_min[2]},
                                      {scene->kd.bounds_max[0], scene->kd.bounds_max[1], scene->kd.bounds_max[2]}};
  const RayOrder ray_order(scene);
  // The thread's own, zeroed once: a lane that has no path still takes part in the lanes' integer
  // arithmetic, which uninitialised bits could make overflow (UBSan); a path's leftovers cannot.
  thread_local std::unique_ptr<Batch> owned(new Batch());
  Batch& batch = *owned;
  FirstSegments first;
  first.next_pixel = begin_pixel;
  first.end_pixel = end_pixel;
  uint64_t rays = 0;
  // Lane l of ps takes the next path that goes on after its first segment, if any is left.
  auto refill = [&](Paths& ps, int l) {
    while (!first.paths.alive)
      if (!first.next(scene, params, arrays, film, nonfinite)) return;
    move_path(ps, l, first.paths, __builtin_ctz(first.paths.alive));
  };
  int used = 0;  // groups [0, used) hold the live paths, every lane but the last group's taken
  for (; used < kGroups && (first.paths.alive || first.next_pixel != first.end_pixel); ++used)
    for (int l = 0; l < kLanes; ++l) refill(batch.groups[used], l);
  used = compact(batch.groups, used);  // the last paths may all have ended in their first segment
  const bool alpha = PT_USES(params, PT_FEATURE_ALPHA);
  int was_alive[kGroups];
  while (used > 0) {
    // The closest hits of every live path, traced in packets in ray order.
    batch.count = 0;
    for (int g = 0; g < used; ++g) {
      const Paths& ps = batch.groups[g];
      add_rays(batch, ray_order, g, ps.alive, ps.ox, ps.oy, ps.oz, ps.dx, ps.dy, ps.dz, INFINITY);
    }
    rays += (uint64_t)batch.count;
    trace_sorted(batch, [&](const RayRecord* packet, int n, const uint16_t* ray) {
      HitRecord hits[kLanes];
      kdray::trace_packet(arrays, packet, n, hits);
      for (int j = 0; j < n; ++j) batch.hits[batch.slot[ray[j]]] = hits[j];
    });
    for (int g = 0; g < used; ++g) {
      was_alive[g] = batch.groups[g].alive;
      shade(batch.groups[g], scene, params, batch.hits + g * kLanes);
    }
    // The shadow rays, likewise (with alpha-tested surfaces, one at a time: trace_shadow_rays).
    batch.count = 0;
    for (int g = 0; g < used; ++g) {
      Paths& ps = batch.groups[g];
      rays += (uint64_t)__builtin_popcount(ps.shadow);
      if (alpha) trace_shadow_rays(ps, scene, params, nullptr);
      else add_rays(batch, ray_order, g, ps.shadow, ps.sox, ps.soy, ps.soz, ps.ssx, ps.ssy, ps.ssz, 1.0f);
    }
    trace_sorted(batch, [&](const RayRecord* packet, int n, const uint16_t* ray) {
      uint8_t occluded[kLanes];
      kdray::trace_packet_any(arrays, packet, n, occluded);
      for (int j = 0; j < n; ++j)
        if (!occluded[j]) add_light_sample(batch.groups[batch.slot[ray[j]] / kLanes], batch.slot[ray[j]] % kLanes);
    });
    for (int g = 0; g < used; ++g) {
      Paths& ps = batch.groups[g];
      for (int ended = was_alive[g] & ~ps.alive; ended; ended &= ended - 1) {
        const int l = __builtin_ctz(ended);
        accumulate(ps, l, params, film, nonfinite);
        refill(ps, l);
      }
    }
    used = compact(batch.groups, used);
  }
  return rays + first.rays;
}

}  // namespace path_lanes
