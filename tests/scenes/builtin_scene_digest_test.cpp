// Every built-in scene against its reviewed layout (tests/data/builtin_scene_digests.json):
// camera, light, projector and, per mesh, triangle and vertex counts, bounds, the mean of the
// vertices (a part moved inside the bounds), the surface area (a degenerate triangle), uv bounds,
// albedo, alpha cutoff and which way the normals face (their mean, and their mean component
// away from the mesh's centre). The file was written from the scenes and
// reviewed entry by entry against their sources and descriptions (docs/scenes.md: the box,
// sphere and legs of the default room where the source places them, normals facing into the
// closed rooms, the foliage plants at their listed positions, and so on); a change to a
// built-in scene shows here as the fields that moved, and the file is rewritten (run the test
// with SHADOWLAB_WRITE_SCENE_DIGESTS=1) only after that diff has been reviewed in turn.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "scenes/scene_registry.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

using nlohmann::json;

// Six significant digits: the file reads as the sources write the numbers.
double r6(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return std::strtod(text, nullptr);
}
json v3(const vec3& v) { return json::array({r6(v.x), r6(v.y), r6(v.z)}); }

// Mean over the vertices of n · (p − c) / |p − c| (c: the mesh's bounds centre): near −1 for a
// room's walls seen from inside, positive for a closed object's outward normals.
double facing(const Mesh& m, const vec3& c) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < m.positions.size() && i < m.normals.size(); ++i) {
    const vec3 d = m.positions[i] - c;
    const float len = glm::length(d);
    if (len == 0.0f) continue;
    sum += double(glm::dot(m.normals[i], d / len));
    ++n;
  }
  return n ? sum / double(n) : 0.0;
}

// Sum of the triangles' areas, m².
double area(const Mesh& m) {
  double sum = 0.0;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const dvec3 a(m.positions[m.indices[3 * t]]), b(m.positions[m.indices[3 * t + 1]]),
        c(m.positions[m.indices[3 * t + 2]]);
    sum += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  return sum;
}

// Mean of the vertex normals: a flat mesh's normal (its facing is 0: every n · (p − c) is).
vec3 mean_normal(const Mesh& m) {
  dvec3 sum(0.0);
  for (const vec3& n : m.normals) sum += dvec3(n);
  return m.normals.empty() ? vec3(0.0f) : vec3(sum / double(m.normals.size()));
}

json digest(const Scene& s) {
  json j;
  j["camera"] = {{"eye", v3(s.camera.eye)}, {"target", v3(s.camera.target)}, {"up", v3(s.camera.up)},
                 {"fov_y_deg", r6(s.camera.fov_y_deg)}, {"near", r6(s.camera.near)}, {"far", r6(s.camera.far)},
                 {"width", s.camera.width}, {"height", s.camera.height}};
  j["light"] = {{"position", v3(s.light.position)}, {"radius", r6(s.light.radius)},
                {"near", r6(s.light.near)}, {"far", r6(s.light.far)}};
  // A posed projector's pose is the scene's even when --slide is what enables it.
  j["projector"] = {{"enabled", s.projector.enabled}, {"posed", s.projector.posed}};
  if (s.projector.enabled || s.projector.posed)
    j["projector"].update({{"position", v3(s.projector.position)}, {"direction", v3(s.projector.direction)},
                           {"up", v3(s.projector.up)}, {"fov_y_deg", r6(s.projector.fov_y_deg)},
                           {"aspect", r6(s.projector.aspect)}});
  j["meshes"] = json::array();
  for (const Mesh& m : s.meshes) {
    vec3 lo(1e30f), hi(-1e30f);
    for (const vec3& p : m.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    dvec3 sum(0.0);
    for (const vec3& p : m.positions) sum += dvec3(p);
    const vec3 centroid = m.positions.empty() ? vec3(0.0f) : vec3(sum / double(m.positions.size()));
    json jm = {{"name", m.name}, {"triangles", m.triangle_count()}, {"vertices", m.positions.size()},
               {"lo", v3(lo)}, {"hi", v3(hi)}, {"centroid", v3(centroid)}, {"area", r6(area(m))},
               {"facing", r6(facing(m, 0.5f * (lo + hi)))},
               {"normal", v3(mean_normal(m))}};
    const Material& mat = s.materials[size_t(m.material)];
    jm["albedo"] = v3(mat.albedo);
    jm["alpha"] = mat.alpha_texture >= 0 ? json(r6(mat.alpha_cutoff)) : json(nullptr);
    if (!m.uvs.empty()) {
      vec2 ulo(1e30f), uhi(-1e30f);
      for (const vec2& u : m.uvs) {
        ulo = glm::min(ulo, u);
        uhi = glm::max(uhi, u);
      }
      jm["uv_lo"] = json::array({r6(ulo.x), r6(ulo.y)});
      jm["uv_hi"] = json::array({r6(uhi.x), r6(uhi.y)});
    }
    j["meshes"].push_back(jm);
  }
  return j;
}

// Numbers agree to 1e-5 of their size, at least 1e-5 absolute (libm's sin and cos, which place
// the spheres' vertices, may differ in the last bit between systems, and the file keeps six
// digits); everything else exactly.
void expect_same(const json& want, const json& got, const std::string& where) {
  if (want.is_number() && got.is_number()) {
    const double a = want.get<double>(), b = got.get<double>();
    EXPECT_LE(std::fabs(a - b), 1e-5 * std::max(1.0, std::fabs(a))) << where << ": " << a << " vs " << b;
    return;
  }
  ASSERT_EQ(want.type(), got.type()) << where;
  if (want.is_object()) {
    ASSERT_EQ(want.size(), got.size()) << where << ": " << got.dump();
    for (auto it = want.begin(); it != want.end(); ++it) {
      ASSERT_TRUE(got.contains(it.key())) << where << "." << it.key();
      expect_same(it.value(), got[it.key()], where + "." + it.key());
    }
  } else if (want.is_array()) {
    ASSERT_EQ(want.size(), got.size()) << where;
    for (size_t i = 0; i < want.size(); ++i) {
      const std::string at =
          want[i].is_object() && want[i].contains("name") ? want[i]["name"].get<std::string>() : std::to_string(i);
      expect_same(want[i], got[i], where + "[" + at + "]");
    }
  } else {
    EXPECT_EQ(want, got) << where;
  }
}

TEST(BuiltinScenes, MatchTheirReviewedLayouts) {
  const std::string path = test::source_path("tests/data/builtin_scene_digests.json");
  json got;
  for (const BuiltinScene& row : builtin_scenes()) got[row.name] = digest(make_builtin_scene(row.name));
  if (std::getenv("SHADOWLAB_WRITE_SCENE_DIGESTS")) {
    std::ofstream(path) << got.dump(1) << "\n";
    GTEST_SKIP() << "wrote " << path;
  }
  std::ifstream f(path);
  ASSERT_TRUE(f) << path;
  const json want = json::parse(f);
  ASSERT_EQ(want.size(), got.size());
  for (auto it = want.begin(); it != want.end(); ++it) {
    ASSERT_TRUE(got.contains(it.key())) << it.key();
    expect_same(it.value(), got[it.key()], it.key());
  }
}

}  // namespace
}  // namespace shadowlab
