// embree_trace SCENE.kdscene RAYS [THREADS] [--robust] [--packets16] [--hits OUT]: the yardstick
// of bench/traverse.sh. Traces a kdray ray file with Embree 3 (rtcIntersect1, one ray at a time,
// high-quality BVH build) and prints one line: rays, hits, seconds, Mrays/s. --packets16 traces
// 16 consecutive rays of the file per rtcIntersect16 call instead: the hybrid packet entry point
// Mitsuba 3's LLVM backend traces its lanes' rays with (packet traversal where the rays run
// together, one ray at a time below where they part). Built by bench/traverse.sh itself against
// Debian's libembree-dev, never by the project's CMake.
// Reads only what it needs of the .kdscene container (formats/container.md, kdscene.md):
// the positions (section 1) and indices (section 2); no checksum check (the file is kdray's).
#include <embree3/rtcore.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

namespace {

struct Ray {
  float ox, oy, oz, dx, dy, dz, tmin, tmax;
};
struct Hit {
  float t;
  uint32_t triangle;
  float u, v;
};

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "embree_trace: %s\n", message.c_str());
  std::exit(1);
}

std::vector<char> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path + ": cannot open");
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}

template <typename T>
T at(const std::vector<char>& bytes, size_t offset) {
  T value;
  if (offset + sizeof(T) > bytes.size()) fail("truncated file");
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

// Section `id` of a kdray container as (offset, size).
std::pair<uint64_t, uint64_t> section(const std::vector<char>& file, uint32_t id, const std::string& path) {
  if (file.size() < 64 || std::memcmp(file.data(), "KDSCENE", 8) != 0) fail(path + ": not a kdscene file");
  const uint32_t count = at<uint32_t>(file, 48);
  for (uint32_t i = 0; i < count; ++i) {
    const size_t entry = 64 + 24 * size_t{i};
    if (at<uint32_t>(file, entry) != id) continue;
    const uint64_t offset = at<uint64_t>(file, entry + 8), size = at<uint64_t>(file, entry + 16);
    if (offset + size > file.size()) fail(path + ": section outside the file");
    return {offset, size};
  }
  fail(path + ": section " + std::to_string(id) + " missing");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) fail("usage: embree_trace SCENE.kdscene RAYS [THREADS] [--robust] [--packets16] [--hits OUT]");
  const std::string scene_path = argv[1], rays_path = argv[2];
  unsigned threads = 2;
  bool robust = false, packets16 = false;
  std::string hits_path;
  for (int i = 3; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--robust") robust = true;
    else if (arg == "--packets16") packets16 = true;
    else if (arg == "--hits" && i + 1 < argc) hits_path = argv[++i];
    else threads = static_cast<unsigned>(std::atoi(argv[i]));
  }
  const std::vector<char> scene_file = read_file(scene_path);
  const auto positions = section(scene_file, 1, scene_path);
  const auto indices = section(scene_file, 2, scene_path);
  const size_t vertex_count = positions.second / 12, triangle_count = indices.second / 12;

  const std::vector<char> ray_bytes = read_file(rays_path);
  if (ray_bytes.size() % sizeof(Ray) != 0) fail(rays_path + ": not a ray file (size)");
  std::vector<Ray> rays(ray_bytes.size() / sizeof(Ray));
  std::memcpy(rays.data(), ray_bytes.data(), ray_bytes.size());

  RTCDevice device = rtcNewDevice(("threads=" + std::to_string(threads)).c_str());
  if (!device) fail("rtcNewDevice failed");
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  if (robust) rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
  float* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, vertex_count));
  std::memcpy(vertices, scene_file.data() + positions.first, positions.second);
  uint32_t* triangles = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, triangle_count));
  std::memcpy(triangles, scene_file.data() + indices.first, indices.second);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);

  std::vector<Hit> hits(rays.size());
  std::atomic<size_t> next{0};
  // Rays [first, end) 16 at a time through rtcIntersect16, the last packet's spare lanes invalid.
  auto trace_packets16 = [&](size_t first, size_t end) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (size_t i = first; i < end; i += 16) {
      alignas(64) RTCRayHit16 packet;
      alignas(64) int valid[16];
      for (int l = 0; l < 16; ++l) {
        valid[l] = i + l < end ? -1 : 0;
        const Ray& r = rays[i + l < end ? i + l : i];
        packet.ray.org_x[l] = r.ox, packet.ray.org_y[l] = r.oy, packet.ray.org_z[l] = r.oz;
        packet.ray.dir_x[l] = r.dx, packet.ray.dir_y[l] = r.dy, packet.ray.dir_z[l] = r.dz;
        packet.ray.tnear[l] = r.tmin > 0 ? r.tmin : 0.0f;
        packet.ray.tfar[l] = r.tmax;
        packet.ray.time[l] = 0;
        packet.ray.mask[l] = 0xFFFFFFFFu;
        packet.ray.id[l] = 0;
        packet.ray.flags[l] = 0;
        packet.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
        packet.hit.instID[0][l] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect16(valid, scene, &context, &packet);
      for (size_t l = 0; l < 16 && i + l < end; ++l)
        hits[i + l] = packet.hit.geomID[l] == RTC_INVALID_GEOMETRY_ID
                          ? Hit{INFINITY, 0xFFFFFFFFu, 0, 0}
                          : Hit{packet.ray.tfar[l], packet.hit.primID[l], packet.hit.u[l], packet.hit.v[l]};
    }
  };
  auto worker = [&] {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    constexpr size_t kBatch = 1024;
    for (;;) {
      const size_t first = next.fetch_add(kBatch);
      if (first >= rays.size()) break;
      const size_t end = std::min(first + kBatch, rays.size());
      if (packets16) {
        trace_packets16(first, end);
        continue;
      }
      for (size_t i = first; i < end; ++i) {
        const Ray& r = rays[i];
        RTCRayHit rh;
        rh.ray.org_x = r.ox;
        rh.ray.org_y = r.oy;
        rh.ray.org_z = r.oz;
        rh.ray.dir_x = r.dx;
        rh.ray.dir_y = r.dy;
        rh.ray.dir_z = r.dz;
        rh.ray.tnear = r.tmin > 0 ? r.tmin : 0.0f;
        rh.ray.tfar = r.tmax;
        rh.ray.time = 0;
        rh.ray.mask = 0xFFFFFFFFu;
        rh.ray.id = 0;
        rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) hits[i] = Hit{INFINITY, 0xFFFFFFFFu, 0, 0};
        else hits[i] = Hit{rh.ray.tfar, rh.hit.primID, rh.hit.u, rh.hit.v};
      }
    }
  };
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  size_t hit_count = 0;
  for (const Hit& h : hits) hit_count += h.triangle != 0xFFFFFFFFu ? 1 : 0;
  std::printf("%zu rays, %zu hits in %.3f s: %.2f Mrays/s\n", rays.size(), hit_count, seconds,
              static_cast<double>(rays.size()) / seconds / 1e6);
  if (!hits_path.empty()) {
    std::ofstream out(hits_path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(hits.data()), static_cast<std::streamsize>(hits.size() * sizeof(Hit)));
    if (!out) fail(hits_path + ": cannot write");
  }
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  return 0;
}
