#include "lab/view_check.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

#include <fmt/format.h>

#include "core/error.h"

namespace shadowlab {
namespace {

struct D3 {
  double x, y, z;
};
D3 d3(const vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
D3 sub(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(const D3& a, const D3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
D3 unit(const D3& a) {
  const double n = std::sqrt(dot(a, a));
  return {a.x / n, a.y / n, a.z / n};
}

std::mutex blame_mutex;
std::map<std::string, std::string>& blames() {
  static std::map<std::string, std::string> m;
  return m;
}

std::string blame_of(const Scene& scene) {
  std::lock_guard<std::mutex> lock(blame_mutex);
  const auto it = blames().find(scene.name);
  return it != blames().end() ? it->second : "--scene " + scene.name;
}

}  // namespace

bool bounds_outside_view(const Camera& c, const Bounds& b) {
  if (!b.valid()) return true;
  const D3 eye = d3(c.eye);
  const D3 f = unit(sub(d3(c.target), eye));
  const D3 r = unit(cross(f, d3(c.up)));
  const D3 u = cross(r, f);
  const double ty = std::tan(0.5 * double(c.fov_y_deg) * M_PI / 180.0);
  const double tx = ty * double(c.width) / double(c.height);
  // A corner's view coordinates (x right, y up, z forward); a plane rejects the box when every
  // corner lies outside it by more than the slack (relative to the corner's distance).
  constexpr double kSlack = 1e-6;
  int outside[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 8; ++i) {
    const D3 p = d3(vec3((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z));
    const D3 v = sub(p, eye);
    const double x = dot(v, r), y = dot(v, u), z = dot(v, f);
    const double slack = kSlack * (std::fabs(x) + std::fabs(y) + std::fabs(z) + 1.0);
    outside[0] += z < double(c.near) - slack;
    outside[1] += z > double(c.far) + slack;
    outside[2] += x > z * tx + slack;
    outside[3] += -x > z * tx + slack;
    outside[4] += y > z * ty + slack;
    outside[5] += -y > z * ty + slack;
  }
  return std::any_of(std::begin(outside), std::end(outside), [](int n) { return n == 8; });
}

void set_view_blame(const std::string& scene_name, const std::string& blame) {
  std::lock_guard<std::mutex> lock(blame_mutex);
  blames()[scene_name] = blame;
}

void check_view_sees_bounds(const Scene& scene, const std::string& blame) {
  if (bounds_outside_view(scene.camera, scene_bounds(scene)))
    throw InputError(blame, "the camera sees none of the scene: its bounds lie outside the view "
                            "frustum (eye, target, fov and near/far " +
                                fmt::format("{:g}/{:g} m", double(scene.camera.near), double(scene.camera.far)) + ")");
}

void require_covered_view(const Scene& scene, const GBuffer& g) {
  if (std::any_of(g.covered.begin(), g.covered.end(), [](uint8_t c) { return c != 0; })) return;
  throw InputError(blame_of(scene), fmt::format("the camera sees no geometry: no pixel of the {}x{} "
                                                "image is covered (nothing to shade or score)",
                                                g.width, g.height));
}

}  // namespace shadowlab
