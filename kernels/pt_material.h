/* What a material's textures and alpha do at a hit: the base colour, metallic-roughness and
 * emissive textures, the normal map, and the alpha test that lets rays pass through cut-out or
 * blended surfaces. Each part is compiled only for scenes that have it. Traversal itself never
 * reads a material: a ray that hits an alpha-tested surface is continued past it by the shading
 * step (camera and bounce rays) or by pt_occluded (shadow rays), so rays through opaque scenes
 * cost what they did. */
#ifndef PT_MATERIAL_H
#define PT_MATERIAL_H

#include "kd_math.h"
#include "kd_traverse.h"
#include "pt_rng.h"
#include "pt_types.h"

#ifdef KD_FEATURE_TEXTURES
/* x wrapped into [0, n): its remainder, made non-negative; x is usually in range already, and the
 * division is the dearest step of a lookup. */
KD_INLINE int pt_wrap(int x, int n) {
  if ((uint)x < (uint)n) return x;
  x = x % n;
  return x < 0 ? x + n : x;
}
/* The texel at (x, y), both wrapped already. */
KD_INLINE float4 pt_texel(KD_GLOBAL const float4* texels, PtTexture tex, int x, int y) {
  return texels[tex.first_texel + (uint)y * tex.width + (uint)x];
}
/* Bilinear lookup with wrapping; v = 0 is the bottom row (OBJ convention). The second column and
 * row are the first ones' neighbours, wrapped: (x + 1) mod n from x mod n, without a division. */
KD_INLINE float4 pt_texture_lookup(KD_GLOBAL const PtTexture* textures, KD_GLOBAL const float4* texels, int index,
                                 float2 uv) {
  PtTexture tex = textures[index];
  float fx = uv.x * (float)tex.width - 0.5f;
  float fy = (1.0f - uv.y) * (float)tex.height - 0.5f;
  float x0 = floor(fx), y0 = floor(fy);
  float ax = fx - x0, ay = fy - y0;
  const int ix = pt_wrap((int)x0, (int)tex.width), iy = pt_wrap((int)y0, (int)tex.height);
  const int ix1 = ix + 1 == (int)tex.width ? 0 : ix + 1, iy1 = iy + 1 == (int)tex.height ? 0 : iy + 1;
  float4 top = kd_mix4(pt_texel(texels, tex, ix, iy), pt_texel(texels, tex, ix1, iy), ax);
  float4 bottom = kd_mix4(pt_texel(texels, tex, ix, iy1), pt_texel(texels, tex, ix1, iy1), ax);
  return kd_mix4(top, bottom, ay);
}
/* The interpolated UV of barycentric point (u, v) of a triangle with vertex numbers idx. */
KD_INLINE float2 pt_triangle_uv(KD_GLOBAL const float* uvs, KD_GLOBAL const kd_u32* idx, float u, float v) {
  return (1.0f - u - v) * vload2(idx[0], uvs) + u * vload2(idx[1], uvs) + v * vload2(idx[2], uvs);
}
#endif

#ifdef KD_FEATURE_NORMAL_MAP
/* The normal map's normal in world space, in the frame of the scene's per-vertex tangents
 * (formats/kdscene.md, "Tangents"; x, y, z, w per vertex): the tangent interpolated at barycentric
 * (u, v) and made orthogonal to the shading normal n, and the bitangent w * cross(n, t) towards +v.
 * Tangents are smooth across the triangles that share a vertex, so no seam shows between them.
 * The handedness w was set for the normal on the side the triangle winds counter-clockwise:
 * `side` is -1 when n faces the other way (a back face), which keeps the bitangent on +v. */
KD_INLINE float3 pt_normal_mapped(float3 n, KD_GLOBAL const float* tangents, KD_GLOBAL const kd_u32* idx, float u,
                               float v, float side, float3 mapped) {
  float4 tw = (1.0f - u - v) * vload4(idx[0], tangents) + u * vload4(idx[1], tangents) + v * vload4(idx[2], tangents);
  float3 t = kd_xyz(tw) - kd_dot(kd_xyz(tw), n) * n;
  if (!(kd_dot(t, t) > 0.0f)) return n;
  t = kd_normalize(t);
  float3 b = (tw.w < 0.0f ? -side : side) * kd_cross(n, t);
  float3 mapped_n = mapped.x * t + mapped.y * b + mapped.z * n;
  return kd_dot(mapped_n, mapped_n) > 0.0f ? kd_normalize(mapped_n) : n;
}
#endif

/* Applies the material's textures at a hit: base colour, metallic and roughness into *m and
 * *color, the normal map into *n (kept on the side of ng_facing; ng is the triangle's
 * counter-clockwise normal). */
KD_INLINE void pt_apply_textures(PtMaterial* m, float3* color, float3* n, float3 ng, float3 ng_facing,
                              KD_GLOBAL const float* uvs, KD_GLOBAL const float* tangents,
                              KD_GLOBAL const PtTexture* textures, KD_GLOBAL const float4* texels,
                              KD_GLOBAL const kd_u32* idx, float u, float v) {
#ifdef KD_FEATURE_TEXTURES
  /* Only a textured material reads the UVs: a scene without UVs has no texture indices. */
  if (m->texture < 0 && m->metal_rough_texture < 0 && m->normal_texture < 0) return;
  float2 uv = pt_triangle_uv(uvs, idx, u, v);
  if (m->texture >= 0) *color *= kd_xyz(pt_texture_lookup(textures, texels, m->texture, uv));
#ifdef KD_FEATURE_METAL_ROUGH_TEXTURE
  if (m->metal_rough_texture >= 0) {
    float4 mr = pt_texture_lookup(textures, texels, m->metal_rough_texture, uv);
    m->roughness *= mr.y * mr.y; /* the factor and the texel scale the perceptual roughness */
    m->metallic *= mr.z;
  }
#endif
#ifdef KD_FEATURE_NORMAL_MAP
  if (m->normal_texture >= 0) {
    float3 mapped = 2.0f * kd_xyz(pt_texture_lookup(textures, texels, m->normal_texture, uv)) - 1.0f;
    float3 mn = pt_normal_mapped(*n, tangents, idx, u, v, kd_dot(ng, ng_facing) > 0.0f ? 1.0f : -1.0f, mapped);
    /* A mapped normal may not face away from the viewer's side of the surface. */
    *n = kd_dot(mn, ng_facing) > 1e-4f ? mn : *n;
  }
#endif
#endif
  (void)m, (void)color, (void)n, (void)ng, (void)ng_facing, (void)uvs, (void)tangents, (void)textures, (void)texels;
  (void)idx, (void)u, (void)v;
}

#ifdef KD_FEATURE_EMISSIVE_TEXTURE
/* Emission of an emissive material at barycentric point (u, v) of a triangle. */
KD_INLINE float3 pt_textured_emission(const PtMaterial* m, KD_GLOBAL const float* uvs, KD_GLOBAL const PtTexture* textures,
                                   KD_GLOBAL const float4* texels, KD_GLOBAL const kd_u32* idx, float u, float v) {
  float3 emission = vload3(0, m->emission);
  if (m->emissive_texture >= 0)
    emission *= kd_xyz(pt_texture_lookup(textures, texels, m->emissive_texture, pt_triangle_uv(uvs, idx, u, v)));
  return emission;
}
#endif

#ifdef KD_FEATURE_ALPHA
/* Whether a ray passes through triangle `tri` at barycentric (u, v). Blended surfaces let it pass
 * with probability 1 - alpha, decided by a hash of the path and the triangle, so every layer a
 * path meets draws its own number and the decision does not depend on the thread. */
KD_INLINE int pt_alpha_passes(KD_GLOBAL const kd_u32* indices, KD_GLOBAL const kd_u32* material_ids,
                           KD_GLOBAL const PtMaterial* materials, KD_GLOBAL const float* uvs,
                           KD_GLOBAL const PtTexture* textures, KD_GLOBAL const float4* texels, uint tri, float u,
                           float v, uint path_key) {
  KD_GLOBAL const PtMaterial* m = &materials[material_ids[tri]];
  float cutoff = m->alpha_cutoff;
  if (cutoff == 0.0f) return 0;
  float alpha = m->alpha;
#ifdef KD_FEATURE_TEXTURES
  if (m->texture >= 0)
    alpha *= pt_texture_lookup(textures, texels, m->texture, pt_triangle_uv(uvs, indices + 3 * tri, u, v)).w;
#endif
  (void)indices, (void)uvs, (void)textures, (void)texels, (void)u, (void)v;
  if (cutoff > 0.0f) return alpha < cutoff;
  float r = (float)(pt_hash32(path_key ^ pt_hash32(tri)) >> 8) * 0x1.0p-24f;
  return r >= alpha;
}
#endif

#endif /* PT_MATERIAL_H */
