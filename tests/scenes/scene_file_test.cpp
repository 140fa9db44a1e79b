// The JSON scene file (scenes/scene_file.h): model transforms against hand-computed positions,
// camera, light, projector and ground keys, framing without a base, and one-line errors naming
// the key.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "scenes/scene_file.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

std::string folder() {
  const std::string dir = test::binary_path("tests/scratch/scene_file");
  std::filesystem::create_directories(dir);
  return dir;
}

std::string write(const std::string& name, const std::string& text) {
  const std::string path = folder() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// One triangle with corners e_x, e_y, e_z.
void write_triangle_obj() {
  write("tri.obj", "v 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n");
}

const Mesh* find(const Scene& s, const std::string& name) {
  for (const Mesh& m : s.meshes)
    if (m.name == name) return &m;
  return nullptr;
}

void expect_near(const vec3& a, const vec3& b, const std::string& what) {
  EXPECT_LE(glm::length(a - b), 1e-5f) << what << ": (" << a.x << "," << a.y << "," << a.z << ")";
}

// scale 2, then 90° about y ((x, y, z) → (z, y, −x)), then translate (1, 2, 3): e_x → (1, 2, 1),
// e_y → (1, 4, 3), e_z → (3, 2, 3).
// A scene file is named by its .json extension, in any case; other names are not.
TEST(SceneFile, PathsEndingInJsonAreSceneFiles) {
  EXPECT_TRUE(is_scene_file_path("scenes/room.json"));
  EXPECT_TRUE(is_scene_file_path("ROOM.JSON"));
  EXPECT_FALSE(is_scene_file_path("room.obj"));
  EXPECT_FALSE(is_scene_file_path("json"));
  EXPECT_FALSE(is_scene_file_path("room.xjson"));
}

TEST(SceneFile, ModelTransformsAndViewKeys) {
  write_triangle_obj();
  const std::string path = write("base.json", R"({
    "base": "plane",
    "models": [{"file": "tri.obj", "scale": 2, "rotate_deg": [0, 90, 0], "translate": [1, 2, 3]},
               {"file": "tri.obj", "translate": [80, 0, 0]}],
    "camera": {"eye": [0, 5, 9], "fov_deg": 45, "width": 320, "height": 200},
    "light": {"radius": 0.02}
  })");
  std::vector<std::string> notes;
  const Scene s = load_scene_file(path, &notes);
  const Mesh* tri = find(s, "tri");
  ASSERT_NE(tri, nullptr);
  expect_near(tri->positions[0], vec3(1, 2, 1), "e_x");
  expect_near(tri->positions[1], vec3(1, 4, 3), "e_y");
  expect_near(tri->positions[2], vec3(3, 2, 3), "e_z");
  EXPECT_EQ(s.camera.eye, vec3(0, 5, 9));
  EXPECT_FLOAT_EQ(s.camera.fov_y_deg, 45.0f);
  EXPECT_EQ(s.camera.width, 320);
  EXPECT_EQ(s.camera.height, 200);
  EXPECT_FLOAT_EQ(s.light.radius, 0.02f);
  // The plane scene's light (2 m above its centre) is kept; its far (40 m in the base) grows to
  // reach the second triangle's corner (81, 0, 0).
  EXPECT_EQ(s.light.position, vec3(0, 2, 0));
  EXPECT_GE(s.light.far, glm::length(vec3(81, -2, 0)));
  EXPECT_TRUE(notes.empty());
}

// Without a base: camera and light framed (with notes), the ground at the given height and size,
// and a mirroring scale keeps the triangle's front facing the mirrored normal.
TEST(SceneFile, FramedWithoutBaseAndGround) {
  write_triangle_obj();
  const std::string path = write("framed.json", R"({
    "models": [{"file": "tri.obj", "scale": [-1, 1, 1]}],
    "ground": {"y": -0.5, "size": 6}
  })");
  std::vector<std::string> notes;
  const Scene s = load_scene_file(path, &notes);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("no camera"), std::string::npos);
  EXPECT_NE(notes[1].find("no light"), std::string::npos);
  const Mesh* ground = find(s, "ground");
  ASSERT_NE(ground, nullptr);
  float lo_x = 1e9f, hi_x = -1e9f;
  for (const vec3& p : ground->positions) {
    EXPECT_FLOAT_EQ(p.y, -0.5f);
    lo_x = std::min(lo_x, p.x);
    hi_x = std::max(hi_x, p.x);
  }
  EXPECT_NEAR(hi_x - lo_x, 6.0f, 1e-5f);
  const Mesh* tri = find(s, "tri");
  ASSERT_NE(tri, nullptr);
  const vec3 a = tri->positions[tri->indices[0]], b = tri->positions[tri->indices[1]],
             c = tri->positions[tri->indices[2]];
  expect_near(glm::normalize(glm::cross(b - a, c - a)), glm::normalize(vec3(-1, 1, 1)), "front after the mirror");
}

// A mirroring scale reverses every triangle's winding back, not only the first: a strip of four
// triangles facing +y (their normals given in the file) still faces +y mirrored in x or in z.
TEST(SceneFile, MirroredModelsKeepEveryTriangleFacingItsNormals) {
  write("strip.obj",
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 0 -1\nv 1 0 -1\nv 2 0 -1\nvn 0 1 0\n"
        "f 1//1 2//1 5//1\nf 1//1 5//1 4//1\nf 2//1 3//1 6//1\nf 2//1 6//1 5//1\n");
  for (const char* scale : {"[-1, 1, 1]", "[1, 1, -2]"}) {
    const Scene s = load_scene_file(write("mirror.json", std::string(R"({"models": [{"file": "strip.obj", "scale": )") +
                                                            scale + R"(}], "ground": {"size": 4}})"));
    const Mesh* strip = find(s, "strip");
    ASSERT_NE(strip, nullptr);
    ASSERT_EQ(strip->triangle_count(), 4u);
    for (size_t t = 0; t < 4; ++t) {
      const vec3 a = strip->positions[strip->indices[3 * t]], b = strip->positions[strip->indices[3 * t + 1]],
                 c = strip->positions[strip->indices[3 * t + 2]];
      const vec3 front = glm::cross(b - a, c - a);
      EXPECT_GT(front.y, 0.0f) << scale << " triangle " << t;
      EXPECT_EQ(strip->normals[strip->indices[3 * t]], vec3(0, 1, 0)) << scale;
    }
  }
}

TEST(SceneFile, ProjectorKey) {
  const std::string path = write("projector.json", R"({
    "base": "plane",
    "projector": {"position": [0, 3, 0], "target": [0, 0, 0], "up": [0, 0, -1], "fov_deg": 50, "slide": "spot"}
  })");
  const Scene s = load_scene_file(path, nullptr);
  EXPECT_TRUE(s.projector.enabled);
  EXPECT_EQ(s.light.position, vec3(0, 3, 0));
  EXPECT_FLOAT_EQ(s.projector.fov_y_deg, 50.0f);
}

// The ranges of docs/scenes.md's table: a value just outside either end is the one-line range
// error naming the key, and the ends load (where another rule allows: a camera far of 1e-6
// would need a near below 1e-6, and a light 1e6 or 1e7 m deep fails the depth-precision check, so
// those ends are tried with the nearest value the other rules accept).
TEST(SceneFile, NumbersLoadAtTheEndsOfTheirDocumentedRanges) {
  struct Range {
    std::string object, key;
    double lo, hi;          // the documented range
    double lo_ok, hi_ok;    // values that must load
    std::string extra = "";  // other keys the object needs
  };
  const std::string proj = R"("position": [0, 3, 0], "target": [0, 0, 0], "up": [0, 0, -1], )";
  const std::vector<Range> ranges = {
      {"camera", "fov_deg", 1, 170, 1, 170},
      {"camera", "near", 1e-6, 1e6, 1e-6, 1e6, R"("far": 1e7, )"},
      {"camera", "far", 1e-6, 1e7, 2e-6, 1e7, R"("near": 1e-6, )"},
      {"light", "radius", 0, 1e4, 0, 1e4, R"("position": [0, 30000, 0], )"},
      {"light", "near", 1e-6, 1e6, 1e-6, 20, R"("position": [0, 30, 0], )"},
      {"light", "far", 1e-6, 1e7, 2e-6, 1e4, R"("near": 1e-6, )"},
      {"ground", "y", -1e7, 1e7, -1e7, 1e7},
      {"ground", "size", 1e-3, 1e6, 1e-3, 1e6},
      {"projector", "fov_deg", 0.1, 169, 0.1, 169, proj},
      {"projector", "aspect", 0.05, 20, 0.05, 20, proj},
  };
  int i = 0;
  for (const Range& r : ranges) {
    auto file = [&](double v) {
      const std::string text = fmt::format(R"({{"base": "plane", "{}": {{{}"{}": {:.17g}}}}})",
                                           r.object, r.extra, r.key, v);
      return std::pair{write("range" + std::to_string(i++) + ".json", text), text};
    };
    for (const double v : {r.lo_ok, r.hi_ok}) {
      const auto [path, text] = file(v);
      EXPECT_NO_THROW(load_scene_file(path, nullptr)) << text;
    }
    for (const double v : {r.lo - std::max(1e-7, std::fabs(r.lo) * 0.01), r.hi + std::fabs(r.hi) * 0.01}) {
      const auto [path, text] = file(v);
      try {
        load_scene_file(path, nullptr);
        ADD_FAILURE() << "accepted: " << text;
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(r.object + "." + r.key + ": is "), std::string::npos)
            << text << " → " << e.what();
      }
    }
  }
}

// Each bad file: one InputError naming the file, the key and the reason, on one line.
TEST(SceneFile, BadFilesNameTheKey) {
  write_triangle_obj();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"base": "plane", "camera": {"fvo": 40}})", "camera.fvo: unknown key (known: eye, target"},
      {R"({"base": "plane", "light": {"radius": "big"}})", "light.radius: expected a number"},
      {R"({"base": "plane", "camera": {"fov_deg": 400}})", "camera.fov_deg: is 400, outside [1, 170]"},
      {R"({"base": "plane", "camera": {"width": 2.5}})", "camera.width: expected an integer"},
      {R"({"base": "plane", "camera": {"eye": [1, 2]}})", "camera.eye: expected [x, y, z]"},
      {R"({"base": "plane", "colour": 1})", "colour: unknown key"},
      {R"({"base": "moon"})", "base: unknown built-in scene 'moon'"},
      {R"({"models": [{"file": "tri.obj", "scale": 0}]})", "models[0].scale: has a zero component"},
      {R"({"models": [{"scale": 1}]})", "models[0].file: is required"},
      {R"({"models": []})", "models: expected a non-empty array"},
      {R"({"base": "plane", "light": {}, "projector": {}})", "projector: conflicts with light"},
      {R"({})", "names neither a base scene nor models"},
      {R"({"base": "plane",)", "JSON syntax error at byte"},
      {R"([1, 2])", "expected an object"},
      // A number beyond double's range threw nlohmann's out_of_range past the loader (exit 1
      // with the library's message; found by fuzz_scene_file).
      {R"({"base": "plane", "light": {"radius": 4e444}})", "a JSON number is out of range"},
  };
  int i = 0;
  for (const auto& [text, expect] : cases) {
    const std::string path = write("bad" + std::to_string(i++) + ".json", text);
    try {
      load_scene_file(path, nullptr);
      ADD_FAILURE() << text;
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(e.where, path) << msg;
      EXPECT_NE(msg.find(expect), std::string::npos) << text << " → " << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
  }
  // A missing model: the OBJ loader's error names the model's path.
  const std::string missing = write("missing.json", R"({"models": [{"file": "nope.obj"}]})");
  try {
    load_scene_file(missing, nullptr);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(e.where.find("nope.obj"), std::string::npos) << e.what();
  }
  // Over 1 MB.
  const std::string big = write("big.json", "{\"base\": \"plane\"" + std::string(1 << 20, ' ') + "}");
  EXPECT_THROW(load_scene_file(big, nullptr), InputError);
}

}  // namespace
}  // namespace shadowlab
