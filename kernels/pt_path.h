/* One path's shading and its whole loop: shade a closest hit (emission with MIS, Russian
 * roulette, next-event estimation, BSDF sampling), and trace a sample, and a pixel's samples, to
 * the film. The path's state is in kernels/pt_path_state.h, direct lighting in
 * kernels/pt_direct_light.h, film accumulation in kernels/pt_film.h. The megakernel runs
 * pt_render_pixel per work-item; the wavefront form runs each step as its own kernel over a
 * buffer of paths. Compiles as C++ too: librender/src/render_host_pixels.cpp runs it on the CPU
 * (kdrender --device host), and tests/render/cpu_integrator.h checks that against the kernel bit
 * for bit. */
#ifndef PT_PATH_H
#define PT_PATH_H

#include "pt_bsdf.h"
#include "pt_direct_light.h"
#include "pt_film.h"
#include "pt_lights.h"
#include "pt_material.h"
#include "pt_path_state.h"
#include "pt_spherical_triangle.h"

/* Russian roulette from this bounce on, surviving with probability min(sqrt(max throughput), 1):
 * the square root keeps more dim paths alive than min(max throughput, 1) would, which costs a
 * few more rays and saves more variance (measured in bench/LOG.md, "Sampler"). */
#define PT_ROULETTE_START 4u

#ifdef KD_FEATURE_ENVIRONMENT
/* A ray that leaves the scene sees the environment (camera rays too), MIS-weighted against
 * next-event estimation when a BSDF sample sent it. */
KD_INLINE void pt_path_escape(PtPath* path, const PtSceneData* scene, KD_GLOBAL const PtRenderParams* params) {
  float2 uv = pt_env_uv(params, path->direction);
  float weight = 1.0f;
  if (path->bsdf_pdf > 0.0f) weight = pt_mis_bsdf(params, path->bsdf_pdf, pt_env_pdf(scene->env_cdf, params, uv));
  path->radiance += path->throughput * pt_env_lookup(scene->env_texels, params, uv) * weight;
}
#endif

/* Advances the path by its closest hit. Bounce k is the k-th surface the path meets; light
 * is gathered at it (emission, and next-event estimation for surface k+1's light) and a new
 * direction sampled while k <= max_bounces, as Cycles counts: max_bounces 0 is direct light only. */
KD_INLINE void pt_path_shade(PtPath* path, const PtSceneData* scene, KD_GLOBAL const PtRenderParams* params,
                          HitRecord hit) {
  path->shadow_pending = 0;
  if (hit.triangle == KD_NO_HIT) {
#ifdef KD_FEATURE_ENVIRONMENT
    if (PT_USES(params, PT_FEATURE_ENVIRONMENT)) pt_path_escape(path, scene, params);
#endif
    path->alive = 0;
    return;
  }
  uint k = path->bounce;
  KD_GLOBAL const kd_u32* idx = scene->indices + 3 * hit.triangle;
  float3 p0 = pt_corner(scene->triangle_vertices, hit.triangle, 0);
  float3 p1 = pt_corner(scene->triangle_vertices, hit.triangle, 1);
  float3 p2 = pt_corner(scene->triangle_vertices, hit.triangle, 2);
  float w0 = 1.0f - hit.u - hit.v;
  float3 p = w0 * p0 + hit.u * p1 + hit.v * p2;
  float3 wo = -path->direction;
  float3 ng = kd_normalize(kd_cross(p1 - p0, p2 - p0));
  int front = kd_dot(ng, wo) > 0.0f;
  float3 ng_facing = front ? ng : -ng;
  float3 n = ng_facing;
#ifdef KD_FEATURE_NORMALS
  if (PT_USES(params, PT_FEATURE_NORMALS)) {
    float3 ns = w0 * pt_load3(scene->normals, idx[0]) + hit.u * pt_load3(scene->normals, idx[1]) +
                hit.v * pt_load3(scene->normals, idx[2]);
    if (kd_dot(ns, ns) > 0.0f) {
      ns = kd_normalize(ns);
      n = kd_dot(ns, ng_facing) < 0.0f ? -ns : ns;
    }
  }
#endif
  PtMaterial m = scene->materials[scene->material_ids[hit.triangle]];
#ifdef KD_FEATURE_ALPHA
  if (m.alpha_cutoff != 0.0f && pt_alpha_passes(scene->indices, scene->material_ids, scene->materials, scene->uvs,
                                                scene->textures, scene->texels, hit.triangle, hit.u, hit.v,
                                                pt_path_key(path, params))) {
    path->origin = pt_offset_origin(p, -ng_facing); /* the same bounce goes on beyond */
    return;
  }
#endif
  float3 color = vload3(0, m.base_color);
  pt_apply_textures(&m, &color, &n, ng, ng_facing, scene->uvs, scene->tangents, scene->textures, scene->texels, idx,
                    hit.u, hit.v);
  if (k == 0) {
    path->albedo = color;
    path->normal = n;
    path->depth = hit.t;
  }
  float3 beta = path->throughput;
#ifdef KD_FEATURE_EMISSION
  if (m.type == PT_EMISSIVE && front && PT_USES(params, PT_FEATURE_EMISSION)) {
    float3 emission = vload3(0, m.emission);
#ifdef KD_FEATURE_EMISSIVE_TEXTURE
    float3 radiance = pt_textured_emission(&m, scene->uvs, scene->textures, scene->texels, idx, hit.u, hit.v);
#else
    float3 radiance = emission;
#endif
    float weight = 1.0f;
    if (path->bsdf_pdf > 0.0f) {
      /* the density next-event estimation gives this direction, measured from the ray's origin
       * (the previous shading point, moved off its surface by a few ulps) */
      float3 a, b, c;
      float solid_angle = pt_spherical_solid_angle(path->origin, p0, p1, p2, &a, &b, &c);
      float pick_per_area = PT_SELECT_TRIANGLES(params) * pt_luminance(emission) * params->light_area_pdf_scale;
      float light_pdf = pt_triangle_light_pdf(pick_per_area, 0.5f * kd_length(kd_cross(p1 - p0, p2 - p0)), solid_angle,
                                              hit.t * hit.t, kd_dot(ng, wo));
      weight = pt_mis_bsdf(params, path->bsdf_pdf, light_pdf);
    }
    path->radiance += beta * radiance * weight;
  }
#endif
  if (k > params->max_bounces) {
    path->alive = 0;
    return;
  }
  const PtBounceSamples samples = pt_path_samples(path, params);
  if (k >= PT_ROULETTE_START) {
    float survive = fmin(sqrt(pt_max3(beta)), 1.0f);
    if (pt_bounce_sample(&samples, PT_DIM_ROULETTE) >= survive) {
      path->alive = 0;
      return;
    }
    beta /= survive;
    path->throughput = beta;
  }
#if defined(KD_FEATURE_ENVIRONMENT) || defined(KD_FEATURE_PUNCTUAL)
  if (!pt_is_delta(m.type)) pt_next_event_any(path, scene, params, &samples, &m, color, p, n, ng_facing, wo);
#elif defined(KD_FEATURE_EMISSION)
  if (params->light_count > 0 && !pt_is_delta(m.type))
    pt_next_event(path, scene, params, &samples, &m, color, p, n, ng_facing, wo);
#endif
  float2 u = pt_bounce_sample2(&samples, PT_DIM_BSDF_U);
#ifdef KD_FEATURE_METALLIC_ROUGHNESS
  /* Only the layered material reads it (pt_bsdf_sample); not drawn for the others. */
  float u_lobe = m.type == PT_METALLIC_ROUGHNESS ? pt_bounce_sample(&samples, PT_DIM_LOBE) : 0.0f;
#else
  float u_lobe = 0.0f;
#endif
  PtBsdfSample s = pt_bsdf_sample(&m, color, n, wo, front, u.x, u.y, u_lobe);
  float side = kd_dot(s.wi, ng_facing);
  if (pt_max3(s.weight) <= 0.0f || (s.transmits ? side >= 0.0f : side <= 0.0f)) {
    path->alive = 0;
    return;
  }
  path->throughput = beta * s.weight;
  path->bsdf_pdf = s.is_delta ? 0.0f : s.pdf;
  path->origin = pt_offset_origin(p, s.transmits ? -ng_facing : ng_facing);
  path->direction = s.wi;
  path->bounce = k + 1;
}

/* Traces sample `sample` of `pixel` to its end and adds it to the pixel's channel sums; returns
 * the number of rays traced. The megakernel's whole per-sample work, and the C++ build's. */
KD_INLINE uint pt_render_sample(const PtSceneData* scene, KD_GLOBAL const PtRenderParams* params, uint pixel, uint sample,
                             long* sums, uint* nonfinite) {
  uint rays = 0;
  PtPath path;
  pt_path_begin(&path, params, pixel, sample);
  while (path.alive) {
    HitRecord hit = kd_intersect_closest(&scene->kd, pt_path_ray(&path));
    ++rays;
    pt_path_shade(&path, scene, params, hit);
    if (path.shadow_pending) {
      ++rays;
      pt_path_resolve_shadow(&path, pt_path_occluded(scene, &path, params));
    }
  }
  pt_path_accumulate(&path, params, sums, nonfinite);
  return rays;
}

/* Traces samples sample_offset .. sample_offset + sample_count - 1 of `pixel` and adds their sums
 * to the pixel's film channels; returns the number of rays traced. The per-pixel work of the
 * megakernel and of the host renderer (librender/src/render_host_pixels.cpp). */
KD_INLINE ulong pt_render_pixel(const PtSceneData* scene, KD_GLOBAL const PtRenderParams* params, uint pixel,
                             KD_GLOBAL long* film, uint* nonfinite) {
  long sums[PT_MAX_FILM_CHANNELS];
  for (uint c = 0; c < PT_MAX_FILM_CHANNELS; ++c) sums[c] = 0;
  ulong rays = 0;
  for (uint i = 0; i < params->sample_count; ++i)
    rays += pt_render_sample(scene, params, pixel, params->sample_offset + i, sums, nonfinite);
  for (uint c = 0; c < params->film_channels; ++c) film[(size_t)pixel * params->film_channels + c] += sums[c];
  return rays;
}

#endif /* PT_PATH_H */
