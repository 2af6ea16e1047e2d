#include "embree_tracer.h"

#include <chrono>
#include <stdexcept>

#include <embree3/rtcore.h>

namespace whisker::bench {

struct EmbreeScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

EmbreeScene* embree_build(const std::vector<Triangle>& tris, double& build_seconds) {
  auto* s = new EmbreeScene;
  s->device = rtcNewDevice(nullptr);
  if (!s->device) throw std::runtime_error("rtcNewDevice failed");
  const auto start = std::chrono::steady_clock::now();
  s->scene = rtcNewScene(s->device);
  rtcSetSceneBuildQuality(s->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry g = rtcNewGeometry(s->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * tris.size()));
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris.size()));
  for (std::size_t i = 0; i < tris.size(); ++i) {
    const vec3* p[3] = {&tris[i].v0, &tris[i].v1, &tris[i].v2};
    for (int k = 0; k < 3; ++k) {
      v[9 * i + 3 * k + 0] = p[k]->x;
      v[9 * i + 3 * k + 1] = p[k]->y;
      v[9 * i + 3 * k + 2] = p[k]->z;
      idx[3 * i + k] = static_cast<unsigned>(3 * i + k);
    }
  }
  rtcCommitGeometry(g);
  rtcAttachGeometry(s->scene, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(s->scene);
  build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

bool embree_intersect(const EmbreeScene* s, const Ray& ray, float& t) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  rh.ray.org_x = ray.o.x;
  rh.ray.org_y = ray.o.y;
  rh.ray.org_z = ray.o.z;
  rh.ray.dir_x = ray.d.x;
  rh.ray.dir_y = ray.d.y;
  rh.ray.dir_z = ray.d.z;
  rh.ray.tnear = ray.tmin;
  rh.ray.tfar = ray.tmax;
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xffffffffu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(s->scene, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  t = rh.ray.tfar;
  return true;
}

void embree_release(EmbreeScene* s) {
  if (!s) return;
  rtcReleaseScene(s->scene);
  rtcReleaseDevice(s->device);
  delete s;
}

}  // namespace whisker::bench
