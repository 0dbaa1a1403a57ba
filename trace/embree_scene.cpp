// The Embree 3 scene of one frame: the secondary and shadow rays of the path [SVGF17 Sec. 3] (primary
// visibility is rasterized). See embree_scene.h.
//
// Embree's idiom (its "minimal" tutorial), followed step by step here:
//   1. one device per process, with an error callback;
//   2. per mesh: create a geometry, fill its vertex and index buffers, commit it, attach it to the scene,
//      release our reference (the scene keeps its own);
//   3. commit the scene, which builds the BVH;
//   4. per query: initialise an intersect context, then rtcIntersect1 (closest hit) or rtcOccluded1 (any hit).
// Errors: Embree reports them through the callback and through rtcGetDeviceError. The callback only
// records the message (throwing through Embree's C interface is not allowed); throw_if_embree_failed then
// turns the recorded error into an rtdr::Error after each step.
#include "trace/embree_scene.h"

#include "core/error.h"
#include "core/frame.h"

#include <string>

namespace rtdr {
namespace {

// The last message Embree sent to the error callback on this thread (rtcGetDeviceError is per thread too).
thread_local std::string t_last_embree_message;

void record_embree_error(void* /*user_ptr*/, RTCError /*code*/, const char* message) {
  t_last_embree_message = message ? message : "";
}

const char* embree_error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
  }
  return "unrecognised error code";
}

// Throws rtdr::Error when the device has recorded an error on this thread since the last check.
// `step` says what we were doing, e.g. "committing the scene".
void throw_if_embree_failed(RTCDevice device, const std::string& step) {
  const RTCError code = rtcGetDeviceError(device);
  if (code == RTC_ERROR_NONE) return;
  std::string message = "Embree failed while " + step + ": " + embree_error_name(code);
  if (!t_last_embree_message.empty()) message += " (" + t_last_embree_message + ")";
  t_last_embree_message.clear();
  throw Error(message);
}

RTCDevice create_device() {
  RTCDevice device = rtcNewDevice(nullptr);  // nullptr: Embree's default configuration
  if (!device)  // rtcGetDeviceError(nullptr) reports errors of device creation itself
    throw Error(std::string("cannot create the Embree device: ") + embree_error_name(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(device, record_embree_error, nullptr);
  return device;
}

// Owns the process-wide device; releasing it at exit is harmless because every scene holds its own
// reference to the device.
struct DeviceOwner {
  RTCDevice device = create_device();
  ~DeviceOwner() { rtcReleaseDevice(device); }
};

// Adds one instance: its mesh's vertices moved to world space by `to_world`, as triangle geometry number
// `geometry_id` (= the instance index), so a hit's geomID names the instance and its primID the triangle.
void attach_instance(RTCDevice device, RTCScene scene, const Mesh& mesh, const glm::mat4& to_world,
                     unsigned geometry_id) {
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  throw_if_embree_failed(device, "creating the geometry of instance " + std::to_string(geometry_id));

  // Vertex buffer: x, y, z floats per vertex (Embree pads it for its 16-byte loads by itself).
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.positions.size()));
  // Index buffer: three vertex indices per triangle, in the mesh's order, so primID = triangle index.
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), mesh.triangles.size()));
  if (!vertices || !indices) {
    rtcReleaseGeometry(geometry);
    throw_if_embree_failed(device, "allocating the buffers of instance " + std::to_string(geometry_id));
    throw Error("Embree could not allocate the buffers of instance " + std::to_string(geometry_id));
  }
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec3 world = glm::vec3(to_world * glm::vec4(mesh.positions[v], 1.0f));  // a point: w = 1
    vertices[3 * v + 0] = world.x;
    vertices[3 * v + 1] = world.y;
    vertices[3 * v + 2] = world.z;
  }
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    indices[3 * t + 0] = mesh.triangles[t].x;
    indices[3 * t + 1] = mesh.triangles[t].y;
    indices[3 * t + 2] = mesh.triangles[t].z;
  }

  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(scene, geometry, geometry_id);
  rtcReleaseGeometry(geometry);  // the scene holds the geometry now
  throw_if_embree_failed(device, "attaching instance " + std::to_string(geometry_id));
}

// An Embree ray from ours: origin, direction, the [tnear, tfar] interval, every geometry mask bit set.
RTCRay to_embree_ray(const Ray& ray, float tnear, float tfar) {
  RTCRay r{};
  r.org_x = ray.origin.x;
  r.org_y = ray.origin.y;
  r.org_z = ray.origin.z;
  r.dir_x = ray.direction.x;
  r.dir_y = ray.direction.y;
  r.dir_z = ray.direction.z;
  r.tnear = tnear;
  r.tfar = tfar;
  r.time = 0.0f;  // no motion blur: the geometry is already at the pose's time
  r.mask = 0xFFFFFFFFu;
  r.flags = 0;
  return r;
}

}  // namespace

RTCDevice embree_device() {
  // A function-local static is initialised exactly once, even when several threads arrive together
  // (C++11 [stmt.dcl]/4); if creation throws, the next call tries again.
  static const DeviceOwner owner;
  return owner.device;
}

EmbreeScene::EmbreeScene(const Scene& scene, const ScenePose& pose) {
  RTCDevice device = embree_device();
  scene_ = rtcNewScene(device);
  throw_if_embree_failed(device, "creating a scene");
  // ROBUST: Embree's watertight mode, so rays through shared edges never slip between two triangles.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  try {
    for (size_t i = 0; i < scene.instances.size(); ++i) {
      const Mesh& mesh = scene.meshes[size_t(scene.instances[i].mesh)];
      if (mesh.triangles.empty()) continue;  // nothing to hit; the id simply stays unused
      attach_instance(device, scene_, mesh, pose.instance_to_world[i], unsigned(i));
    }
    rtcCommitScene(scene_);  // builds the BVH
    throw_if_embree_failed(device, "committing the scene");
  } catch (...) {
    rtcReleaseScene(scene_);  // the destructor does not run when a constructor throws
    throw;
  }
}

EmbreeScene::~EmbreeScene() { rtcReleaseScene(scene_); }

Hit EmbreeScene::intersect(const Ray& ray, float tnear, float tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit query{};
  query.ray = to_embree_ray(ray, tnear, tfar);
  query.hit.geomID = RTC_INVALID_GEOMETRY_ID;  // stays invalid when nothing is hit
  query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &query);

  Hit hit;  // instance and triangle default to kInvalidId (= RTC_INVALID_GEOMETRY_ID)
  if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.instance = query.hit.geomID;
  hit.triangle = query.hit.primID;
  hit.bary = {query.hit.u, query.hit.v};
  hit.t = query.ray.tfar;  // Embree shortens tfar to the closest hit's distance
  return hit;
}

bool EmbreeScene::occluded(const Ray& ray, float tnear, float tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay query = to_embree_ray(ray, tnear, tfar);
  rtcOccluded1(scene_, &context, &query);
  return query.tfar < 0.0f;  // rtcOccluded1 sets tfar to -inf when it finds any hit
}

static_assert(kInvalidId == RTC_INVALID_GEOMETRY_ID, "a missed ray must carry the visibility buffer's kInvalidId");

}  // namespace rtdr
