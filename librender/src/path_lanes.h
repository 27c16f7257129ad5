// The host's path tracer 8 paths at a time in AVX2 lanes, for scenes of diffuse and emissive
// triangles lit by their emissive triangles alone (paths_in_lanes_apply): each step traces the
// closest hits of the live paths one after another (kernels/kd_traverse.h), shades all 8 at once
// (pt_path_shade's parts for that scene kind: the hit point, emission with MIS, Russian roulette,
// next-event estimation on the triangle lights, the Lambertian BSDF sample), then traces their
// shadow rays; a path that ends is added to the film and its lane takes the next sample. Each
// lane computes what pt_path_shade computes for its path, bit for bit, so the film is the scalar
// path tracer's and the kernel's (tests/render/cpu_integrator.h compares them). Sample values,
// the light pick's search and a path's start and film sums stay scalar, lane by lane.
//
// Compiled into the x86-64-v3 build of render_host_pixels.cpp, inside its namespace after the
// device code, whose functions it calls.
#pragma once

#include "lane8_sampling.h"

namespace path_lanes {

using namespace lane8;

// Whether the lanes render this pass as the scalar path tracer would: no feature but emission
// (so every material is diffuse or emissive, untextured and opaque), next-event estimation on the
// triangle lights alone, and few enough triangles that a corner's float index fits the gathers'
// 32-bit signed indices.
inline bool apply(const PtRenderParams& params, size_t triangle_count) {
  return (params.features & ~PT_FEATURE_EMISSION) == 0 && params.light_count > 0 && params.select_triangles == 1.0f &&
         triangle_count <= size_t{0x7fffffff} / KD_TRIANGLE_FLOATS;
}

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
  PtPath path[kLanes];  // what is read one lane at a time: pixel, sample, its hash, first-hit AOVs
  int alive = 0, shadow = 0;  // bit per lane
};

// The words shade() gathers: a HitRecord's t, triangle, u and v, a PtMaterial's base colour, type
// and emission.
static_assert(sizeof(HitRecord) == 16 && KD_OFFSETOF(HitRecord, t) == 0 && KD_OFFSETOF(HitRecord, triangle) == 4 &&
                  KD_OFFSETOF(HitRecord, u) == 8 && KD_OFFSETOF(HitRecord, v) == 12,
              "HitRecord: 4 words t, triangle, u, v");
static_assert(sizeof(PtMaterial) == 16 * 4 && KD_OFFSETOF(PtMaterial, base_color) == 0 &&
                  KD_OFFSETOF(PtMaterial, type) == 3 * 4 && KD_OFFSETOF(PtMaterial, emission) == 4 * 4,
              "PtMaterial: 16 words, base colour at 0, type at 3, emission at 4");

// The lanes' float3 from, and to, its coordinates' arrays.
inline V3 load3(const float* x, const float* y, const float* z) { return {load(x), load(y), load(z)}; }
inline void store3(float* x, float* y, float* z, V3 v) {
  store(x, v.x);
  store(y, v.y);
  store(z, v.z);
}
// pt_corner of each lane's triangle, in the lanes of the mask (0 in the others).
inline V3 corners(const float* triangle_vertices, i8 triangle, i8 lanes, int corner) {
  const i8 index = triangle * (int32_t)KD_TRIANGLE_FLOATS + 3 * corner;
  return {gather(triangle_vertices, index, lanes), gather(triangle_vertices + 1, index, lanes),
          gather(triangle_vertices + 2, index, lanes)};
}

// pt_path_shade for the live lanes, each with its hit: the lanes still alive after it, and those
// with a shadow ray to trace, are left in ps.alive and ps.shadow.
inline void shade(Paths& ps, const PtSceneData* scene, const PtRenderParams* params, const HitRecord* hits) {
  ps.shadow = 0;
  const i8 lane_bit = {1, 2, 4, 8, 16, 32, 64, 128};
  const i8 hit_index = {0, 4, 8, 12, 16, 20, 24, 28};  // HitRecord: 4 words
  const int32_t* hit_words = reinterpret_cast<const int32_t*>(hits);
  const float* hit_floats = reinterpret_cast<const float*>(hits);
  const i8 tri = gather(hit_words + 1, hit_index, (lane_bit & ps.alive) != 0);
  i8 active = ((lane_bit & ps.alive) != 0) & (tri != (int32_t)KD_NO_HIT);
  const int live = bits(active);
  ps.alive = live;
  if (!live) return;
  f8 t = gather(hit_floats, hit_index, active), u = gather(hit_floats + 2, hit_index, active),
     v = gather(hit_floats + 3, hit_index, active);
  // PtMaterial: 16 words
  const i8 material = gather(reinterpret_cast<const int32_t*>(scene->material_ids), tri, active) * 16;
  const float* material_floats = reinterpret_cast<const float*>(scene->materials);
  const i8 type = gather(reinterpret_cast<const int32_t*>(scene->materials) + 3, material, active);
  V3 p0 = corners(scene->triangle_vertices, tri, active, 0);
  V3 p1 = corners(scene->triangle_vertices, tri, active, 1);
  V3 p2 = corners(scene->triangle_vertices, tri, active, 2);
  f8 w0 = 1.0f - u - v;
  V3 p = w0 * p0 + u * p1 + v * p2;
  V3 direction = load3(ps.dx, ps.dy, ps.dz), origin = load3(ps.ox, ps.oy, ps.oz);
  V3 wo = -direction;
  V3 ng = normalize(cross(p1 - p0, p2 - p0));
  i8 front = dot(ng, wo) > 0.0f;
  V3 ng_facing = sel(front, ng, -ng);
  V3 n = ng_facing;
  V3 color = {gather(material_floats, material, active), gather(material_floats + 1, material, active),
              gather(material_floats + 2, material, active)};
  i8 bounce = loadi(ps.bounce);
  {
    int first = bits(active & (bounce == 0));
    alignas(32) float cx[kLanes], cy[kLanes], cz[kLanes], nx[kLanes], ny[kLanes], nz[kLanes];
    store3(cx, cy, cz, color);
    store3(nx, ny, nz, n);
    for (int l = 0; l < kLanes; ++l)
      if (first >> l & 1) {
        ps.path[l].albedo = KD_FLOAT3(cx[l], cy[l], cz[l]);
        ps.path[l].normal = KD_FLOAT3(nx[l], ny[l], nz[l]);
        ps.path[l].depth = t[l];
      }
  }
  V3 beta = load3(ps.tx, ps.ty, ps.tz);
  V3 radiance = load3(ps.rx, ps.ry, ps.rz);
  f8 bsdf_pdf = load(ps.bsdf_pdf);
  i8 emissive = active & (type == (int32_t)PT_EMISSIVE) & front;
  if (any(emissive)) {
    V3 emission = {gather(material_floats + 4, material, emissive), gather(material_floats + 5, material, emissive),
                   gather(material_floats + 6, material, emissive)};
    f8 weight = splat(1.0f);
    i8 mis = emissive & (bsdf_pdf > 0.0f);
    if (any(mis)) {
      V3 a, b, c;
      f8 solid_angle = spherical_solid_angle(mis, origin, p0, p1, p2, &a, &b, &c);
      f8 pick_per_area = params->select_triangles * luminance(emission) * params->light_area_pdf_scale;
      f8 light_pdf = triangle_light_pdf(pick_per_area, 0.5f * length(cross(p1 - p0, p2 - p0)), solid_angle, t * t,
                                        dot(ng, wo));
      weight = mis ? power_heuristic(bsdf_pdf, light_pdf) : weight;
    }
    radiance = sel(emissive, radiance + beta * emission * weight, radiance);
  }
  active &= bounce <= (int32_t)(params->max_bounces < 0x7fffffffu ? params->max_bounces : 0x7fffffffu);
  // sample values, per lane
  alignas(32) float roulette[kLanes] = {}, pick_u[kLanes] = {}, pick_v[kLanes] = {}, bsdf_u[kLanes] = {},
                    bsdf_v[kLanes] = {};
  alignas(32) uint32_t light_tri[kLanes] = {};
  const int sampled = bits(active);
  for (int l = 0; l < kLanes; ++l)
    if (sampled >> l & 1) {
      const PtBounceSamples samples = pt_bounce_samples(params->sampler, ps.path[l].sample_hash, ps.path[l].sample,
                                                        PT_BOUNCE_DIMS((uint32_t)ps.bounce[l]));
      if (ps.bounce[l] >= (int32_t)PT_ROULETTE_START) roulette[l] = pt_bounce_sample(&samples, PT_DIM_ROULETTE);
      float2 pick = pt_bounce_sample2(&samples, PT_DIM_LIGHT_PICK);
      pick_v[l] = pick.y;
      light_tri[l] = pt_pick_light(scene->lights, params->light_count, &pick.x);
      pick_u[l] = pick.x;
      float2 bsdf = pt_bounce_sample2(&samples, PT_DIM_BSDF_U);
      bsdf_u[l] = bsdf.x;
      bsdf_v[l] = bsdf.y;
    }
  i8 roulette_lanes = active & (bounce >= (int32_t)PT_ROULETTE_START);
  if (any(roulette_lanes)) {
    f8 survive = vmin(vsqrt(max3(beta)), splat(1.0f));
    active &= ~(roulette_lanes & (load(roulette) >= survive));
    beta = sel(roulette_lanes, beta / survive, beta);
  }
  // next-event estimation (pt_next_event)
  {
    i8 ok = active;
    const i8 light = loadi(reinterpret_cast<const int32_t*>(light_tri));
    V3 q0 = corners(scene->triangle_vertices, light, ok, 0);
    V3 q1 = corners(scene->triangle_vertices, light, ok, 1);
    V3 q2 = corners(scene->triangle_vertices, light, ok, 2);
    V3 scaled_normal = cross(q1 - q0, q2 - q0);
    f8 twice_area = length(scaled_normal);
    V3 light_normal = scaled_normal / twice_area;
    V3 a, b, c;
    f8 lu = load(pick_u), lv = load(pick_v);
    f8 solid_angle = spherical_solid_angle(ok, p, q0, q1, q2, &a, &b, &c);
    i8 spherical = solid_angle > 0.0f;
    V3 wi = splat3(0.0f);
    f8 dist2 = splat(0.0f);
    if (any(spherical)) {
      wi = sample_spherical_triangle(a, b, c, solid_angle, lu, lv);
      f8 tl = dot(q0 - p, light_normal) / dot(wi, light_normal);
      ok &= ~spherical | ((tl > 0.0f) & (tl < INFINITY));
      dist2 = tl * tl;
    }
    if (any(ok & ~spherical)) {
      f8 s = vsqrt(lu);
      f8 bx = s * (1.0f - lv), by = s * lv;
      V3 to_light = q0 + bx * (q1 - q0) + by * (q2 - q0) - p;
      f8 d2 = dot(to_light, to_light);
      ok &= spherical | (d2 > 0.0f);
      wi = sel(spherical, wi, to_light * rsqrt(d2));
      dist2 = spherical ? dist2 : d2;
    }
    f8 cos_light = -dot(light_normal, wi);
    ok &= ~(cos_light <= 0.0f);
    f8 cos_i = dot(n, wi);
    f8 pdf = cos_i <= 0.0f ? splat(0.0f) : cos_i * PT_INV_PI;
    V3 f_cos = sel(cos_i <= 0.0f, splat3(0.0f), color * (cos_i * PT_INV_PI));
    ok &= ~(pdf <= 0.0f) & ~(dot(wi, ng_facing) <= 0.0f);
    const int shadow = bits(ok);
    if (shadow) {
      const i8 light_material = gather(reinterpret_cast<const int32_t*>(scene->material_ids), light, ok) * 16;
      V3 emission = {gather(material_floats + 4, light_material, ok), gather(material_floats + 5, light_material, ok),
                     gather(material_floats + 6, light_material, ok)};
      f8 pick_per_area = params->select_triangles * luminance(emission) * params->light_area_pdf_scale;
      f8 light_pdf = triangle_light_pdf(pick_per_area, 0.5f * twice_area, solid_angle, dist2, cos_light);
      f8 weight = power_heuristic(light_pdf, pdf);
      V3 shadow_origin = offset_origin(p, ng_facing);
      V3 target = offset_origin(p + vsqrt(dist2) * wi, light_normal);
      store3(ps.sox, ps.soy, ps.soz, shadow_origin);
      store3(ps.ssx, ps.ssy, ps.ssz, target - shadow_origin);
      store3(ps.scx, ps.scy, ps.scz, beta * f_cos * emission * (weight / light_pdf));
      ps.shadow = shadow;
    }
  }
  // the BSDF sample (pt_bsdf_sample's Lambertian lobe)
  V3 wi = sample_cosine(n, load(bsdf_u), load(bsdf_v));
  f8 pdf = vmax(dot(n, wi), splat(0.0f)) * PT_INV_PI;
  V3 weight = sel(pdf > 0.0f, color, splat3(0.0f));
  f8 side = dot(wi, ng_facing);
  active &= ~((max3(weight) <= 0.0f) | (side <= 0.0f));
  store3(ps.tx, ps.ty, ps.tz, sel(active, beta * weight, beta));
  store3(ps.rx, ps.ry, ps.rz, radiance);
  store(ps.bsdf_pdf, pdf);
  store3(ps.ox, ps.oy, ps.oz, offset_origin(p, ng_facing));
  store3(ps.dx, ps.dy, ps.dz, wi);
  i8 next = bounce + 1;
  std::memcpy(ps.bounce, &next, sizeof next);
  ps.alive = bits(active);
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
  ps.alive |= 1 << l;
}

// pt_path_accumulate of lane l's path, into its pixel's film sums.
inline void accumulate(Paths& ps, int l, const PtRenderParams* params, int64_t* film, uint32_t* nonfinite) {
  PtPath& path = ps.path[l];
  path.radiance = KD_FLOAT3(ps.rx[l], ps.ry[l], ps.rz[l]);
  long sums[PT_MAX_FILM_CHANNELS] = {};
  pt_path_accumulate(&path, params, sums, nonfinite);
  for (uint32_t c = 0; c < params->film_channels; ++c) film[(size_t)path.pixel * params->film_channels + c] += sums[c];
}

// pt_render_pixel for pixels [begin_pixel, end_pixel): the rays traced.
inline uint64_t render(const PtSceneData* scene, const PtRenderParams* params, uint32_t begin_pixel, uint32_t end_pixel,
                       int64_t* film, uint32_t* nonfinite) {
  Paths ps;
  uint64_t rays = 0;
  uint32_t next_pixel = begin_pixel, next_sample = 0;
  auto refill = [&](int l) {
    if (next_pixel == end_pixel) return;
    begin(ps, l, params, next_pixel, params->sample_offset + next_sample);
    if (++next_sample == params->sample_count) next_sample = 0, ++next_pixel;
  };
  if (params->sample_count == 0) return 0;
  for (int l = 0; l < kLanes; ++l) refill(l);
  HitRecord hits[kLanes];
  while (ps.alive) {
    for (int l = 0; l < kLanes; ++l)
      if (ps.alive >> l & 1) {
        hits[l] = kd_intersect_closest(&scene->kd, pt_ray(KD_FLOAT3(ps.ox[l], ps.oy[l], ps.oz[l]),
                                                          KD_FLOAT3(ps.dx[l], ps.dy[l], ps.dz[l]), INFINITY));
        ++rays;
      }
    const int was_alive = ps.alive;
    shade(ps, scene, params, hits);
    for (int l = 0; l < kLanes; ++l)
      if (ps.shadow >> l & 1) {
        ++rays;
        RayRecord ray = pt_ray(KD_FLOAT3(ps.sox[l], ps.soy[l], ps.soz[l]), KD_FLOAT3(ps.ssx[l], ps.ssy[l], ps.ssz[l]), 1.0f);
        if (!kd_intersect_any(&scene->kd, ray)) {
          ps.rx[l] += ps.scx[l];
          ps.ry[l] += ps.scy[l];
          ps.rz[l] += ps.scz[l];
        }
      }
    const int ended = was_alive & ~ps.alive;
    for (int l = 0; l < kLanes; ++l)
      if (ended >> l & 1) {
        accumulate(ps, l, params, film, nonfinite);
        refill(l);
      }
  }
  return rays;
}

}  // namespace path_lanes
