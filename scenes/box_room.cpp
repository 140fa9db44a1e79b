#include "scenes/box_room.h"

#include <cmath>

#include "scenes/mesh_builders.h"

namespace shadowlab {

BoxRoom make_box_room() {
  BoxRoom b;
  Scene& s = b.scene;
  s.name = "box";
  s.materials.push_back(Material{});
  Mesh m;
  add_box(m, glm::scale(mat4(1.0f), vec3(4.0f)));
  s.meshes.push_back(m);
  s.light.position = vec3(0.3f, 0.2f, 0.1f);
  s.light.near = 0.05f;
  s.light.far = 10.0f;
  const int n = 90000;
  b.g.resize(n, 1);
  const float golden = 3.14159265f * (3.0f - std::sqrt(5.0f));
  for (int i = 0; i < n; ++i) {
    const float y = 1.0f - 2.0f * (float(i) + 0.5f) / float(n), r = std::sqrt(1.0f - y * y);
    const vec3 d(r * std::cos(golden * float(i)), y, r * std::sin(golden * float(i)));
    float t = 1e30f;
    int axis = 0;
    for (int a = 0; a < 3; ++a) {
      if (d[a] == 0.0f) continue;
      const float ta = ((d[a] > 0.0f ? 2.0f : -2.0f) - s.light.position[a]) / d[a];
      if (ta < t) t = ta, axis = a;
    }
    const vec3 q = s.light.position + t * d;
    int near_edges = 0;
    for (int a = 0; a < 3; ++a) near_edges += std::fabs(q[a]) > 1.6f;
    if (near_edges >= 2) continue;
    vec3 normal(0.0f);
    normal[axis] = d[axis] > 0.0f ? -1.0f : 1.0f;
    b.g.position[size_t(i)] = q;
    b.g.normal[size_t(i)] = b.g.geo_normal[size_t(i)] = normal;
    b.g.covered[size_t(i)] = 1;
  }
  return b;
}

}  // namespace shadowlab
