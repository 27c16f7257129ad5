// The rough coat's tables for bench/materials.sh: the time to build them for one eta (median of
// five etas near ETA, as librender keeps the blocks it has built), and the diffuse term of kdray's plastic (kernels/pt_bsdf.h with the table
// lookups of kernels/pt_coat.h, compiled here as C++) for a white base, light arriving along the
// normal, at the alphas and outgoing angles given, to set beside Mitsuba 3's roughplastic.
// usage: coat_bench ETA ALPHA,... DEGREES,...   (prints "alpha degrees value" lines, then the time)
#include <kdray/coat_tables.h>

#include <kernels/pt_coat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::vector<double> numbers(const std::string& list) {
  std::vector<double> values;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');) values.push_back(std::atof(item.c_str()));
  return values;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: coat_bench ETA ALPHA,... DEGREES,...\n");
    return 2;
  }
  const float eta = float(std::atof(argv[1]));
  const double pi = 3.14159265358979323846;
  std::vector<double> seconds;
  std::vector<float> table;
  for (int run = 0; run < 5; ++run) {
    const auto start = std::chrono::steady_clock::now();
    table = kdray::build_coat_tables({eta * (1 + 0.01f * float(run - 2))});
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  table = kdray::build_coat_tables({eta});
  for (double alpha : numbers(argv[2]))
    for (double degrees : numbers(argv[3])) {
      const PtCoatRow row = pt_coat_row(table.data(), eta, float(alpha));
      const float t_i = pt_coat_transmittance(table.data(), row, 1.0f);
      const float t_o = pt_coat_transmittance(table.data(), row, float(std::cos(degrees * pi / 180)));
      const float f_int = pt_coat_internal_reflectance(table.data(), row);
      std::printf("%g %g %.6f\n", alpha, degrees, t_i * t_o / (pi * eta * eta * (1 - f_int)));
    }
  std::sort(seconds.begin(), seconds.end());
  std::printf("table build seconds (one eta, median of 5): %.4f\n", seconds[2]);
  return 0;
}
