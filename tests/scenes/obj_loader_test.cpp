#include "scenes/obj_loader.h"

#include <gtest/gtest.h>

#include <tuple>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>
// stb is a private dependency of core (implementation in libstb): full include path.
#include <stb/stb_image_write.h>

#include "core/error.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

// Writes `content` to build/test_output/core/obj/<name> and returns the path.
std::string write_file(const std::string& name, const std::string& content) {
  const std::string path = test::binary_path("core/obj/" + name);
  std::ofstream out(path, std::ios::binary);
  out << content;
  return path;
}

// Writes a w × h PNG with `comp` channels from interleaved bytes.
std::string write_png(const std::string& name, int w, int h, int comp,
                      const std::vector<unsigned char>& px) {
  const std::string path = test::binary_path("core/obj/" + name);
  EXPECT_NE(0, stbi_write_png(path.c_str(), w, h, comp, px.data(), w * comp));
  return path;
}

// Loads `path` expecting an InputError whose message contains every needle.
void expect_load_error(const std::string& path, const std::vector<std::string>& needles) {
  try {
    std::vector<std::string> notes;
    const Scene s = load_obj_scene(path, &notes);
    ADD_FAILURE() << path << " loaded (" << s.triangle_count() << " triangles) instead of failing";
  } catch (const InputError& e) {
    for (const std::string& n : needles)
      EXPECT_NE(std::string(e.what()).find(n), std::string::npos)
          << "message '" << e.what() << "' lacks '" << n << "'";
  }
}

const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
// The start of a binary file (ELF header bytes, then a PNG signature).
const char kBinary[] = {'\x7f', 'E',    'L', 'F', '\x02', '\x01', '\x01', '\0',   '\0',
                        '\0',   '\x89', 'P', 'N', 'G',    '\r',   '\n',   '\x1a', '\n'};

// Texture coordinates on some corners only: the others get (0, 0), and a note says so; on
// every corner, or on none, there is no note.
TEST(ObjLoader, PartialTextureCoordinatesAreNoted) {
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nvt 0.5 0.5\n";
  for (const auto& [name, faces, noted] :
       {std::tuple<const char*, const char*, bool>{"vt_some.obj", "f 1/1 2/1 3/1\nf 1 3 4\n", true},
        {"vt_all.obj", "f 1/1 2/1 3/1\nf 1/1 3/1 4/1\n", false},
        {"vt_none.obj", "f 1 2 3\nf 1 3 4\n", false}}) {
    std::vector<std::string> notes;
    load_obj_scene(write_file(name, quad + faces), &notes);
    bool found = false;
    for (const std::string& n : notes) found = found || n.find("texture coordinates on only some corners") != std::string::npos;
    EXPECT_EQ(found, noted) << name;
  }
}

TEST(ObjLoader, MissingFileNamesIt) {
  const std::string path = test::binary_path("core/obj/missing.obj");
  std::remove(path.c_str());
  expect_load_error(path, {"missing.obj", "cannot open", "No such file"});
}

TEST(ObjLoader, MalformedFilesAreInputErrorsNamingTheFile) {
  struct Case {
    const char* name;
    std::string text;
    const char* detail;
  };
  const std::vector<Case> cases = {
      {"bad_number.obj", "v abc 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "line 1"},
      {"short_vertex.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "line 1"},
      {"bad_face_index.obj", std::string(kTriangle) + "f 1 x 3\n", "line 4"},
      {"face_out_of_range.obj", std::string(kTriangle) + "f 1 2 9\n", "vertex 9"},
      {"negative_out_of_range.obj", std::string(kTriangle) + "f -1 -2 -4\n", "line 4"},
      {"zero_index.obj", std::string(kTriangle) + "f 0 1 2\n", "index 0"},
      {"two_corner_face.obj", std::string(kTriangle) + "f 1 2\n", "line 4"},
      {"leading_slash.obj", std::string(kTriangle) + "f /1 2 3\n", "face corner '/1' has an empty index"},
      {"trailing_slash.obj", std::string(kTriangle) + "f 1 2 3/\n", "face corner '3/' has an empty index"},
      {"normal_out_of_range.obj", std::string(kTriangle) + "f 1//1 2//1 3//1\n", "normal 1"},
      {"unknown_statement.obj", std::string(kTriangle) + "vx 1 2 3\nf 1 2 3\n", "line 4"},
      {"binary.obj", std::string(kBinary, sizeof kBinary), "line 1"},
      {"empty.obj", "", "no triangles"},
      {"points_only.obj", std::string(kTriangle) + "p 1 2 3\n", "no triangles"},
      {"comment_only.obj", "# nothing here\n", "no triangles"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    expect_load_error(write_file(c.name, c.text), {c.name, c.detail});
  }
}

// Every index error names the line of the face that makes it, forward references checked at the
// end of the file included (the largest index's first use; the face on line 5 here).
TEST(ObjLoader, EveryIndexErrorNamesItsLine) {
  const std::string tri = std::string(kTriangle) + "f 1 2 3\n";  // lines 1-4
  expect_load_error(write_file("fwd_vertex.obj", tri + "f 1 2 9\nv 0 0 1\nf 1 2 4\n"),
                    {"fwd_vertex.obj", "line 5:", "vertex 9", "has 4"});
  expect_load_error(write_file("fwd_normal.obj", tri + "vn 0 0 1\nf 1//1 2//1 3//2\n"),
                    {"fwd_normal.obj", "line 6:", "normal 2", "has 1"});
  expect_load_error(write_file("fwd_texcoord.obj", tri + "vt 0 0\nf 1/3 2/1 3/1\n"),
                    {"fwd_texcoord.obj", "line 6:", "texcoord 3", "has 1"});
  expect_load_error(write_file("back_vertex.obj", tri + "f -1 -2 -9\n"),
                    {"back_vertex.obj", "line 5:", "vertex -9"});
}

TEST(ObjLoader, NanAndInfVerticesNameTheVertex) {
  expect_load_error(write_file("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n"),
                    {"nan.obj", "vertex 3", "NaN or infinite"});
  expect_load_error(write_file("nan_upper.obj", "v 0 0 0\nv NaN 0 0\nv 0 1 0\nf 1 2 3\n"),
                    {"nan_upper.obj", "vertex 2"});
  expect_load_error(write_file("inf.obj", "v inf 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
                    {"inf.obj", "vertex 1", "NaN or infinite"});
  expect_load_error(write_file("neg_inf.obj", "v 0 0 0\nv 1 -infinity 0\nv 0 1 0\nf 1 2 3\n"),
                    {"neg_inf.obj", "vertex 2"});
  // 1e39 is a finite double but overflows the float tinyobjloader stores.
  expect_load_error(write_file("overflow.obj", "v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n"),
                    {"overflow.obj", "vertex 3"});
}

TEST(ObjLoader, MissingMtlNamesTheMtl) {
  const std::string obj =
      write_file("uses_missing_mtl.obj",
                 "mtllib not_there.mtl\n" + std::string(kTriangle) + "usemtl a\nf 1 2 3\n");
  expect_load_error(obj, {"not_there.mtl", "cannot open"});
}

TEST(ObjLoader, MissingTextureNamesTheTexture) {
  write_file("missing_tex.mtl", "newmtl leaves\nKd 1 1 1\nmap_d missing_alpha.png\n");
  const std::string obj =
      write_file("uses_missing_tex.obj", "mtllib missing_tex.mtl\n" + std::string(kTriangle) +
                                             "vt 0 0\nusemtl leaves\nf 1/1 2/1 3/1\n");
  expect_load_error(obj, {"missing_alpha.png", "cannot open", "map_d of material 'leaves'"});
}

// The text check and tinyobjloader must read the same bytes the same way. Cases from a fuzz and
// a user's session: a vertical tab before "v" (tinyobjloader: not a space, so no vertex; the
// check took it for one and a relative index then resolved to -1: a heap overflow), a form
// feed, a NUL, and a lone carriage return, which ends a line for both.
TEST(ObjLoader, CheckAndParserAgreeOnWhitespaceAndLineEnds) {
  expect_load_error(write_file("vtab.obj", "\vv 0 0 0\nf -1 -1 -1\n"),
                    {"vtab.obj", "line 1", "control byte 0x0B"});
  expect_load_error(write_file("vtab2.obj", std::string(kTriangle) + "\vv 5 5 5\nf -1 -2 -3\n"),
                    {"vtab2.obj", "line 4", "0x0B"});
  expect_load_error(write_file("ff.obj", std::string(kTriangle) + "f 1 2\f3\n"), {"ff.obj", "0x0C"});
  expect_load_error(write_file("nul.obj", std::string(kTriangle) + std::string("f 1 2 3\0 9\n", 12)),
                    {"nul.obj", "line 4", "0x00"});
  // "# note\rv 9 9 9": the comment ends at the \r, so (9, 9, 9) is vertex 1 for both readers.
  const Scene s = load_obj_scene(
      write_file("cr.obj", "# note\rv 9 9 9\nv 0 0 0\r\nv 1 0 0\rv 0 1 0\nf 1 2 3\nf 2 3 4\n"));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.triangle_count(), 2u);
  EXPECT_EQ(s.meshes[0].positions[0], vec3(9, 9, 9));
}

// An index beyond tinyobjloader's int (the most negative 64-bit value made the check negate it,
// which is undefined behaviour) is a clear error.
TEST(ObjLoader, HugeFaceIndicesAreOutOfRange) {
  expect_load_error(write_file("min64.obj", std::string(kTriangle) + "f -9223372036854775808 1 2\n"),
                    {"min64.obj", "line 4", "out of range"});
  expect_load_error(write_file("big.obj", std::string(kTriangle) + "f 1 2 4294967299\n"),
                    {"big.obj", "line 4", "out of range"});
}

// UTF-16 text is named as such (it used to fail with "unknown statement '???#?'").
TEST(ObjLoader, Utf16IsNamed) {
  std::string u16 = "\xFF\xFE";
  for (char c : std::string("# x\nv 0 0 0\n")) u16 += std::string(1, c) + '\0';
  expect_load_error(write_file("u16.obj", u16), {"u16.obj", "UTF-16"});
  std::string u16_no_bom;
  for (char c : std::string(kTriangle)) u16_no_bom += std::string(1, c) + '\0';
  expect_load_error(write_file("u16b.obj", u16_no_bom), {"u16b.obj", "UTF-16"});
}

// A legal polygon of any corner count is triangulated (more than 63 corners used to be refused):
// a convex 100-gon gives 98 triangles covering the disc's area.
TEST(ObjLoader, LargePolygonsAreTriangulated) {
  std::string text, face = "f";
  const int n = 100;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * 3.14159265358979 * i / n;
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on " " + std::string.
    text += "v ";
    text += std::to_string(std::cos(a));
    text += ' ';
    text += std::to_string(std::sin(a));
    text += " 0\n";
    face += ' ';
    face += std::to_string(i + 1);
  }
  const Scene s = load_obj_scene(write_file("poly100.obj", text + face + "\n"));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.triangle_count(), size_t(n - 2));
  double area = 0.0;
  const Mesh& m = s.meshes[0];
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
               c = m.positions[m.indices[3 * t + 2]];
    area += 0.5 * double(glm::length(glm::cross(b - a, c - a)));
  }
  // The regular n-gon's area: n/2 · sin(2π/n) (float vertices: within 1e-5).
  EXPECT_NEAR(area, 0.5 * n * std::sin(2.0 * 3.14159265358979 / n), 1e-5);
}

TEST(ObjLoader, ByteOrderMarkIsSkipped) {
  // tinyobjloader alone would drop the first vertex and fail on "f 1 2 3".
  const Scene s =
      load_obj_scene(write_file("bom.obj", "\xEF\xBB\xBF" + std::string(kTriangle) + "f 1 2 3\n"));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].positions[0], vec3(0, 0, 0));
  EXPECT_EQ(s.meshes[0].positions.size(), 3u);
}

TEST(ObjLoader, BadMtlValueAndUnknownMaterialAreErrors) {
  write_file("bad_kd.mtl", "newmtl a\nKd 1 zero 1\n");
  expect_load_error(write_file("uses_bad_kd.obj", "mtllib bad_kd.mtl\n" + std::string(kTriangle) +
                                                      "usemtl a\nf 1 2 3\n"),
                    {"bad_kd.mtl", "line 2"});
  // "d -halo" takes its value after the option: alone it has none (not "-halo" as a number).
  write_file("halo.mtl", "newmtl a\nd -halo\n");
  expect_load_error(write_file("uses_halo.obj", "mtllib halo.mtl\n" + std::string(kTriangle) + "usemtl a\nf 1 2 3\n"),
                    {"halo.mtl", "line 2", "'d' without a value"});
  write_file("halo_ok.mtl", "newmtl a\nd -halo 0.5\nKd 1 1 1\n");
  EXPECT_NO_THROW(load_obj_scene(write_file("uses_halo_ok.obj", "mtllib halo_ok.mtl\n" + std::string(kTriangle) +
                                                                   "usemtl a\nf 1 2 3\n")));
  write_file("good.mtl", "newmtl a\nKd 0.5 0.25 1\n");
  expect_load_error(
      write_file("unknown_material.obj",
                 "mtllib good.mtl\n" + std::string(kTriangle) + "usemtl b\nf 1 2 3\n"),
      {"unknown_material.obj", "'b'"});
}

TEST(ObjLoader, QuadWithUvAndNormalLoadsExactly) {
  // A 1 × 1 m quad in y = 0, facing +y, uv = (x, -z): split into two triangles, 4 welded
  // vertices, the file's normal, no material → one "default" material.
  const std::string path = write_file("quad.obj",
                                      "o quad\n"
                                      "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\n"
                                      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                      "vn 0 2 0\n"
                                      "f 1/1/1 2/2/1 3/3/1 4/4/1\n");
  std::vector<std::string> notes;
  const Scene s = load_obj_scene(path, &notes);
  EXPECT_TRUE(notes.empty()) << notes.front();
  EXPECT_EQ(s.name, "quad");
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.name, "quad");
  EXPECT_EQ(m.triangle_count(), 2u);
  ASSERT_EQ(m.positions.size(), 4u);
  ASSERT_EQ(m.normals.size(), 4u);
  ASSERT_EQ(m.uvs.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(m.normals[i], vec3(0, 1, 0)) << "normalised file normal, vertex " << i;
    EXPECT_EQ(m.uvs[i], vec2(m.positions[i].x, -m.positions[i].z)) << "vertex " << i;
  }
  for (size_t t = 0; t < 2; ++t) {
    const vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
               c = m.positions[m.indices[3 * t + 2]];
    EXPECT_GT(glm::cross(b - a, c - a).y, 0.0f) << "winding kept, triangle " << t;
  }
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "default");
  EXPECT_EQ(s.materials[0].alpha_texture, -1);
}

TEST(ObjLoader, WeldsIdenticalTriplesOnlyAndComputesMissingNormals) {
  // Two triangles sharing an edge by position index: 4 vertices; the same positions with
  // different texcoords on the shared edge: 6 vertices. No vn: normals computed (+z).
  const std::string shared =
      write_file("shared.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
  const Scene a = load_obj_scene(shared);
  ASSERT_EQ(a.meshes.size(), 1u);
  EXPECT_EQ(a.meshes[0].positions.size(), 4u);
  EXPECT_TRUE(a.meshes[0].uvs.empty());
  for (const vec3& n : a.meshes[0].normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
  const std::string split = write_file("split.obj",
                                       "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\n"
                                       "f 1/1 2/1 3/1\nf 1/2 3/2 4/2\n");
  EXPECT_EQ(load_obj_scene(split).meshes[0].positions.size(), 6u);
}

TEST(ObjLoader, OneMeshPerShapeAndMaterial) {
  write_file("two.mtl", "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n");
  const std::string path =
      write_file("two_materials.obj",
                 "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                 "g thing\nusemtl red\nf 1 2 3\nusemtl blue\nf 1 3 4\nusemtl red\nf 1 4 2\n"
                 "g other\nf 2 3 4\n");
  const Scene s = load_obj_scene(path);
  ASSERT_EQ(s.meshes.size(), 3u);
  EXPECT_EQ(s.meshes[0].name, "thing/red");
  EXPECT_EQ(s.meshes[0].triangle_count(), 2u);
  EXPECT_EQ(s.meshes[1].name, "thing/blue");
  EXPECT_EQ(s.meshes[2].name, "other");  // usemtl carries over a `g`: still "red"
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[size_t(s.meshes[0].material)].albedo, vec3(1, 0, 0));
  EXPECT_EQ(s.materials[size_t(s.meshes[1].material)].name, "blue");
  EXPECT_EQ(s.meshes[2].material, s.meshes[0].material);
}

// A 4 × 2 texture: left half alpha 0, right half alpha 255 (RGBA), or grey for map_d.
std::vector<unsigned char> rgba_half_transparent() {
  std::vector<unsigned char> px;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x)
      px.insert(px.end(), {200, 100, 50, (unsigned char)(x < 2 ? 0 : 255)});
  return px;
}

TEST(ObjLoader, AlphaTextureRules) {
  write_png("half.png", 4, 2, 4, rgba_half_transparent());
  write_png("grey_mask.png", 4, 2, 1, {0, 0, 255, 255, 0, 0, 255, 255});
  std::vector<unsigned char> opaque(4 * 2 * 4, 255);
  write_png("opaque.png", 4, 2, 4, opaque);
  write_file("alpha.mtl",
             "newmtl from_map_d\nKd 1 1 1\nmap_Kd half.png\nmap_d half.png\n"
             "newmtl from_grey_map_d\nKd 1 1 1\nmap_d grey_mask.png\n"
             "newmtl from_map_kd\nKd 1 1 1\nmap_Kd half.png\n"
             "newmtl opaque_kd\nKd 1 1 1\nmap_Kd opaque.png\n"
             "newmtl dissolved\nKd 0.5 0.5 0.5\nd 0\n");
  std::string obj = "mtllib alpha.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n";
  for (const char* m : {"from_map_d", "from_grey_map_d", "from_map_kd", "opaque_kd", "dissolved"})
    obj += std::string("usemtl ") + m + "\nf 1/1 2/2 3/3\n";
  std::vector<std::string> notes;
  const Scene s = load_obj_scene(write_file("alpha.obj", obj), &notes);
  ASSERT_EQ(s.materials.size(), 5u);
  auto mat = [&](const std::string& name) {
    for (const Material& m : s.materials)
      if (m.name == name) return m;
    ADD_FAILURE() << "no material " << name;
    return Material{};
  };
  const Material d = mat("from_map_d"), g = mat("from_grey_map_d"), k = mat("from_map_kd");
  ASSERT_GE(d.alpha_texture, 0);
  ASSERT_GE(g.alpha_texture, 0);
  ASSERT_GE(k.alpha_texture, 0);
  EXPECT_EQ(d.alpha_texture, k.alpha_texture) << "one texture per file and alpha source";
  EXPECT_EQ(mat("opaque_kd").alpha_texture, -1) << "map_Kd alpha all 1: opaque fast path";
  EXPECT_EQ(mat("dissolved").alpha_texture, -1) << "d 0 alone never makes a cutout";
  EXPECT_FLOAT_EQ(d.alpha_cutoff, 0.5f);
  const ImageF& tex = s.textures[size_t(g.alpha_texture)];
  EXPECT_EQ(tex.at(0, 0, 3), 0.0f);  // grey 0 → alpha 0
  EXPECT_EQ(tex.at(3, 1, 3), 1.0f);  // grey 255 → alpha 1
  // Albedo = Kd × mean linear colour of the texels that pass the alpha test.
  EXPECT_NEAR(d.albedo.x, 0.5776f, 1e-3f);  // sRGB 200 → linear 0.5776
  // map_Kd is also the colour texture (linear RGB), with Kd as its factor; without map_Kd none.
  ASSERT_GE(k.color_texture, 0);
  EXPECT_EQ(k.color_factor, vec3(1.0f));
  EXPECT_NEAR(s.textures[size_t(k.color_texture)].at(0, 0, 1), 0.1274f, 1e-3f);  // sRGB 100
  EXPECT_EQ(mat("dissolved").color_texture, -1);
  EXPECT_EQ(g.color_texture, -1);
  bool dissolve_note = false;
  for (const std::string& n : notes) dissolve_note |= n.find("dissolved") != std::string::npos;
  EXPECT_TRUE(dissolve_note) << "d < 1 without map_d gives a note";
  // An alpha-textured mesh without uvs cannot be alpha tested.
  expect_load_error(
      write_file("alpha_no_uv.obj",
                 "mtllib alpha.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl from_map_d\nf 1 2 3\n"),
      {"alpha_no_uv.obj", "texture coordinates"});
}

TEST(ObjLoader, ViewHeaderIsParsed) {
  const std::string path = write_file(
      "header.obj",
      "# scene: point light (1,2.5,-3), near 0.1 far 25\n"
      "# camera eye (0, 4.5, 9.5) target (0,3,0) up (0,1,0) vertical fov 45 deg, 640x480\n" +
          std::string(kTriangle) + "f 1 2 3\n# camera eye (9,9,9) target (0,0,0)\n");
  const ObjViewHeader h = read_obj_view_header(path);
  ASSERT_TRUE(h.light.has_value());
  EXPECT_EQ(h.light->position, vec3(1.0f, 2.5f, -3.0f));
  EXPECT_FLOAT_EQ(h.light->near, 0.1f);
  EXPECT_FLOAT_EQ(h.light->far, 25.0f);
  ASSERT_TRUE(h.camera.has_value());
  EXPECT_EQ(h.camera->eye, vec3(0.0f, 4.5f, 9.5f)) << "only the leading comments count";
  EXPECT_EQ(h.camera->target, vec3(0.0f, 3.0f, 0.0f));
  EXPECT_FLOAT_EQ(h.camera->fov_y_deg, 45.0f);
  EXPECT_EQ(h.camera->width, 640);
  EXPECT_EQ(h.camera->height, 480);
  const ObjViewHeader none = read_obj_view_header(write_file("no_header.obj", kTriangle));
  EXPECT_FALSE(none.light.has_value());
  EXPECT_FALSE(none.camera.has_value());
}

// Misspelled keys in the view header are errors naming the line (they used to drop the light or
// camera silently); free-text comments without a position are still free.
TEST(ObjLoader, ViewHeaderTyposAreErrors) {
  auto expect_header_error = [](const std::string& name, const std::string& header, const std::string& needle) {
    try {
      read_obj_view_header(write_file(name, header + kTriangle + "f 1 2 3\n"));
      ADD_FAILURE() << name << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("line"), std::string::npos) << e.what();
    }
  };
  expect_header_error("typo_light.obj", "# point ligth (0,4,0), near 0.05 far 40\n", "'ligth'");
  expect_header_error("typo_target.obj", "# camera eye (0,4.5,9.5) targte (0,3,0)\n", "'targte'");
  expect_header_error("typo_near.obj", "# light (0,4,0) naer 0.05 far 40\n", "misspelled 'near'");
  // Two edits: two letters replaced ("noxr"), or one replaced and one dropped ("fr").
  expect_header_error("typo_near2.obj", "# light (0,4,0) noxr 0.05 far 40\n", "misspelled 'near'");
  expect_header_error("typo_far2.obj", "# light (0,4,0) near 0.05 fr 40\n", "misspelled 'far'");
  expect_header_error("typo_fov.obj", "# camera eye (0,1,5) target (0,0,0) vertical fvo 45\n", "misspelled 'fov'");
  // Malformed positions and a misspelled "camera" drop nothing silently either.
  expect_header_error("short_eye.obj", "# camera eye (0,1) target (0,0,0)\n", "'eye' is followed by a malformed position");
  expect_header_error("short_light.obj", "# point light (0,4), near 0.05\n", "'light' is followed by a malformed position");
  expect_header_error("typo_camera.obj", "# camra eye (0,1,2) target (0,0,0)\n", "a camera line reads");
  expect_header_error("no_target.obj", "# camera eye (0,1,2)\n", "a camera line reads");
  const ObjViewHeader free = read_obj_view_header(
      write_file("free_text.obj", std::string("# made with a tool (v2), far from perfect: 3 parts\n") + kTriangle));
  EXPECT_FALSE(free.light.has_value());
}

// ---- real assets ---------------------------------------------------------------------------

double load_ms(const std::string& path, Scene& out) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::string> notes;
  out = load_obj_scene(path, &notes);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

TEST(ObjAssets, BunnyHasExactlyItsTriangles) {
  Scene s;
  const double ms = load_ms(test::assets_dir() + "/bunny/stanford-bunny.obj", s);
  std::printf("[ timing ] bunny: %.1f ms\n", ms);
  EXPECT_EQ(s.triangle_count(), 69451u);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_TRUE(s.meshes[0].uvs.empty());
  for (const vec3& n : s.meshes[0].normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
  EXPECT_NO_THROW(validate_scene(s, "bunny"));
}

TEST(ObjAssets, Room100kHasExactlyItsTriangles) {
  Scene s;
  const double ms = load_ms(test::assets_dir() + "/bench/room100k.obj", s);
  std::printf("[ timing ] room100k: %.1f ms\n", ms);
  EXPECT_EQ(s.triangle_count(), 99852u);
  EXPECT_EQ(s.materials.size(), 1u);
}

TEST(ObjAssets, PalmLeavesAreAlphaTexturedTrunkIsNot) {
  const Scene s = load_obj_scene(test::assets_dir() + "/palm_tree/palm_tree.obj");
  EXPECT_EQ(s.triangle_count(), 632u);
  int leaves = -1, trunk = -1;
  for (size_t i = 0; i < s.materials.size(); ++i) {
    if (s.materials[i].name == "palm_leaves") leaves = int(i);
    if (s.materials[i].name == "palm_trunk") trunk = int(i);
  }
  ASSERT_GE(leaves, 0);
  ASSERT_GE(trunk, 0);
  EXPECT_GE(s.materials[size_t(leaves)].alpha_texture, 0);
  EXPECT_EQ(s.materials[size_t(trunk)].alpha_texture, -1);
  size_t leaf_triangles = 0;
  for (const Mesh& m : s.meshes)
    if (m.material == leaves) {
      leaf_triangles += m.triangle_count();
      EXPECT_EQ(m.uvs.size(), m.positions.size());
    }
  EXPECT_EQ(leaf_triangles, 560u);
  // The leaf PNG is a near-binary mask: a good share of texels is fully transparent.
  const ImageF& tex = s.textures[size_t(s.materials[size_t(leaves)].alpha_texture)];
  size_t transparent = 0;
  for (int y = 0; y < tex.height; ++y)
    for (int x = 0; x < tex.width; ++x) transparent += tex.at(x, y, 3) == 0.0f;
  EXPECT_GT(double(transparent) / double(tex.pixel_count()), 0.3);
}

TEST(ObjAssets, PlantsLoadWithCutouts) {
  const std::pair<const char*, size_t> plants[] = {
      {"parviflora", 448}, {"fern3", 608}, {"shrub", 472}, {"shrub_red", 508}};
  for (const auto& [name, triangles] : plants) {
    SCOPED_TRACE(name);
    const Scene s = load_obj_scene(test::assets_dir() + "/plants/" + name + ".obj");
    EXPECT_EQ(s.triangle_count(), triangles);
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_GE(s.materials[0].alpha_texture, 0);
  }
}

}  // namespace
}  // namespace shadowlab
