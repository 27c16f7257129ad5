// Brute-force integrals of a rough dielectric interface, independent of librender's tables
// (kdray/coat_tables.h): the reflected and refracted energy as integrals of Walter et al.'s (2007)
// GGX BRDF and BTDF (separable Smith masking) over outgoing directions on a fine (theta, phi)
// midpoint grid, and the cosine-weighted hemispherical means built from them.
#pragma once

#include <algorithm>
#include <cmath>

namespace kdray::test {

struct RoughInterface {
  double alpha, eta;  // eta: index of the far side over the near side
  int steps = 400;    // theta and phi steps of the grid

  static constexpr double kPi = 3.14159265358979323846;

  double ggx_d(double cos_h) const {
    const double a2 = alpha * alpha, c2 = cos_h * cos_h, t = c2 * (a2 - 1) + 1;
    return a2 / (kPi * t * t);
  }
  double smith_g1(double cos_v) const {
    const double c2 = cos_v * cos_v;
    return 2 / (1 + std::sqrt(1 + alpha * alpha * (1 - c2) / c2));
  }
  double fresnel(double cos_i) const {
    const double sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return 1;
    const double ct = std::sqrt(1 - sin2_t);
    const double rs = (cos_i - eta * ct) / (cos_i + eta * ct), rp = (eta * cos_i - ct) / (eta * cos_i + ct);
    return 0.5 * (rs * rs + rp * rp);
  }

  // Energy reflected (transmit = false) or refracted for light arriving at cos theta = mu: the
  // integral of f |cos theta_o| over the outgoing hemisphere on that side.
  double energy(double mu, bool transmit) const {
    const double wi[3] = {std::sqrt(1 - mu * mu), 0, mu};
    const double dt = 0.5 * kPi / steps, dp = kPi / steps;  // phi in [0, pi], doubled by symmetry
    double sum = 0;
    for (int a = 0; a < steps; ++a) {
      const double theta = (a + 0.5) * dt, st = std::sin(theta), ct = std::cos(theta);
      for (int b = 0; b < steps; ++b) {
        const double phi = (b + 0.5) * dp;
        const double wo[3] = {st * std::cos(phi), st * std::sin(phi), transmit ? -ct : ct};
        double h[3];
        const double k = transmit ? eta : 1;  // generalised half vector
        for (int c = 0; c < 3; ++c) h[c] = wi[c] + k * wo[c];
        const double len = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        for (double& v : h) v /= (h[2] < 0 ? -len : len);
        const double ih = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2];
        const double oh = wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2];
        if (ih <= 0 || (transmit ? oh >= 0 : oh <= 0)) continue;
        const double g = smith_g1(mu) * smith_g1(ct), d = ggx_d(h[2]);
        double f_cos;  // f |cos theta_o|
        if (transmit) {
          const double denom = ih + eta * oh;
          f_cos = ih * -oh * eta * eta * (1 - fresnel(ih)) * d * g / (mu * denom * denom);
        } else {
          f_cos = fresnel(ih) * d * g / (4 * mu);
        }
        sum += f_cos * st * dt * dp;
      }
    }
    return 2 * sum;
  }

  // 2 * integral of energy(mu) mu dmu: the cosine-weighted mean over the hemisphere.
  double hemispherical_mean(bool transmit, int nodes = 48) const {
    double sum = 0;
    for (int i = 0; i < nodes; ++i) {
      const double mu = (i + 0.5) / nodes;
      sum += energy(mu, transmit) * mu / nodes;
    }
    return 2 * sum;
  }
};

}  // namespace kdray::test
