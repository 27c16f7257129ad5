#!/usr/bin/env python3
"""White-furnace values of the glTF 2.0 metallic-roughness BRDF, from the specification's formulas
(Appendix B, "BRDF Implementation") alone: the known answers of tests/render/material_test.cpp.

A convex object under a uniform environment of radiance 1 reflects each light path once, so a
pixel that sees it at cos theta_o = mu shows the directional albedo a(mu) = integral of f cos theta_i
over the hemisphere; averaged over a sphere's projected disk (mu has density 2 mu there) that is the
hemispherical albedo 2 * integral_0^1 a(mu) mu dmu. Both integrals are Gauss-Legendre quadratures:
mu_o, and theta_i, phi_i over the hemisphere (phi over half of it, by symmetry).

The BRDF is linear in the base colour c:
  dielectric = (1 - F) c / pi + F * specular,      F = 0.04 + 0.96 (1 - |V.H|)^5
  metal      = (c + (1 - c) (1 - |V.H|)^5) * specular
  specular   = D * G / (4 |N.L| |N.V|), GGX D with alpha = roughness^2, G height-correlated Smith
so each roughness needs four integrals, and any base colour follows from them.

  /usr/bin/python3 tests/render/gltf_brdf_reference.py [--check]

--check repeats the quadrature on finer grids and prints the largest change (convergence);
it also prints the values with the separable Smith G, which the specification does not use, to show
the difference the choice makes."""

import sys

import numpy as np

ROUGHNESSES = (0.25, 0.5, 1.0)  # glTF's perceptual roughness
BASES = (0.2, 0.5, 0.8)


def g_height_correlated(nl, nv, a2):
    return 2 * nl * nv / (nv * np.sqrt(a2 + (1 - a2) * nl * nl) + nl * np.sqrt(a2 + (1 - a2) * nv * nv))


def g_separable(nl, nv, a2):
    g1 = lambda c: 2 * c / (c + np.sqrt(a2 + (1 - a2) * c * c))
    return g1(nl) * g1(nv)


def gauss(n, lo, hi):
    x, w = np.polynomial.legendre.leggauss(n)
    return lo + (x + 1) * (hi - lo) / 2, w * (hi - lo) / 2


def hemispherical_integrals(roughness, g, n_mu=48, n_theta=768, n_phi=768):
    """The four hemispherical albedos the BRDF is a linear combination of: diffuse (1 - F)/pi,
    F * specular, (1 - w) * specular and w * specular, with w = (1 - |V.H|)^5."""
    a2 = roughness ** 4
    mu_o, w_mu = gauss(n_mu, 0.0, 1.0)
    theta, w_theta = gauss(n_theta, 0.0, np.pi / 2)
    phi, w_phi = gauss(n_phi, 0.0, np.pi)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    dl = np.outer(w_theta, w_phi) * np.sin(t) * 2  # solid angle, both halves of phi
    l = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1)
    nl = l[..., 2]
    totals = np.zeros(4)
    for mu, w in zip(mu_o, w_mu):
        v = np.array([np.sqrt(1 - mu * mu), 0.0, mu])
        h = l + v
        h /= np.linalg.norm(h, axis=-1, keepdims=True)
        nh = h[..., 2]
        fresnel_w = (1 - np.abs(h @ v)) ** 5
        d = a2 / (np.pi * (nh * nh * (a2 - 1) + 1) ** 2)
        specular = d * g(nl, mu, a2) / (4 * nl * mu)
        f = 0.04 + 0.96 * fresnel_w
        terms = ((1 - f) / np.pi, f * specular, (1 - fresnel_w) * specular, fresnel_w * specular)
        albedos = np.array([np.sum(term * nl * dl) for term in terms])
        totals += w * 2 * mu * albedos
    return totals


def furnace(integrals, base, metallic):
    diffuse, dielectric_specular, metal_tint, metal_white = integrals
    dielectric = base * diffuse + dielectric_specular
    metal = base * metal_tint + metal_white
    return (1 - metallic) * dielectric + metallic * metal


def main():
    check = "--check" in sys.argv[1:]
    print("white furnace, sphere's projected disk (hemispherical albedo), glTF 2.0 Appendix B BRDF")
    print("roughness metallic " + " ".join("base %.1f" % b for b in BASES))
    worst = 0.0
    for roughness in ROUGHNESSES:
        integrals = hemispherical_integrals(roughness, g_height_correlated)
        if check:
            fine = hemispherical_integrals(roughness, g_height_correlated, 64, 1024, 1024)
            for metallic in (0.0, 1.0):
                for base in BASES:
                    worst = max(worst, abs(furnace(fine, base, metallic) - furnace(integrals, base, metallic)))
        for metallic in (0.0, 1.0):
            print("%9.2f %8.0f " % (roughness, metallic) +
                  " ".join("%8.5f" % furnace(integrals, base, metallic) for base in BASES))
    if check:
        print("largest change on finer grids (64 x 1024 x 1024): %.2e" % worst)
        print("with the separable Smith G instead (not the specification's):")
        for roughness in ROUGHNESSES:
            integrals = hemispherical_integrals(roughness, g_separable)
            for metallic in (0.0, 1.0):
                print("%9.2f %8.0f " % (roughness, metallic) +
                      " ".join("%8.5f" % furnace(integrals, base, metallic) for base in BASES))


if __name__ == "__main__":
    main()
