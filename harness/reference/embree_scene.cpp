#include "harness/reference/embree_scene.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>

#include "harness/util/error.h"

namespace ldm {
namespace {

void throw_on_error(RTCDevice device, const char* what) {
  const RTCError code = rtcGetDeviceError(device);
  if (code != RTC_ERROR_NONE)
    throw GpuError(std::string("Embree: ") + what + " failed (error " + std::to_string(code) + ")");
}

RTCRayHit make_ray_hit(glm::vec3 origin, glm::vec3 direction, float t_near, float t_far) {
  RTCRayHit r;
  std::memset(&r, 0, sizeof r);
  r.ray.org_x = origin.x;
  r.ray.org_y = origin.y;
  r.ray.org_z = origin.z;
  r.ray.dir_x = direction.x;
  r.ray.dir_y = direction.y;
  r.ray.dir_z = direction.z;
  r.ray.tnear = t_near;
  r.ray.tfar = t_far;
  r.ray.mask = 0xFFFFFFFFu;
  r.ray.flags = 0;
  r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  r.hit.primID = RTC_INVALID_GEOMETRY_ID;
  return r;
}

// Collects every hit and rejects it, so that traversal goes on to the next one.
struct AllHitsContext {
  RTCIntersectContext base;  // must come first: Embree passes a pointer to it
  std::vector<RayHit>* hits;
};

void collect_hit(const RTCFilterFunctionNArguments* args) {
  auto* context = reinterpret_cast<AllHitsContext*>(args->context);
  const RTCRay ray = rtcGetRayFromRayN(args->ray, args->N, 0);
  const RTCHit hit = rtcGetHitFromHitN(args->hit, args->N, 0);
  if (args->valid[0] == 0) return;
  context->hits->push_back(RayHit{ray.tfar, hit.primID, hit.u, hit.v});
  args->valid[0] = 0;  // reject: keep looking
}

}  // namespace

EmbreeScene::EmbreeScene(const Scene& scene) : scene_(scene) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw GpuError("Embree: rtcNewDevice failed");
  rtc_scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(rtc_scene_, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(rtc_scene_, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  const auto& mesh = scene.mesh;
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
      mesh.positions.size()));
  std::memcpy(vertices, mesh.positions.data(), mesh.positions.size() * 3 * sizeof(float));
  auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
      mesh.triangles.size()));
  std::memcpy(indices, mesh.triangles.data(), mesh.triangles.size() * 3 * sizeof(uint32_t));
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(rtc_scene_, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(rtc_scene_);
  throw_on_error(device_, "building the scene BVH");
}

EmbreeScene::~EmbreeScene() {
  if (rtc_scene_) rtcReleaseScene(rtc_scene_);
  if (device_) rtcReleaseDevice(device_);
}

std::optional<RayHit> EmbreeScene::intersect(glm::vec3 origin, glm::vec3 direction, float t_near,
                                             float t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit r = make_ray_hit(origin, direction, t_near, t_far);
  rtcIntersect1(rtc_scene_, &context, &r);
  if (r.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return RayHit{r.ray.tfar, r.hit.primID, r.hit.u, r.hit.v};
}

bool EmbreeScene::occluded(glm::vec3 origin, glm::vec3 direction, float t_near,
                           float t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit r = make_ray_hit(origin, direction, t_near, t_far);
  rtcOccluded1(rtc_scene_, &context, &r.ray);
  return r.ray.tfar < 0.0f;  // Embree sets tfar = -inf on a hit
}

std::vector<RayHit> EmbreeScene::all_hit_records(glm::vec3 origin, glm::vec3 direction,
                                                 float t_near, float t_far) const {
  std::vector<RayHit> hits;
  AllHitsContext context;
  rtcInitIntersectContext(&context.base);
  context.base.filter = collect_hit;
  context.hits = &hits;
  RTCRayHit r = make_ray_hit(origin, direction, t_near, t_far);
  rtcIntersect1(rtc_scene_, &context.base, &r);
  // A triangle referenced by several BVH leaves may be reported more than once.
  std::sort(hits.begin(), hits.end(),
            [](const RayHit& a, const RayHit& b) { return a.triangle < b.triangle; });
  hits.erase(std::unique(hits.begin(), hits.end(),
                         [](const RayHit& a, const RayHit& b) { return a.triangle == b.triangle; }),
             hits.end());
  std::sort(hits.begin(), hits.end(), [](const RayHit& a, const RayHit& b) { return a.t < b.t; });
  return hits;
}

std::vector<float> EmbreeScene::all_hits(glm::vec3 origin, glm::vec3 direction, float t_near,
                                         float t_far) const {
  std::vector<float> t;
  for (const RayHit& h : all_hit_records(origin, direction, t_near, t_far)) t.push_back(h.t);
  return t;
}

glm::vec3 EmbreeScene::geometric_normal(uint32_t triangle) const {
  const glm::uvec3 tri = scene_.mesh.triangles[triangle];
  const auto& p = scene_.mesh.positions;
  return glm::normalize(glm::cross(p[tri.y] - p[tri.x], p[tri.z] - p[tri.x]));
}

glm::vec3 EmbreeScene::shading_normal(const RayHit& hit) const {
  const glm::uvec3 tri = scene_.mesh.triangles[hit.triangle];
  const auto& n = scene_.mesh.normals;
  return (1.0f - hit.u - hit.v) * n[tri.x] + hit.u * n[tri.y] + hit.v * n[tri.z];
}

}  // namespace ldm
