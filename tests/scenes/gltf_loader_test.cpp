// The glTF 2.0 loader (scenes/gltf_loader.h): node transforms against hand-computed positions,
// winding under mirroring, lights and cameras, alpha masks, malformed files (one InputError
// naming the file), and a glTF scene rendered by every technique with the camera pass agreeing
// with Embree's primary rays.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <tuple>

#include <stb_image_write.h>

#include "core/error.h"
#include "core/texture.h"
#include "gltf_writer.h"
#include "raster/gbuffer_pass.h"
#include "raytrace/embree_scene.h"
#include "raytrace/visibility.h"
#include "scenes/gltf_loader.h"
#include "techniques/shading/scene_shading.h"
#include "techniques/registry/technique.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

using nlohmann::json;
using test::GltfPrimitive;
using test::GltfWriter;

std::string scratch(const std::string& name) {
  const std::string dir = test::binary_path("tests/scratch/gltf");
  std::filesystem::create_directories(dir);
  return dir + "/" + name;
}

GltfPrimitive triangle() {
  GltfPrimitive p;
  p.positions = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const float n = 1.0f / std::sqrt(3.0f);
  p.normals = {n, n, n, n, n, n, n, n, n};
  p.indices = {0, 1, 2};
  return p;
}

void expect_near(const vec3& a, const vec3& b, float tol, const std::string& what) {
  EXPECT_LE(glm::length(a - b), tol) << what << ": (" << a.x << "," << a.y << "," << a.z << ") vs ("
                                     << b.x << "," << b.y << "," << b.z << ")";
}

// T·R·S of nested nodes and a column-major matrix with a mirror, by hand: S = 2 maps the
// triangle's corners to 2·e_i, R (90° about +y) maps (x, y, z) to (z, y, −x), T adds (1, 2, 3).
TEST(Gltf, NodeTransformsGiveTheHandComputedPositions) {
  GltfWriter w;
  const int mesh = w.mesh({triangle()}, "tri");
  const double s45 = std::sqrt(0.5);
  w.json["nodes"] = json::array({
      {{"translation", {1, 2, 3}}, {"children", {1}}},
      {{"rotation", {0, s45, 0, s45}}, {"scale", {2, 2, 2}}, {"mesh", mesh}},
      // Column-major: x mirrored, then translated by (0, 5, 0).
      {{"matrix", {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 5, 0, 1}}, {"mesh", mesh}}});
  w.json["scenes"] = json::array({{{"nodes", {0, 2}}}});
  w.json["scene"] = 0;
  for (const char* file : {"hierarchy.gltf", "hierarchy.glb"}) {
    const std::string path = scratch(file);
    w.write(path);
    std::vector<std::string> notes;
    GltfContents c;
    const Scene s = load_gltf_scene(path, {}, &c, &notes);
    ASSERT_EQ(s.meshes.size(), 2u) << file;
    const Mesh& a = s.meshes[0];
    expect_near(a.positions[0], vec3(1, 2, 1), 1e-6f, "R·S·e_x + T");
    expect_near(a.positions[1], vec3(1, 4, 3), 1e-6f, "R·S·e_y + T");
    expect_near(a.positions[2], vec3(3, 2, 3), 1e-6f, "R·S·e_z + T");
    // Normals: R (the scale does not turn them) of (1, 1, 1)/√3 = (1, 1, −1)/√3.
    expect_near(a.normals[0], vec3(1, 1, -1) / std::sqrt(3.0f), 1e-6f, "normal");
    const Mesh& b = s.meshes[1];
    expect_near(b.positions[0], vec3(-1, 5, 0), 1e-6f, "mirrored e_x");
    // The mirror reverses the winding: the triangle's front (counter-clockwise) normal stays the
    // mirrored normal (−1, 1, 1)/√3, which the file's normals become.
    const vec3 p0 = b.positions[b.indices[0]], p1 = b.positions[b.indices[1]],
               p2 = b.positions[b.indices[2]];
    const vec3 front = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    expect_near(front, vec3(-1, 1, 1) / std::sqrt(3.0f), 1e-6f, "front after the mirror");
    expect_near(b.normals[0], vec3(-1, 1, 1) / std::sqrt(3.0f), 1e-6f, "mirrored normal");
    EXPECT_EQ(c.lights, 0);
    EXPECT_EQ(c.cameras, 0);
  }
}

// A scale of (2, 3, 4) stretches each axis by its own factor: the corners e_i become s_i·e_i.
TEST(Gltf, NonUniformScaleStretchesEachAxis) {
  GltfWriter w;
  const int mesh = w.mesh({triangle()}, "tri");
  w.json["nodes"] = json::array({{{"scale", {2, 3, 4}}, {"mesh", mesh}}});
  w.json["scenes"] = json::array({{{"nodes", {0}}}});
  const std::string path = scratch("stretch.gltf");
  w.write(path);
  const Scene s = load_gltf_scene(path, {}, nullptr, nullptr);
  ASSERT_EQ(s.meshes.size(), 1u);
  expect_near(s.meshes[0].positions[0], vec3(2, 0, 0), 1e-6f, "S·e_x");
  expect_near(s.meshes[0].positions[1], vec3(0, 3, 0), 1e-6f, "S·e_y");
  expect_near(s.meshes[0].positions[2], vec3(0, 0, 4), 1e-6f, "S·e_z");
}

// One triangle with one material and one point light, edited by `edit`; the loaded scene.
Scene one_material_scene(const std::string& file, const json& material, const json& light) {
  GltfWriter w;
  w.mesh({triangle()}, "tri");
  w.json["materials"] = json::array({material});
  w.json["meshes"][0]["primitives"][0]["material"] = 0;
  w.json["extensionsUsed"] = {"KHR_lights_punctual"};
  w.json["extensions"]["KHR_lights_punctual"]["lights"] = json::array({light});
  w.json["nodes"] = json::array(
      {{{"mesh", 0}}, {{"translation", {0.2, 0.3, 0.4}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}});
  w.json["scenes"] = json::array({{{"nodes", {0, 1}}}});
  const std::string path = scratch(file);
  w.write(path);
  return load_gltf_scene(path, {}, nullptr, nullptr);
}

// glTF 2.0: alphaCutoff defaults to 0.5 and applies to MASK only; BLEND (no translucency here)
// becomes MASK at 0.5 whatever cutoff the file gives. A point light's range is its far plane,
// small ranges included.
TEST(Gltf, CutoffDefaultsAndBlendAndRangeFollowTheSpecification) {
  const json point = {{"type", "point"}, {"range", 0.75}};
  const Scene mask = one_material_scene("mask_default.gltf", {{"alphaMode", "MASK"}}, point);
  EXPECT_FLOAT_EQ(mask.materials[size_t(mask.meshes[0].material)].alpha_cutoff, 0.5f);
  const Scene mask9 = one_material_scene("mask9.gltf", {{"alphaMode", "MASK"}, {"alphaCutoff", 0.9}}, point);
  EXPECT_FLOAT_EQ(mask9.materials[size_t(mask9.meshes[0].material)].alpha_cutoff, 0.9f);
  const Scene blend = one_material_scene("blend.gltf", {{"alphaMode", "BLEND"}, {"alphaCutoff", 0.9}}, point);
  const Material& b = blend.materials[size_t(blend.meshes[0].material)];
  EXPECT_FLOAT_EQ(b.alpha_cutoff, 0.5f);
  EXPECT_GE(b.alpha_texture, 0);
  EXPECT_FLOAT_EQ(mask.light.far, 0.75f);
  EXPECT_LE(mask.light.near, 0.75e-3f);
}

// KHR_lights_punctual allows outer cone angles up to π/2; the projector takes fields of view
// below 2 × 1.48 rad (170°) and refuses wider spots in one line.
TEST(Gltf, SpotConesWiderThanTheProjectorTakesAreRefused) {
  const json opaque = {{"name", "plain"}};
  for (const double outer : {0.2, 1.47}) {
    const Scene s = one_material_scene("spot_ok.gltf", opaque, {{"type", "spot"}, {"spot", {{"outerConeAngle", outer}}}});
    EXPECT_NEAR(s.projector.fov_y_deg, 2 * outer * 180.0 / M_PI, 1e-3) << outer;
  }
  for (const double outer : {1.49, 1.57}) {
    try {
      one_material_scene("spot_wide.gltf", opaque, {{"type", "spot"}, {"spot", {{"outerConeAngle", outer}}}});
      ADD_FAILURE() << outer;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("outerConeAngle must be in (0, 1.48) rad"), std::string::npos) << e.what();
    }
  }
}

// A lit scene: floor, box, an alpha-masked card with a checkerboard alpha, a point light (range,
// extras.radius), a spot light and a perspective camera. Returns the path.
// `leaf_alpha`: the leaf's baseColorFactor alpha; `bulb_radius`: the point light's extras.radius.
std::string lit_scene(const std::string& file, bool with_light = true, bool with_camera = true,
                      double leaf_alpha = 1.0, double bulb_radius = 0.05) {
  GltfWriter w;
  // An 8×8 RGBA texture: alpha 0 on black squares of a 2×2-texel checkerboard, 255 elsewhere.
  std::vector<uint8_t> rgba(8 * 8 * 4);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      uint8_t* p = &rgba[size_t(4 * (8 * y + x))];
      // Opaque texels green (40, 160, 60), cut-out ones red: the mean colour is neither.
      const bool hole = (x / 2 + y / 2) % 2;
      p[0] = hole ? 255 : 40;
      p[1] = hole ? 0 : 160;
      p[2] = hole ? 0 : 60;
      p[3] = hole ? 0 : 255;
    }
  std::vector<uint8_t> png;
  stbi_write_png_to_func(
      [](void* ctx, void* data, int size) {
        auto* v = static_cast<std::vector<uint8_t>*>(ctx);
        v->insert(v->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
      },
      &png, 8, 8, 4, rgba.data(), 32);
  while (w.bin.size() % 4) w.bin.push_back(0);
  const size_t off = w.bin.size();
  w.bin.insert(w.bin.end(), png.begin(), png.end());
  w.json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", off}, {"byteLength", png.size()}});
  w.json["images"] = json::array({{{"bufferView", w.json["bufferViews"].size() - 1}, {"mimeType", "image/png"}}});
  w.json["textures"] = json::array({{{"source", 0}}});
  w.json["materials"] = json::array({
      {{"name", "floor"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.7, 0.7, 0.7, 1.0}}}}},
      {{"name", "leaf"},
       {"alphaMode", "MASK"},
       {"alphaCutoff", 0.5},
       {"doubleSided", true},
       {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}},
                                 {"baseColorFactor", {1.0, 1.0, 1.0, leaf_alpha}}}}}});
  const float lo[3] = {-0.5f, 0.0f, -0.5f}, hi[3] = {0.5f, 1.0f, 0.5f};
  const int floor_mesh = w.mesh({test::floor_quad(5.0f, 0.0f, 0)}, "floor");
  const int box_mesh = w.mesh({test::box(lo, hi, 0)}, "box");
  GltfPrimitive card = test::floor_quad(1.0f, 0.0f, 1);
  const int card_mesh = w.mesh({card}, "leaf");
  json nodes = json::array({{{"mesh", floor_mesh}},
                            {{"mesh", box_mesh}, {"translation", {-1.0, 0.0, 0.5}},
                             {"rotation", {0, std::sin(0.25), 0, std::cos(0.25)}}},
                            {{"mesh", card_mesh}, {"translation", {1.2, 1.3, -0.2}}}});
  json roots = {0, 1, 2};
  if (with_light) {
    w.json["extensionsUsed"] = {"KHR_lights_punctual"};
    w.json["extensions"]["KHR_lights_punctual"]["lights"] = json::array(
        {{{"type", "point"}, {"range", 20.0}, {"extras", {{"radius", bulb_radius}}}, {"name", "bulb"}},
         {{"type", "spot"}, {"spot", {{"outerConeAngle", 0.5}}}},
         {{"type", "directional"}}});
    nodes.push_back({{"translation", {0.4, 3.0, 0.3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    // The spot at (0, 4, 0) aimed straight down: −z turned to −y (−90° about x).
    nodes.push_back({{"translation", {0.0, 4.0, 0.0}},
                     {"rotation", {-std::sqrt(0.5), 0, 0, std::sqrt(0.5)}},
                     {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    nodes.push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
    roots.push_back(3);
    roots.push_back(4);
    roots.push_back(5);
  }
  if (with_camera) {
    // Eye (0, 4, 8) looking at the origin: −z pitched down by atan(4/8) about x.
    const double a = -std::atan(0.5);
    w.json["cameras"] = json::array({{{"type", "perspective"},
                                      {"perspective", {{"yfov", 0.8}, {"znear", 0.1}, {"zfar", 50.0}, {"aspectRatio", 1.5}}}}});
    nodes.push_back({{"camera", 0}, {"translation", {0.0, 4.0, 8.0}}, {"rotation", {std::sin(a / 2), 0, 0, std::cos(a / 2)}}});
    roots.push_back(int(nodes.size()) - 1);
  }
  w.json["nodes"] = nodes;
  w.json["scenes"] = json::array({{{"nodes", roots}}});
  const std::string path = scratch(file);
  w.write(path, /*embed=*/true);
  return path;
}

TEST(Gltf, LightsAndCamerasComeFromTheFile) {
  const std::string path = lit_scene("lit.gltf");
  std::vector<std::string> notes;
  const Scene s = make_gltf_scene(path, {}, &notes);
  expect_near(s.light.position, vec3(0.4f, 3.0f, 0.3f), 1e-6f, "point light");
  EXPECT_FLOAT_EQ(s.light.radius, 0.05f);
  EXPECT_FLOAT_EQ(s.light.far, 20.0f);
  EXPECT_FALSE(s.projector.enabled);
  expect_near(s.camera.eye, vec3(0, 4, 8), 1e-6f, "eye");
  expect_near(glm::normalize(s.camera.target - s.camera.eye), glm::normalize(vec3(0, -4, -8)), 1e-6f,
              "view direction");
  EXPECT_NEAR(s.camera.fov_y_deg, 0.8 * 180.0 / M_PI, 1e-4);
  EXPECT_EQ(s.camera.width, 1152);  // 768 × 1.5
  EXPECT_EQ(s.camera.height, 768);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("light 0 'bulb'"), std::string::npos) << notes[0];
  EXPECT_NE(notes[1].find("camera 0 of 1"), std::string::npos) << notes[1];

  // The spot light becomes the slide projector, aimed down, fov 2 × 0.5 rad.
  GltfChoice spot;
  spot.light = 1;
  const Scene p = make_gltf_scene(path, spot, &notes);
  EXPECT_TRUE(p.projector.enabled);
  expect_near(glm::normalize(p.projector.direction), vec3(0, -1, 0), 1e-6f, "spot direction");
  EXPECT_NEAR(p.projector.fov_y_deg, 2 * 0.5 * 180.0 / M_PI, 1e-4);
  EXPECT_FLOAT_EQ(p.light.radius, 0.0f);

  // A directional light, a light and a camera that do not exist: one-line errors.
  for (const auto& [light, camera, expect] :
       std::vector<std::tuple<int, int, std::string>>{{2, 0, "directional light is not supported"},
                                                      {3, 0, "is not a light of"},
                                                      {0, 1, "is not a camera of"}}) {
    GltfChoice ch;
    ch.light = light;
    ch.camera = camera;
    try {
      make_gltf_scene(path, ch, &notes);
      ADD_FAILURE() << expect;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  }
}

TEST(Gltf, WithoutLightAndCameraTheyAreFramedAndSaidSo) {
  const std::string path = lit_scene("bare.gltf", false, false);
  std::vector<std::string> notes;
  const Scene s = make_gltf_scene(path, {}, &notes);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("no light in the file"), std::string::npos);
  EXPECT_NE(notes[1].find("no camera in the file"), std::string::npos);
  // The OBJ framing: light above the bounds centre, camera looking at it.
  EXPECT_GT(s.light.position.y, 1.0f);
  EXPECT_GT(s.light.radius, 0.0f);
}

TEST(Gltf, TheFactorsAlphaScalesTheTexturesAlphaOnly) {
  // baseColorFactor.a = 0.5 (glTF: the alpha is texture alpha × factor alpha): the alpha plane
  // holds 0.5 where the texture's alpha is 1, and the colour planes are the texture's.
  const Scene s = make_gltf_scene(lit_scene("half_alpha.gltf", true, true, 0.5), {}, nullptr);
  const Mesh* leaf = nullptr;
  for (const Mesh& m : s.meshes)
    if (m.name == "leaf/0") leaf = &m;
  ASSERT_NE(leaf, nullptr);
  const ImageF& t = s.textures[size_t(s.materials[size_t(leaf->material)].alpha_texture)];
  ASSERT_EQ(t.channels, 4);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool hole = (x / 2 + y / 2) % 2;
      EXPECT_EQ(t.data[size_t((3 * 8 + y) * 8 + x)], hole ? 0.0f : 0.5f) << x << "," << y;
      EXPECT_EQ(t.data[size_t((0 * 8 + y) * 8 + x)], hole ? 1.0f : t.data[0]) << x << "," << y;  // red 255 or 40
    }
  EXPECT_LT(t.data[0], 0.03f);  // texel (0, 0) is opaque green: red 40 decodes to 0.021
}

TEST(Gltf, ALightRadiusOfZeroIsAPointLight) {
  const Scene s = make_gltf_scene(lit_scene("point.gltf", true, true, 1.0, 0.0), {}, nullptr);
  EXPECT_EQ(s.light.radius, 0.0f);
}

// The alpha mask: material cutoff, the texture's alpha plane (v flipped: glTF's top image row is
// uv v = 0, shadowlab's v = 1), and the card's uv mapping.
TEST(Gltf, AlphaMaskBecomesTheAlphaTexture) {
  const std::string path = lit_scene("mask.gltf");
  std::vector<std::string> notes;
  const Scene s = make_gltf_scene(path, {}, &notes);
  const Mesh* leaf = nullptr;
  for (const Mesh& m : s.meshes)
    if (m.name == "leaf/0") leaf = &m;
  ASSERT_NE(leaf, nullptr);
  const Material& mat = s.materials[size_t(leaf->material)];
  ASSERT_GE(mat.alpha_texture, 0);
  EXPECT_FLOAT_EQ(mat.alpha_cutoff, 0.5f);
  // The albedo is the texture's mean linear colour (factor 1): half the texels (40, 160, 60),
  // half (255, 0, 0), decoded by the sRGB standard's curve.
  auto decode = [](double c) {
    c /= 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  };
  EXPECT_NEAR(mat.albedo.x, 0.5 * (decode(40) + decode(255)), 1e-6);
  EXPECT_NEAR(mat.albedo.y, 0.5 * (decode(160) + decode(0)), 1e-6);
  EXPECT_NEAR(mat.albedo.z, 0.5 * (decode(60) + decode(0)), 1e-6);
  const ImageF& t = s.textures[size_t(mat.alpha_texture)];
  ASSERT_EQ(t.width, 8);
  ASSERT_EQ(t.channels, 4);
  // Texel (x, y) of the image has alpha 0 where (x/2 + y/2) is odd.
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      EXPECT_EQ(t.data[size_t((3 * 8 + y) * 8 + x)], ((x / 2 + y / 2) % 2) ? 0.0f : 1.0f);
  // glTF uv (0, 0) (vertex 0) is the image's top-left: shadowlab uv (0, 1).
  EXPECT_EQ(leaf->uvs[0], vec2(0.0f, 1.0f));
  EXPECT_EQ(sample_alpha(t, vec2(0.01f, 0.99f)), 1.0f);   // texel (0, 0)
  EXPECT_EQ(sample_alpha(t, vec2(0.26f, 0.99f)), 0.0f);   // texel (2, 0)
  // The floor stays opaque.
  EXPECT_EQ(s.materials[size_t(s.meshes[0].material)].alpha_texture, -1);
  // The base colour texture is the colour texture: shaded card pixels have their opaque texels'
  // colour, sRGB (40, 160, 60) decoded, whatever their lighting (a ratio of channels), not the
  // texture's mean (which the cut-out red texels pull towards red).
  ASSERT_GE(mat.color_texture, 0);
  Scene small = s;
  small.camera.width = 160;
  small.camera.height = 120;
  const GBuffer g = render_gbuffer(small);
  ImageF vis(g.width, g.height, 1, 1.0f);
  const ImageF shaded = shade_scene(small, g, vis, 0.1f);
  const float ratio = srgb8_to_linear(160) / srgb8_to_linear(40);
  size_t card = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i) {
    if (!g.covered[i] || small.meshes[g.mesh_id[i]].name != "leaf/0") continue;
    ++card;
    EXPECT_NEAR(shaded.data[g.pixel_count() + i] / shaded.data[i], ratio, 1e-4f * ratio);
  }
  EXPECT_GT(card, 20u);
}

// The scene renders with every technique (finite masks in [0, 1]); the camera pass agrees with
// Embree's primary rays (with the alpha filter) as for OBJ scenes, with the masked card a fair
// part of the view.
TEST(Gltf, EveryTechniqueRendersAndTheCameraPassAgreesWithEmbree) {
  Scene s = make_gltf_scene(lit_scene("render.glb"), {}, nullptr);
  s.camera.width = 192;
  s.camera.height = 128;
  const GBuffer g = render_gbuffer(s);
  const EmbreeScene rt(s);
  const PrimaryHits hits = primary_visibility(rt, s.camera);
  size_t covered = 0, same = 0, leaf = 0, coverage_diff = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i) {
    coverage_diff += bool(g.covered[i]) != (hits.mesh_id[i] != kNoPrimitive);
    if (!g.covered[i]) continue;
    ++covered;
    same += g.mesh_id[i] == hits.mesh_id[i] && g.prim_id[i] == hits.prim_id[i];
    leaf += s.meshes[g.mesh_id[i]].name == "leaf/0";
  }
  EXPECT_GE(double(same), 0.995 * double(covered)) << same << " of " << covered;
  EXPECT_LE(double(coverage_diff), 0.005 * double(g.pixel_count()));
  EXPECT_GT(leaf, 100u) << "the masked card must be in view";
  EXPECT_GT(covered, g.pixel_count() / 2);
  size_t runs = 0;
  for (const auto& [name, what] : technique_list()) {
    if (name[0] == 'p') continue;  // the projector layout needs a spot light (light 1)
    const std::string spec = name == "rt"    ? "rt:spp=4"
                             : name == "rts" ? "rts:spp=2,denoise=atrous"
                                             : name + ":res=64";
    RunOptions opt;
    const ShadowResult r = run_technique(parse_technique_spec(spec, "test"), s, g, opt);
    ASSERT_EQ(r.mask.data.size(), g.pixel_count()) << spec;
    size_t dark = 0;
    for (const float v : r.mask.data) {
      ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f) << spec;
      dark += v < 0.5f;
    }
    EXPECT_GT(dark, g.pixel_count() / 100) << spec << ": the box and card cast shadows";
    ++runs;
  }
  EXPECT_GE(runs, 10u);
}

// Malformed files: each one InputError naming the file, with the reason on one line.
TEST(Gltf, MalformedFilesAreOneLineErrorsNamingTheFile) {
  struct Bad {
    std::string name, expect;
    std::function<void(GltfWriter&)> edit;
    bool remove_bin = false;
  };
  auto base = [](GltfWriter& w) {
    w.mesh({triangle()}, "tri");
    w.json["nodes"] = json::array({{{"mesh", 0}}});
    w.json["scenes"] = json::array({{{"nodes", {0}}}});
  };
  const std::vector<Bad> cases = {
      {"index.gltf", "index 2 is 3, past the 3 vertices",
       [&](GltfWriter& w) {
         GltfPrimitive p = triangle();
         p.indices = {0, 1, 3};  // one past the last vertex
         w.mesh({p}, "tri");
         w.json["nodes"] = json::array({{{"mesh", 0}}});
         w.json["scenes"] = json::array({{{"nodes", {0}}}});
       }},
      {"inf.gltf", "vertex 1 is not finite",
       [&](GltfWriter& w) {
         GltfPrimitive p = triangle();
         p.positions[4] = std::numeric_limits<float>::infinity();
         w.mesh({p}, "tri");
         w.json["nodes"] = json::array({{{"mesh", 0}}});
         w.json["scenes"] = json::array({{{"nodes", {0}}}});
       }},
      {"lines.gltf", "primitive mode 1",
       [&](GltfWriter& w) {
         base(w);
         w.json["meshes"][0]["primitives"][0]["mode"] = 1;
       }},
      {"missing_bin.gltf", "not found", base, true},
      {"no_scene.gltf", "no scene",
       [&](GltfWriter& w) {
         w.mesh({triangle()}, "tri");
       }},
      {"count.gltf", "past its bufferView",
       [&](GltfWriter& w) {
         base(w);
         w.json["accessors"][0]["count"] = 1000;
       }},
      {"cycle.gltf", "reached twice",
       [&](GltfWriter& w) {
         base(w);
         w.json["nodes"] = json::array({{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}});
       }},
      {"cutoff.gltf", "alphaCutoff",
       [&](GltfWriter& w) {
         base(w);
         w.json["materials"] = json::array({{{"alphaMode", "MASK"}, {"alphaCutoff", 2.0}}});
         w.json["meshes"][0]["primitives"][0]["material"] = 0;
       }},
      {"huge_scale.gltf", "not finite",
       [&](GltfWriter& w) {
         base(w);
         w.json["nodes"][0]["scale"] = {1e300, 1, 1};
       }},
      {"version.gltf", "not glTF 2",
       [&](GltfWriter& w) {
         base(w);
         w.json["asset"]["version"] = "1.0";
       }},
  };
  for (const Bad& b : cases) {
    GltfWriter w;
    b.edit(w);
    const std::string path = scratch(b.name);
    w.write(path);
    if (b.remove_bin) std::filesystem::remove(path + ".bin");
    try {
      load_gltf_scene(path, {}, nullptr, nullptr);
      ADD_FAILURE() << b.name << ": no error";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(e.where, path) << msg;
      EXPECT_NE(msg.find(b.expect), std::string::npos) << b.name << ": " << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << b.name << ": " << msg;
    }
  }
  // Not JSON at all.
  const std::string junk = scratch("junk.gltf");
  { std::ofstream(junk) << "{ not json"; }
  EXPECT_THROW(load_gltf_scene(junk, {}, nullptr, nullptr), InputError);
  EXPECT_THROW(load_gltf_scene(scratch("absent.glb"), {}, nullptr, nullptr), InputError);
}

}  // namespace
}  // namespace shadowlab
