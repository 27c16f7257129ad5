// The rough dielectric coat's tables (see kdray/coat_tables.h and kernels/pt_coat.h). Each value
// is an expectation over the GGX distribution of normals visible from the incident direction
// (sampled as in Heitz 2018, "Sampling the GGX Distribution of Visible Normals"), integrated with
// a product Gauss-Legendre rule over the sampler's unit square.
#include <kdray/coat_tables.h>

#include <kernels/pt_coat.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

namespace kdray {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Radii of the visible-normal disc (and half as many angles); the interface seen from inside has
// total internal reflection, whose edge crosses the disc, so it takes more. With these, values
// are within 5e-4 of those of rules 4x as fine in each dimension (eta 1.33 to 2).
constexpr int kOutsideNodes = 24, kInsideNodes = 48;
// Nodes per piece of the cosine integral of the internal reflectance (split at the critical
// angle, where the smooth interface's reflectance has its kink).
constexpr int kCosineNodes = 12;
// The GGX code's smallest alpha (pt_ggx_alpha2 in kernels/pt_bsdf.h).
constexpr double kMinAlpha = 1e-3;

struct V3 {
  double x, y, z;
};
V3 operator*(double s, V3 v) { return {s * v.x, s * v.y, s * v.z}; }
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 normalized(V3 v) { return (1.0 / std::sqrt(dot(v, v))) * v; }

struct Rule {
  std::vector<double> nodes, weights;  // on [0, 1], weights summing to 1
};

// Gauss-Legendre nodes by Newton's iteration on the Legendre polynomial P_n.
Rule gauss_legendre(int n) {
  Rule rule;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5)), derivative = 1;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-15) break;
    }
    rule.nodes.push_back(0.5 * (1 - x));
    rule.weights.push_back(1 / ((1 - x * x) * derivative * derivative));
  }
  return rule;
}

// A product rule over the visible-normal sampler's disc (radius sqrt(u1), angle phi): n radii
// and n / 2 angles in [-pi/2, pi/2]. The incident direction lies in the xz plane, so phi and
// pi - phi give normals mirrored in it and equal values: half of the angles cover the disc.
struct DiscRule {
  std::vector<double> radius, radius_weight, cos_angle, sin_angle, angle_weight;
};
DiscRule disc_rule(int n) {
  DiscRule disc;
  const Rule radii = gauss_legendre(n), angles = gauss_legendre(n / 2);
  for (int i = 0; i < n; ++i) {
    disc.radius.push_back(std::sqrt(radii.nodes[i]));
    disc.radius_weight.push_back(radii.weights[i]);
  }
  for (int j = 0; j < n / 2; ++j) {
    const double phi = kPi * (angles.nodes[j] - 0.5);
    disc.cos_angle.push_back(std::cos(phi));
    disc.sin_angle.push_back(std::sin(phi));
    disc.angle_weight.push_back(angles.weights[j]);
  }
  return disc;
}

// A GGX normal visible from wi = (sin, 0, cos) (upper hemisphere), for the point of the unit
// square at radius r = sqrt(u1) and angle phi = 2 pi u2.
V3 sample_visible_normal(V3 wi, double alpha, double r, double cos_phi, double sin_phi) {
  const V3 v = normalized({alpha * wi.x, 0, wi.z});
  const V3 t1 = v.x > 0 ? V3{0, 1, 0} : V3{1, 0, 0};
  const V3 t2 = {v.y * t1.z - v.z * t1.y, v.z * t1.x - v.x * t1.z, v.x * t1.y - v.y * t1.x};
  const double a = r * cos_phi, s = 0.5 * (1 + v.z);
  const double b = (1 - s) * std::sqrt(std::max(0.0, 1 - a * a)) + s * r * sin_phi;
  const V3 h = a * t1 + b * t2 + std::sqrt(std::max(0.0, 1 - a * a - b * b)) * v;
  return normalized({alpha * h.x, alpha * h.y, std::max(0.0, h.z)});
}

// Smith masking of direction w for microfacet normal m; a facet is never seen from its back.
double smith_g1(V3 w, V3 m, double alpha) {
  if (dot(w, m) * w.z <= 0) return 0;
  const double tan2 = std::max(0.0, 1 - w.z * w.z) / (w.z * w.z);
  return 2 / (1 + std::sqrt(1 + alpha * alpha * tan2));
}

// Fresnel reflectance at cos_i (> 0) into relative index eta, and the refracted cosine (0 under
// total internal reflection).
double fresnel(double cos_i, double eta, double* cos_t) {
  const double sin2_t = (1 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1) {
    *cos_t = 0;
    return 1;
  }
  *cos_t = std::sqrt(1 - sin2_t);
  const double rs = (cos_i - eta * *cos_t) / (cos_i + eta * *cos_t);
  const double rp = (eta * cos_i - *cos_t) / (eta * cos_i + *cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

// Reflected (transmit = false) or refracted energy at cos_theta.
double lobe_energy(double cos_theta, double alpha, double eta, bool transmit) {
  alpha = std::max(alpha, kMinAlpha);
  cos_theta = std::clamp(cos_theta, 1e-6, 1.0);
  const V3 wi{std::sqrt(1 - cos_theta * cos_theta), 0, cos_theta};
  static const DiscRule outside = disc_rule(kOutsideNodes), inside = disc_rule(kInsideNodes);
  const DiscRule& r = eta < 1 ? inside : outside;
  double sum = 0;
  for (size_t i = 0; i < r.radius.size(); ++i)
    for (size_t j = 0; j < r.cos_angle.size(); ++j) {
      const V3 m = sample_visible_normal(wi, alpha, r.radius[i], r.cos_angle[j], r.sin_angle[j]);
      const double c = dot(wi, m);
      if (c <= 0) continue;
      double cos_t;
      const double f = fresnel(c, eta, &cos_t);
      double value;
      if (transmit) {
        const V3 wt = (-1 / eta) * wi + (c / eta - cos_t) * m;
        value = f < 1 && wt.z < 0 ? (1 - f) * smith_g1(wt, m, alpha) : 0;
      } else {
        const V3 wr = (2 * c) * m + (-1.0) * wi;
        value = wr.z > 0 ? f * smith_g1(wr, m, alpha) : 0;
      }
      sum += r.radius_weight[i] * r.angle_weight[j] * value;
    }
  return sum;
}

}  // namespace

double rough_dielectric_transmittance(double cos_theta, double alpha, double eta) {
  return lobe_energy(cos_theta, alpha, eta, true);
}

double rough_dielectric_reflectance(double cos_theta, double alpha, double eta) {
  return lobe_energy(cos_theta, alpha, eta, false);
}

double rough_dielectric_internal_reflectance(double alpha, double eta) {
  const double critical = eta > 1 ? std::sqrt(1 - 1 / (eta * eta)) : 0;
  static const Rule r = gauss_legendre(kCosineNodes);
  double sum = 0;
  for (auto [lo, hi] : {std::pair{0.0, critical}, std::pair{critical, 1.0}}) {
    if (hi <= lo) continue;
    for (size_t i = 0; i < r.nodes.size(); ++i) {
      const double mu = lo + (hi - lo) * r.nodes[i];
      sum += (hi - lo) * r.weights[i] * rough_dielectric_reflectance(mu, alpha, 1 / eta) * mu;
    }
  }
  return 2 * sum;
}

std::vector<float> build_coat_tables(const std::vector<float>& etas) {
  // A block costs about 0.2 s of one core's time and depends on eta alone: batches (kdrender --jobs)
  // upload their scene once per frame, so blocks are kept for the life of the process.
  static std::mutex mutex;
  static std::map<float, std::vector<float>> blocks;
  std::vector<float> unique;
  for (float eta : etas)
    if (std::find(unique.begin(), unique.end(), eta) == unique.end()) unique.push_back(eta);
  std::vector<float> table{float(unique.size())};
  table.insert(table.end(), unique.begin(), unique.end());
  std::lock_guard<std::mutex> lock(mutex);
  for (float eta : unique) {
    std::vector<float>& block = blocks[eta];
    if (block.empty()) {
      // Rows are independent: one task each, every value written to its own place.
      block.resize(PT_COAT_BLOCK);
      tbb::parallel_for(0, PT_COAT_ALPHAS, [&block, eta](int j) {
        const double roughness = double(j) / (PT_COAT_ALPHAS - 1);
        const double alpha = roughness * roughness;
        float* row = block.data() + size_t(j) * PT_COAT_ROW;
        row[0] = float(rough_dielectric_internal_reflectance(alpha, eta));
        for (int i = 0; i < PT_COAT_COSINES; ++i)
          row[1 + i] = float(rough_dielectric_transmittance(double(i) / (PT_COAT_COSINES - 1), alpha, eta));
      });
    }
    table.insert(table.end(), block.begin(), block.end());
  }
  return table;
}

}  // namespace kdray
