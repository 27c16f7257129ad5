// Generated scenes and environments for the environment and punctual light tests.
#pragma once

#include <kdray/environment.h>
#include <kdray/scene.h>

#include <cmath>
#include <memory>

namespace kdray::test {

// A closed, convex UV sphere of radius r around the origin (outward winding), one material,
// seen from +Z by a camera whose view it fills about half of.
inline Scene make_sphere_scene(const Material& material, float r = 1.0f, int stacks = 24, int slices = 48) {
  Scene scene;
  scene.materials.push_back(material);
  const double pi = 3.14159265358979323846;
  scene.positions.push_back({0, r, 0});
  for (int i = 1; i < stacks; ++i) {
    const double theta = pi * i / stacks;
    for (int j = 0; j < slices; ++j) {
      const double phi = 2 * pi * j / slices;
      scene.positions.push_back({float(r * std::sin(theta) * std::cos(phi)), float(r * std::cos(theta)),
                                 float(-r * std::sin(theta) * std::sin(phi))});
    }
  }
  scene.positions.push_back({0, -r, 0});
  const uint32_t bottom = uint32_t(scene.positions.size() - 1);
  auto ring = [&](int i, int j) { return uint32_t(1 + (i - 1) * slices + (j % slices)); };
  auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    scene.indices.insert(scene.indices.end(), {a, b, c});
    scene.material_ids.push_back(0);
  };
  for (int j = 0; j < slices; ++j) {
    add(0, ring(1, j), ring(1, j + 1));
    add(bottom, ring(stacks - 1, j + 1), ring(stacks - 1, j));
    for (int i = 1; i + 1 < stacks; ++i) {
      add(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1));
      add(ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
    }
  }
  Camera camera;
  camera.position = {0, 0, 4 * r};
  camera.target = {0, 0, 0};
  camera.vertical_fov_degrees = 40;
  scene.cameras.push_back(camera);
  return scene;
}

inline std::shared_ptr<const Environment> shared_environment(Environment env) {
  return std::make_shared<const Environment>(std::move(env));
}

// A map whose red channel is the column index and green channel the row index (blue 0): a
// lookup's result tells where it looked.
inline Environment coordinate_environment(uint32_t width, uint32_t height) {
  Environment env;
  env.source = "coordinates";
  env.width = width;
  env.height = height;
  for (uint32_t j = 0; j < height; ++j)
    for (uint32_t i = 0; i < width; ++i) env.rgb.insert(env.rgb.end(), {float(i), float(j), 0.0f});
  return env;
}

// A dim sky with a bright, smooth "sun" (a Gaussian a few pixels wide) and a black lower half:
// far from uniform, so light and BSDF sampling differ a lot, yet smooth enough that light
// sampling alone (the bilinear lookup against a piecewise-constant table) has bounded variance.
inline Environment sun_environment(uint32_t width = 64, uint32_t height = 32) {
  Environment env;
  env.source = "sun";
  env.width = width;
  env.height = height;
  const double cx = width / 3.0, cy = height / 5.0, sigma = 1.5;
  for (uint32_t j = 0; j < height; ++j) {
    for (uint32_t i = 0; i < width; ++i) {
      const double r2 = ((i - cx) * (i - cx) + (j - cy) * (j - cy)) / (sigma * sigma);
      const float sun = float(50 * std::exp(-0.5 * r2));
      const float sky = j < height / 2 ? 0.2f : 0.0f;
      env.rgb.insert(env.rgb.end(), {sky + sun, sky + 0.75f * sun, 2 * sky + 0.5f * sun});
    }
  }
  return env;
}

}  // namespace kdray::test
