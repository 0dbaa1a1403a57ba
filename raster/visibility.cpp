// The visibility-buffer rasterizer [ASVGF18 Sec. 3.1: primary visibility as (instance, triangle, barycentrics)].
// Conventions in raster/visibility.h; the walk-through in raster/README.md.
//
// Three steps:
//   1. clip:  each triangle is clipped in homogeneous clip space to w >= znear and to the guard band; every
//             clipped vertex carries its barycentrics in the ORIGINAL triangle (clip space is a linear image of
//             object space, so barycentrics interpolate along a clipped edge exactly like the coordinates).
//   2. setup: the clipped polygon is cut into a fan of sub-triangles; each gets snapped integer edge functions
//             (coverage) and three screen-space planes, 1/w, b1/w and b2/w (perspective-correct interpolation).
//   3. walk:  horizontal bands of rows run in parallel; each band walks every sub-triangle in input order and
//             keeps the nearest sample per pixel centre.
#include "raster/visibility.h"

#include "core/error.h"
#include "core/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace rtdr {
namespace {

// Rows per band of the parallel walk: small enough for load balance, large enough to amortise the
// per-band scan over all triangles.
constexpr int kBandRows = 8;

// ---------------------------------------------------------------------------------------------------------
// 1. Clipping in homogeneous clip space (Sutherland-Hodgman against one plane at a time).

// A polygon vertex: clip-space position and barycentrics (b1, b2) in the original triangle. Double precision,
// because far out in the guard band float's 24 bits would not resolve the 1/256-pixel snapping grid.
struct ClipVertex {
  glm::dvec4 clip;
  glm::dvec2 bary;
};

// 3 vertices plus at most one more per clipping plane (1 near + 4 guard-band planes).
struct ClipPolygon {
  std::array<ClipVertex, 8> vertices;
  int count = 0;
  void push(const ClipVertex& v) { vertices[size_t(count++)] = v; }
};

// The half-space dot(coefficients, clip) >= offset.
struct ClipPlane {
  glm::dvec4 coefficients;
  double offset;
  double distance(const glm::dvec4& clip) const { return glm::dot(coefficients, clip) - offset; }
};

ClipPolygon clip_against(const ClipPolygon& polygon, const ClipPlane& plane) {
  ClipPolygon out;
  for (int i = 0; i < polygon.count; ++i) {
    const ClipVertex& a = polygon.vertices[size_t(i)];
    const ClipVertex& b = polygon.vertices[size_t((i + 1) % polygon.count)];
    const double da = plane.distance(a.clip), db = plane.distance(b.clip);
    if (da >= 0.0) out.push(a);                   // a is inside: keep it
    if ((da >= 0.0) == (db >= 0.0)) continue;     // the edge a-b does not cross the plane
    // The crossing point, always interpolated from the inside end to the outside end, so two triangles
    // sharing this edge (walking it in opposite directions) compute bit-identical points: no cracks.
    const ClipVertex& in = da >= 0.0 ? a : b;
    const ClipVertex& outside = da >= 0.0 ? b : a;
    const double d_in = std::max(da, db), d_out = std::min(da, db);
    const double s = d_in / (d_in - d_out);
    out.push({in.clip + s * (outside.clip - in.clip), in.bary + s * (outside.bary - in.bary)});
  }
  return out;
}

// The near plane w >= znear, then the guard band: screen x in [-G, width + G] is, with ndc x = x / w and
// screen x = (ndc x + 1) / 2 * width, the pair x + g_x w >= 0 and g_x w - x >= 0 with g_x = 1 + 2 G / width
// (w > 0 after the near plane). Likewise for y with the height.
std::array<ClipPlane, 5> clip_planes(int width, int height, double znear) {
  const double gx = 1.0 + 2.0 * kGuardBandPixels / width;
  const double gy = 1.0 + 2.0 * kGuardBandPixels / height;
  return {{{{0.0, 0.0, 0.0, 1.0}, znear},
           {{1.0, 0.0, 0.0, gx}, 0.0},
           {{-1.0, 0.0, 0.0, gx}, 0.0},
           {{0.0, 1.0, 0.0, gy}, 0.0},
           {{0.0, -1.0, 0.0, gy}, 0.0}}};
}

// ---------------------------------------------------------------------------------------------------------
// 2. Setup of one sub-triangle.

// An edge function E(p) = (b - a) x (p - a) in snapped sub-pixel units. With our y-down screen and the
// vertices ordered so the area is positive, E > 0 inside. `bias` is 0 on top/left edges and -1 otherwise,
// so "E + bias >= 0" is the top-left rule on integers.
struct EdgeFunction {
  int64_t ax, ay, dx, dy, bias;
  int64_t at(int64_t px, int64_t py) const { return dx * (py - ay) - dy * (px - ax) + bias; }
};

// An affine function of the continuous screen position, anchored at a vertex to keep the evaluation precise.
struct ScreenPlane {
  double x0, y0, value0, ddx, ddy;
  double at(double x, double y) const { return value0 + ddx * (x - x0) + ddy * (y - y0); }
};

// One sub-triangle ready to walk: ids, edge functions, pixel bounds (inclusive), interpolation planes.
struct RasterTriangle {
  uint32_t instance, triangle;
  std::array<EdgeFunction, 3> edges;
  int x_min, x_max, y_min, y_max;
  ScreenPlane inv_w, b1_over_w, b2_over_w;
};

// A clipped vertex after the perspective divide: exact screen position, snapped position, 1/w, barycentrics.
struct ScreenVertex {
  glm::dvec2 screen;
  int64_t fx, fy;
  double inv_w;
  glm::dvec2 bary;
};

ScreenVertex to_screen(const ClipVertex& v, int width, int height) {
  ScreenVertex s;
  s.inv_w = 1.0 / v.clip.w;
  const double ndc_x = v.clip.x * s.inv_w, ndc_y = v.clip.y * s.inv_w;
  s.screen = {(ndc_x * 0.5 + 0.5) * width, (0.5 - ndc_y * 0.5) * height};  // y flips: screen y is down
  s.fx = std::llround(s.screen.x * double(kSubpixels));                    // snap to the 1/256-pixel grid
  s.fy = std::llround(s.screen.y * double(kSubpixels));
  s.bary = v.bary;
  return s;
}

// Top-left rule for a positively oriented triangle on our y-down screen: a TOP edge is horizontal with
// the interior below it, which for this orientation means it runs in +x (dy == 0, dx > 0); a LEFT edge
// has the interior to its right, which means it runs upwards (dy < 0). Pixel centres exactly on such an
// edge are covered; on the other (bottom, right) edges they are not.
EdgeFunction make_edge(const ScreenVertex& a, const ScreenVertex& b) {
  const int64_t dx = b.fx - a.fx, dy = b.fy - a.fy;
  const bool top = dy == 0 && dx > 0;
  const bool left = dy < 0;
  return {a.fx, a.fy, dx, dy, (top || left) ? 0 : -1};
}

// The plane through three (screen position, value) pairs: solve [e1; e2] * gradient = [f1 - f0; f2 - f0].
ScreenPlane make_plane(const std::array<ScreenVertex, 3>& v, double f0, double f1, double f2, double det) {
  const glm::dvec2 e1 = v[1].screen - v[0].screen, e2 = v[2].screen - v[0].screen;
  const double ddx = ((f1 - f0) * e2.y - (f2 - f0) * e1.y) / det;
  const double ddy = ((f2 - f0) * e1.x - (f1 - f0) * e2.x) / det;
  return {v[0].screen.x, v[0].screen.y, f0, ddx, ddy};
}

int64_t floor_div(int64_t a, int64_t b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0))); }

// Builds the RasterTriangle of one fan sub-triangle; false when it covers no pixel centre of the image.
bool setup_sub_triangle(std::array<ScreenVertex, 3> v, int width, int height, RasterTriangle& t) {
  // Twice the snapped signed area. Both faces are drawn, so a negative one is made positive by swapping
  // vertices 1 and 2 (each carries its own barycentrics, so nothing else changes).
  const int64_t area2 = (v[1].fx - v[0].fx) * (v[2].fy - v[0].fy) - (v[1].fy - v[0].fy) * (v[2].fx - v[0].fx);
  if (area2 == 0) return false;  // degenerate on the snapping grid: covers nothing
  if (area2 < 0) std::swap(v[1], v[2]);
  // Pixel bounds: x such that the centre x*256 + 128 lies in [min fx, max fx], clamped to the image.
  const int64_t min_fx = std::min({v[0].fx, v[1].fx, v[2].fx}), max_fx = std::max({v[0].fx, v[1].fx, v[2].fx});
  const int64_t min_fy = std::min({v[0].fy, v[1].fy, v[2].fy}), max_fy = std::max({v[0].fy, v[1].fy, v[2].fy});
  const int64_t half = kSubpixels / 2;
  t.x_min = int(std::max<int64_t>(0, -floor_div(-(min_fx - half), kSubpixels)));
  t.y_min = int(std::max<int64_t>(0, -floor_div(-(min_fy - half), kSubpixels)));
  t.x_max = int(std::min<int64_t>(width - 1, floor_div(max_fx - half, kSubpixels)));
  t.y_max = int(std::min<int64_t>(height - 1, floor_div(max_fy - half, kSubpixels)));
  if (t.x_min > t.x_max || t.y_min > t.y_max) return false;
  // Edge k is opposite vertex k.
  t.edges = {make_edge(v[1], v[2]), make_edge(v[2], v[0]), make_edge(v[0], v[1])};
  // 1/w and b/w are affine in screen space, so they are planes; from them b = (b/w) / (1/w) is the
  // perspective-correct barycentric. Planes use the exact (unsnapped) positions, so the barycentrics are
  // those of the true pixel-centre ray; only coverage sees the snapped grid.
  const double det = (v[1].screen.x - v[0].screen.x) * (v[2].screen.y - v[0].screen.y) -
                     (v[1].screen.y - v[0].screen.y) * (v[2].screen.x - v[0].screen.x);
  if (det == 0.0) return false;
  t.inv_w = make_plane(v, v[0].inv_w, v[1].inv_w, v[2].inv_w, det);
  t.b1_over_w = make_plane(v, v[0].bary.x * v[0].inv_w, v[1].bary.x * v[1].inv_w, v[2].bary.x * v[2].inv_w, det);
  t.b2_over_w = make_plane(v, v[0].bary.y * v[0].inv_w, v[1].bary.y * v[1].inv_w, v[2].bary.y * v[2].inv_w, det);
  return true;
}

// Clips one triangle and appends the sub-triangles of its clipped polygon (a fan around its first vertex).
void setup_triangle(const ClipTriangle& tri, const std::array<ClipPlane, 5>& planes, int width, int height,
                    std::vector<RasterTriangle>& out) {
  ClipPolygon polygon;
  polygon.push({glm::dvec4(tri.clip[0]), {0.0, 0.0}});  // vertex 0: b0 = 1
  polygon.push({glm::dvec4(tri.clip[1]), {1.0, 0.0}});  // vertex 1: b1 = 1
  polygon.push({glm::dvec4(tri.clip[2]), {0.0, 1.0}});  // vertex 2: b2 = 1
  for (const ClipPlane& plane : planes) {
    polygon = clip_against(polygon, plane);
    if (polygon.count < 3) return;  // entirely behind the near plane or outside the guard band
  }
  std::array<ScreenVertex, 8> screen;
  for (int i = 0; i < polygon.count; ++i) screen[size_t(i)] = to_screen(polygon.vertices[size_t(i)], width, height);
  for (int i = 1; i + 1 < polygon.count; ++i) {
    RasterTriangle t{tri.instance, tri.triangle, {}, 0, 0, 0, 0, {}, {}, {}};
    if (setup_sub_triangle({screen[0], screen[size_t(i)], screen[size_t(i + 1)]}, width, height, t)) out.push_back(t);
  }
}

// ---------------------------------------------------------------------------------------------------------
// 3. The walk.

// Depth test and write of one covered pixel centre (x + 0.5, y + 0.5).
void write_if_nearer(const RasterTriangle& t, int x, int y, VisibilityBuffer& vis) {
  const double sx = x + 0.5, sy = y + 0.5;
  const double inv_w = t.inv_w.at(sx, sy);  // 1/depth, affine in screen space
  const float depth = float(1.0 / inv_w);
  const size_t i = vis.index(x, y);
  if (!(depth < vis.depth[i])) return;      // nearest wins; strictly, so on a tie the earlier triangle stays
  // Perspective-correct barycentrics of the original triangle: (b/w) / (1/w).
  double b1 = t.b1_over_w.at(sx, sy) / inv_w;
  double b2 = t.b2_over_w.at(sx, sy) / inv_w;
  // Snapping may cover a centre up to 1/512 pixel outside the exact triangle: clamp into the triangle so
  // every stored sample lies on its surface.
  b1 = std::clamp(b1, 0.0, 1.0);
  b2 = std::clamp(b2, 0.0, 1.0 - b1);
  vis.instance[i] = t.instance;
  vis.triangle[i] = t.triangle;
  vis.bary[i] = {float(b1), float(b2)};
  vis.depth[i] = depth;
}

// Rasterizes every sub-triangle, in order, into rows [y_begin, y_end). Rows of other bands are not touched,
// so bands can run in parallel and the result does not depend on how they are scheduled.
void rasterize_band(const std::vector<RasterTriangle>& triangles, int y_begin, int y_end, VisibilityBuffer& vis) {
  // Start from "nothing seen yet": background ids, and an infinite depth for the depth test.
  const size_t first = vis.index(0, y_begin), last = vis.index(0, y_end);
  for (size_t i = first; i < last; ++i) {
    vis.instance[i] = vis.triangle[i] = kInvalidId;
    vis.bary[i] = glm::vec2(0.0f);
    vis.depth[i] = std::numeric_limits<float>::infinity();
  }
  for (const RasterTriangle& t : triangles) {
    const int row_begin = std::max(t.y_min, y_begin), row_end = std::min(t.y_max + 1, y_end);
    for (int y = row_begin; y < row_end; ++y) {
      // Edge values at the first pixel centre of the row, in sub-pixel units.
      const int64_t px = int64_t(t.x_min) * kSubpixels + kSubpixels / 2;
      const int64_t py = int64_t(y) * kSubpixels + kSubpixels / 2;
      int64_t e0 = t.edges[0].at(px, py), e1 = t.edges[1].at(px, py), e2 = t.edges[2].at(px, py);
      // One pixel to the right changes E = dx (py - ay) - dy (px - ax) by -dy * 256.
      const int64_t step0 = -t.edges[0].dy * kSubpixels, step1 = -t.edges[1].dy * kSubpixels,
                    step2 = -t.edges[2].dy * kSubpixels;
      for (int x = t.x_min; x <= t.x_max; ++x) {
        if (e0 >= 0 && e1 >= 0 && e2 >= 0) write_if_nearer(t, x, y, vis);  // inside all three edges
        e0 += step0;
        e1 += step1;
        e2 += step2;
      }
    }
  }
  for (size_t i = first; i < last; ++i)
    if (vis.instance[i] == kInvalidId) vis.depth[i] = 0.0f;  // background depth is 0 by convention
}

}  // namespace

VisibilityBuffer::VisibilityBuffer(int w, int h)
    : width(w),
      height(h),
      instance(size_t(w) * size_t(h), kInvalidId),
      triangle(size_t(w) * size_t(h), kInvalidId),
      bary(size_t(w) * size_t(h), glm::vec2(0.0f)),
      depth(size_t(w) * size_t(h), 0.0f) {}

void rasterize_clip_triangles_into(const std::vector<ClipTriangle>& triangles, int width, int height, float znear,
                                   VisibilityBuffer& vis) {
  if (width <= 0 || height <= 0 || width > kMaxImageSize || height > kMaxImageSize)
    throw Error("rasterize: image size " + std::to_string(width) + "x" + std::to_string(height) +
                " is outside 1.." + std::to_string(kMaxImageSize));
  // Set up every triangle once, in input order.
  const std::array<ClipPlane, 5> planes = clip_planes(width, height, double(znear));
  std::vector<RasterTriangle> setup;
  setup.reserve(triangles.size());
  for (const ClipTriangle& tri : triangles) setup_triangle(tri, planes, width, height, setup);
  // Walk bands of rows in parallel; every band rewrites all of its pixels, so `vis` may hold an old frame.
  if (vis.width != width || vis.height != height) vis = VisibilityBuffer(width, height);
  const int bands = (height + kBandRows - 1) / kBandRows;
  parallel_rows(bands, [&](int band) {
    rasterize_band(setup, band * kBandRows, std::min(height, (band + 1) * kBandRows), vis);
  });
}

VisibilityBuffer rasterize_clip_triangles(const std::vector<ClipTriangle>& triangles, int width, int height,
                                          float znear) {
  VisibilityBuffer vis;
  rasterize_clip_triangles_into(triangles, width, height, znear, vis);
  return vis;
}

VisibilityBuffer rasterize(const Scene& scene, const ScenePose& pose, const View& view) {
  VisibilityBuffer vis;
  rasterize_into(scene, pose, view, vis);
  return vis;
}

void rasterize_into(const Scene& scene, const ScenePose& pose, const View& view, VisibilityBuffer& vis) {
  std::vector<ClipTriangle> triangles;
  std::vector<glm::vec4> clip;  // one instance's vertices in clip space, each transformed once
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Mesh& mesh = scene.meshes[size_t(scene.instances[i].mesh)];
    const glm::mat4 object_to_clip = view.world_to_clip * pose.instance_to_world[i];
    clip.resize(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) clip[v] = object_to_clip * glm::vec4(mesh.positions[v], 1.0f);
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      const glm::uvec3& tri = mesh.triangles[t];
      triangles.push_back({{clip[tri[0]], clip[tri[1]], clip[tri[2]]}, uint32_t(i), uint32_t(t)});
    }
  }
  rasterize_clip_triangles_into(triangles, view.width, view.height, view.znear, vis);
}

}  // namespace rtdr
