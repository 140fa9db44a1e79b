// Deep and non-regular input to the scene loaders: a glTF node chain far deeper than any call
// stack would take loads (the hierarchy is walked with a heap stack), JSON nested deeper than
// kMaxJsonDepth (a glTF's extras, a GLB's JSON chunk, a scene file) is refused before a
// recursive parser sees it, a buffer URI naming a folder and a model that is /dev/zero are one
// InputError naming the file, and duplicate keys in a scene file are refused. The files are
// generated here: each expected position is the sum of the chain's translations.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "gltf_writer.h"
#include "scenes/gltf_loader.h"
#include "scenes/obj_loader.h"
#include "scenes/scene_file.h"
#include "test_paths.h"
#include "test_scratch.h"

namespace shadowlab {
namespace deep_inputs_test {

using nlohmann::json;

std::string scratch(const std::string& name) { return test::scratch_path("deep_inputs", name); }

std::string write_text(const std::string& name, const std::string& text) {
  return test::write_scratch_text("deep_inputs", name, text);
}

using test::input_error;

test::GltfWriter one_triangle() {
  test::GltfWriter w;
  test::GltfPrimitive p;
  p.positions = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  p.indices = {0, 1, 2};
  w.mesh({p}, "tri");
  return w;
}

std::string deep_arrays(int depth) { return std::string(size_t(depth), '[') + std::string(size_t(depth), ']'); }

// 50,000 nodes, each the only child of the one before and translated by (1, 0, 0); the last
// holds the triangle, so its corners move by (50000, 0, 0). A recursive walk overflows the
// stack at about 20,000 levels.
TEST(DeepInputs, GltfNodeChainFarDeeperThanTheStackLoads) {
  constexpr int kDepth = 50000;
  test::GltfWriter w = one_triangle();
  json nodes = json::array();
  for (int i = 0; i < kDepth; ++i) {
    json n = {{"translation", {1, 0, 0}}};
    if (i + 1 < kDepth) n["children"] = {i + 1};
    else n["mesh"] = 0;
    nodes.push_back(n);
  }
  w.json["nodes"] = nodes;
  w.json["scenes"] = json::array({{{"nodes", {0}}}});
  w.json["scene"] = 0;
  const std::string path = scratch("chain.gltf");
  w.write(path, /*embed=*/true);
  std::vector<std::string> notes;
  GltfContents c;
  const Scene s = load_gltf_scene(path, {}, &c, &notes);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].positions[0], vec3(kDepth + 1, 0, 0));
  EXPECT_EQ(s.meshes[0].positions[1], vec3(kDepth, 1, 0));
  EXPECT_EQ(s.meshes[0].positions[2], vec3(kDepth, 0, 1));
}

// 20,000 arrays nested in "extras" (tinygltf converts them with one call per level): refused
// by the depth scan, naming the file and the limit.
TEST(DeepInputs, GltfExtrasNestedBeyondTheLimitAreRefused) {
  test::GltfWriter w = one_triangle();
  w.json["nodes"] = json::array({{{"mesh", 0}}});
  w.json["scenes"] = json::array({{{"nodes", {0}}}});
  w.json["scene"] = 0;
  const std::string path = scratch("deep_extras.gltf");
  w.write(path, /*embed=*/true);
  std::string text;
  {
    std::ifstream in(path);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  ASSERT_EQ(text.front(), '{');
  text.insert(1, "\"extras\": {\"deep\": " + deep_arrays(20000) + "},");
  std::ofstream(path, std::ios::binary) << text;
  const std::string e = input_error([&] { load_gltf_scene(path, {}, nullptr, nullptr); });
  EXPECT_EQ(e.rfind(path + ": JSON nesting deeper than 64 levels at extras.deep[0][0]", 0), 0u) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos);
}

// The same inside a GLB's JSON chunk.
TEST(DeepInputs, GlbJsonNestedBeyondTheLimitIsRefused) {
  std::string text = "{\"asset\": {\"version\": \"2.0\"}, \"extras\": " + deep_arrays(20000) + "}";
  while (text.size() % 4) text += ' ';
  std::string glb;
  auto u32 = [&](uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
  u32(0x46546C67u);  // "glTF"
  u32(2);
  u32(uint32_t(20 + text.size()));
  u32(uint32_t(text.size()));
  u32(0x4E4F534Au);  // "JSON"
  glb += text;
  const std::string path = write_text("deep.glb", glb);
  const std::string e = input_error([&] { load_gltf_scene(path, {}, nullptr, nullptr); });
  EXPECT_EQ(e.rfind(path + ": JSON nesting deeper than 64 levels at extras[0][0]", 0), 0u) << e;
}

// A buffer "uri": "." names the glTF's folder: one InputError naming it (tinygltf's own reader
// takes the folder's size as a length: std::bad_alloc, without a file name).
TEST(DeepInputs, GltfBufferUriNamingAFolderIsRefused) {
  test::GltfWriter w = one_triangle();
  w.json["nodes"] = json::array({{{"mesh", 0}}});
  w.json["scenes"] = json::array({{{"nodes", {0}}}});
  w.json["scene"] = 0;
  const std::string path = scratch("folder_buffer.gltf");
  w.write(path);
  json j;
  {
    std::ifstream in(path);
    j = json::parse(in);
  }
  j["buffers"][0]["uri"] = ".";
  std::ofstream(path) << j.dump();
  const std::string e = input_error([&] { load_gltf_scene(path, {}, nullptr, nullptr); });
  EXPECT_NE(e.find("/.: is a directory, not a regular file"), std::string::npos) << e;
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(DeepInputs, ModelThatIsACharacterDeviceIsRefused) {
  EXPECT_EQ(input_error([] { load_obj_scene("/dev/zero", nullptr); }),
            "/dev/zero: is a character device, not a regular file");
  EXPECT_EQ(input_error([] { load_scene_file("/dev/zero", nullptr); }),
            "/dev/zero: is a character device, not a regular file");
}

TEST(DeepInputs, SceneFileNestedBeyondTheLimitIsRefused) {
  const std::string path = write_text("deep.json", "{\"base\": \"plane\", \"camera\": " + deep_arrays(20000) + "}");
  const std::string e = input_error([&] { load_scene_file(path, nullptr); });
  EXPECT_EQ(e.rfind(path + ": JSON nesting deeper than 64 levels at camera[0][0]", 0), 0u) << e;
}

// A key given twice is refused (nlohmann would keep the last one, silently).
TEST(DeepInputs, SceneFileDuplicateKeysAreRefused) {
  const std::string top = write_text("dup_top.json", R"({"base": "plane", "base": "default"})");
  EXPECT_EQ(input_error([&] { load_scene_file(top, nullptr); }),
            top + ": base: duplicate key in a JSON object (each key may appear once)");
  const std::string nested =
      write_text("dup_nested.json", R"({"base": "plane", "camera": {"fov_deg": 40, "fov_deg": 60}})");
  EXPECT_EQ(input_error([&] { load_scene_file(nested, nullptr); }),
            nested + ": camera.fov_deg: duplicate key in a JSON object (each key may appear once)");
}

}  // namespace deep_inputs_test
}  // namespace shadowlab
