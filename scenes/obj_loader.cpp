#include "scenes/obj_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "core/error.h"
#include "core/input_file.h"
#include "core/notes.h"
#include "core/run_inputs.h"
#include "scenes/obj_text_check.h"
#include "core/rng.h"
#include "core/texture.h"

namespace shadowlab {
namespace {

namespace fs = std::filesystem;

// Drops a UTF-8 byte-order mark: tinyobjloader would read "\xEF\xBB\xBFv" as an unknown
// statement and silently lose the first vertex.
void strip_bom(std::string& text) {
  if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);
}

// `name` from an OBJ/MTL statement resolved against `dir` (Windows separators accepted).
std::string resolve_path(const std::string& dir, std::string name) {
  for (char& c : name)
    if (c == '\\') c = '/';
  const fs::path p(name);
  return p.is_absolute() ? p.string() : (fs::path(dir) / p).lexically_normal().string();
}

// Loads MTL files relative to the OBJ's folder, checks their text first, and remembers which
// file each material came from (texture paths are relative to it). Failures are recorded,
// not thrown, because tinyobjloader's compiled code sits between us and the caller.
class MtlReader : public tinyobj::MaterialReader {
 public:
  MtlReader(std::string obj_path, std::string obj_dir)
      : obj_path_(std::move(obj_path)), obj_dir_(std::move(obj_dir)) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* material_map, std::string* warn,
                  std::string* err) override {
    const std::string path = resolve_path(obj_dir_, name);
    std::string text, why;
    note_input(path);
    if (!try_read_input_file(path, kMaterialFileLimit, text, &why)) {
      record(InputError(path, why + " (mtllib of " + obj_path_ + ")"));
      return false;
    }
    strip_bom(text);
    try {
      check_mtl_text(path, text);
    } catch (const InputError& e) {
      record(e);
      return false;
    }
    std::istringstream in(text);
    tinyobj::LoadMtl(material_map, materials, &in, warn, err);
    source_mtl.resize(materials->size(), path);
    return true;
  }

  std::vector<std::string> source_mtl;  // per tinyobj material: the MTL it came from
  std::unique_ptr<InputError> failure;  // first failure, rethrown after parsing

 private:
  void record(const InputError& e) {
    if (!failure) failure = std::make_unique<InputError>(e);
  }
  std::string obj_path_;
  std::string obj_dir_;
};

// A face corner as indexed by the file; identical triples are welded.
struct CornerKey {
  int v, vn, vt;
  bool operator==(const CornerKey& o) const { return v == o.v && vn == o.vn && vt == o.vt; }
};
struct CornerHash {
  size_t operator()(const CornerKey& k) const {
    return size_t(mix64((uint64_t(uint32_t(k.v)) << 32 | uint32_t(k.vn)) ^ mix64(uint32_t(k.vt))));
  }
};

struct MeshBuild {
  int material = -1;              // tinyobj material id, -1 = none
  std::string shape_name;         // `g`/`o` name, may be empty
  bool split = false;             // the shape uses several materials
  std::vector<CornerKey> keys;    // welded vertices in first-use order
  std::vector<uint32_t> indices;  // 3 per triangle, into keys
};

struct Notes {
  std::string path;
  std::vector<std::string>* out;
  void add(const std::string& note) const {
    if (out)
      out->push_back(note);
    else
      hold_note("warning: " + path + ": " + note);
  }
};

// Turns tinyobjloader's warning text into errors, except for messages that lose nothing.
void handle_tinyobj_warnings(const std::string& path, const std::string& warn, bool has_mtllib,
                             const Notes& notes) {
  std::istringstream lines(warn);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty() || line == ".") continue;
    const bool missing_material = line.find("not found in .mtl") != std::string::npos;
    if (line.find("Empty group name") != std::string::npos ||
        line.find("Both `d` and `Tr`") != std::string::npos || (missing_material && !has_mtllib)) {
      notes.add(line + (missing_material ? " (no mtllib: default material used)" : ""));
      continue;
    }
    throw InputError(path, "tinyobjloader: " + line);
  }
}

// Adds the triangles of one tinyobj shape to per-material mesh builders, welding corners.
void build_shape_meshes(const tinyobj::shape_t& shape, std::vector<MeshBuild>& out) {
  const tinyobj::mesh_t& m = shape.mesh;
  std::vector<MeshBuild> local;
  std::vector<std::unordered_map<CornerKey, uint32_t, CornerHash>> welds;
  size_t offset = 0;
  for (size_t f = 0; f < m.num_face_vertices.size(); ++f) {
    const size_t n = m.num_face_vertices[f];
    const int mat = f < m.material_ids.size() ? m.material_ids[f] : -1;
    size_t bi = 0;
    while (bi < local.size() && local[bi].material != mat) ++bi;
    if (bi == local.size()) {
      local.emplace_back();
      local.back().material = mat;
      local.back().shape_name = shape.name;
      welds.emplace_back();
    }
    MeshBuild& b = local[bi];
    auto& weld = welds[bi];
    uint32_t corner[3] = {0, 0, 0};
    // Triangulated input has n == 3; anything else is fanned defensively.
    for (size_t k = 0; k < n; ++k) {
      const tinyobj::index_t& ix = m.indices[offset + k];
      const CornerKey key{ix.vertex_index, ix.normal_index, ix.texcoord_index};
      const auto [it, inserted] = weld.try_emplace(key, uint32_t(b.keys.size()));
      if (inserted) b.keys.push_back(key);
      if (k < 2) {
        corner[k] = it->second;
        continue;
      }
      corner[2] = it->second;
      b.indices.insert(b.indices.end(), {corner[0], corner[1], corner[2]});
      corner[1] = corner[2];
    }
    offset += n;
  }
  for (MeshBuild& b : local) {
    b.split = local.size() > 1;
    if (!b.indices.empty()) out.push_back(std::move(b));
  }
}

// Builds a Mesh from a welded builder and tinyobj's attribute arrays.
Mesh make_mesh(const std::string& path, const tinyobj::attrib_t& a, const MeshBuild& b,
               std::string name, const Notes& notes) {
  Mesh mesh;
  mesh.name = std::move(name);
  mesh.indices = b.indices;
  const size_t nv = b.keys.size();
  size_t with_vn = 0, with_vt = 0;
  for (const CornerKey& k : b.keys) {
    with_vn += k.vn >= 0;
    with_vt += k.vt >= 0;
  }
  const bool all_vn = with_vn == nv;
  mesh.positions.resize(nv);
  if (all_vn) mesh.normals.resize(nv);
  if (with_vt > 0) mesh.uvs.assign(nv, vec2(0.0f));
  bool bad_normal = false;
  // Every index is range-checked here too (the text check should have caught any bad one; a
  // disagreement between it and tinyobjloader must not read outside the arrays).
  const size_t n_pos = a.vertices.size() / 3, n_nrm = a.normals.size() / 3, n_uv = a.texcoords.size() / 2;
  for (const CornerKey& k : b.keys)
    if (k.v < 0 || size_t(k.v) >= n_pos || (all_vn && size_t(k.vn) >= n_nrm) ||
        (k.vt >= 0 && size_t(k.vt) >= n_uv))
      throw InputError(path, "a face refers to a vertex, normal or texcoord the file does not have");
  for (size_t i = 0; i < nv; ++i) {
    const CornerKey& key = b.keys[i];
    const float* p = &a.vertices[3 * size_t(key.v)];
    mesh.positions[i] = vec3(p[0], p[1], p[2]);
    if (!is_finite(mesh.positions[i]))
      throw InputError(path,
                       "vertex " + std::to_string(key.v + 1) + " has a NaN or infinite coordinate");
    if (all_vn) {
      const float* q = &a.normals[3 * size_t(key.vn)];
      const vec3 n(q[0], q[1], q[2]);
      const float len = glm::length(n);
      const bool ok = len > 0.0f && std::isfinite(len);
      bad_normal |= !ok;
      mesh.normals[i] = ok ? n / len : vec3(0.0f, 1.0f, 0.0f);
    }
    if (key.vt >= 0)
      mesh.uvs[i] = vec2(a.texcoords[2 * size_t(key.vt)], a.texcoords[2 * size_t(key.vt) + 1]);
  }
  if (!all_vn || bad_normal) {
    if (with_vn > 0)
      notes.add("mesh '" + mesh.name +
                "': " + (bad_normal ? "zero-length normals" : "normals on only some corners") +
                ", all its normals recomputed");
    mesh.normals.clear();
    compute_vertex_normals(mesh);
  }
  if (with_vt > 0 && with_vt < nv)
    notes.add("mesh '" + mesh.name + "': texture coordinates on only some corners; (0, 0) used");
  return mesh;
}

// Converts the used tinyobj materials and loads their textures (once per file).
class MaterialBuilder {
 public:
  MaterialBuilder(const std::vector<tinyobj::material_t>& mats,
                  const std::vector<std::string>& source_mtl, Scene& scene, const Notes& notes)
      : mats_(mats), source_mtl_(source_mtl), scene_(scene), notes_(notes) {}

  // Scene material index of tinyobj material `id` (-1: the default material).
  int index_of(int id) {
    if (auto it = done_.find(id); it != done_.end()) return it->second;
    scene_.materials.push_back(id < 0 ? default_material() : convert(size_t(id)));
    return done_[id] = int(scene_.materials.size()) - 1;
  }

 private:
  static Material default_material() {
    Material m;
    m.name = "default";
    m.albedo = vec3(0.8f);
    return m;
  }

  // Loads a texture file once; errors name the file and, in the reason, who refers to it.
  const Texture8& texture(const std::string& path, const char* statement, size_t material) {
    auto it = files_.find(path);
    if (it == files_.end()) {
      try {
        it = files_.emplace(path, load_texture8(path)).first;
      } catch (const InputError& e) {
        throw InputError(e.where, e.reason + " (" + statement + " of material '" +
                                      mats_[material].name + "' in " + source_mtl_[material] + ")");
      }
    }
    return it->second;
  }

  // Index into scene.textures of the RGBA texture whose alpha is channel `alpha_from` of the
  // file; -1 when that alpha is 1 everywhere (the material is then opaque).
  int alpha_texture(const std::string& path, int alpha_from) {
    const std::string key = path + "#" + std::to_string(alpha_from);
    if (auto it = alpha_.find(key); it != alpha_.end()) return it->second;
    const Texture8& t = files_.at(path);
    ImageF img = texture_to_linear_rgba(t);
    bool any_transparent = false;
    for (int y = 0; y < t.height; ++y)
      for (int x = 0; x < t.width; ++x) {
        const uint8_t a = t.at(x, y, alpha_from);
        any_transparent |= a < 255;
        img.at(x, y, 3) = float(a) / 255.0f;
      }
    int index = -1;
    if (any_transparent) {
      scene_.textures.push_back(std::move(img));
      index = int(scene_.textures.size()) - 1;
    }
    return alpha_[key] = index;
  }

  // Index into scene.textures of the linear RGBA colour texture of a map_Kd file (one per file).
  int color_texture(const std::string& path) {
    const std::string key = path + "#colour";
    if (auto it = alpha_.find(key); it != alpha_.end()) return it->second;
    scene_.textures.push_back(texture_to_linear_rgba(files_.at(path)));
    return alpha_[key] = int(scene_.textures.size()) - 1;
  }

  Material convert(size_t id) {
    const tinyobj::material_t& tm = mats_[id];
    const std::string dir = fs::path(source_mtl_[id]).parent_path().string();
    Material m;
    m.name = tm.name;
    m.albedo = glm::max(vec3(tm.diffuse[0], tm.diffuse[1], tm.diffuse[2]), vec3(0.0f));
    m.alpha_cutoff = 0.5f;
    const Texture8* kd = nullptr;
    std::string kd_path;
    if (!tm.diffuse_texname.empty()) {
      kd_path = resolve_path(dir, tm.diffuse_texname);
      kd = &texture(kd_path, "map_Kd", id);
    }
    if (!tm.alpha_texname.empty()) {
      const std::string path = resolve_path(dir, tm.alpha_texname);
      const Texture8& t = texture(path, "map_d", id);
      m.alpha_texture = alpha_texture(path, t.file_has_alpha() ? 3 : 0);
      if (m.alpha_texture < 0)
        notes_.add("material '" + m.name + "': map_d is opaque everywhere, alpha test skipped");
    } else if (kd && kd->file_has_alpha()) {
      m.alpha_texture = alpha_texture(kd_path, 3);
      if (m.alpha_texture >= 0)
        notes_.add("material '" + m.name + "': no map_d, map_Kd's alpha channel is the cutout");
    }
    if (tm.dissolve < 1.0f)
      notes_.add("material '" + m.name + "': d " + (std::ostringstream() << tm.dissolve).str() +
                 " ignored (no translucency); " +
                 (m.alpha_texture >= 0 ? "its alpha texture is the cutout" : "treated as opaque"));
    if (kd) {
      m.color_factor = m.albedo;
      m.color_texture = color_texture(kd_path);
      m.albedo *= mean_colour(*kd, m.alpha_cutoff);
    }
    return m;
  }

  // Mean linear colour over the texels whose alpha passes the cutoff (all if none does).
  static vec3 mean_colour(const Texture8& t, float cutoff) {
    dvec3 sum(0.0), all(0.0);
    size_t count = 0;
    for (int y = 0; y < t.height; ++y)
      for (int x = 0; x < t.width; ++x) {
        const dvec3 c(srgb8_to_linear(t.at(x, y, 0)), srgb8_to_linear(t.at(x, y, 1)),
                      srgb8_to_linear(t.at(x, y, 2)));
        all += c;
        if (alpha_test_passes(float(t.at(x, y, 3)) / 255.0f, cutoff)) {
          sum += c;
          ++count;
        }
      }
    return count > 0 ? vec3(sum / double(count)) : vec3(all / double(t.width * t.height));
  }

  const std::vector<tinyobj::material_t>& mats_;
  const std::vector<std::string>& source_mtl_;
  Scene& scene_;
  const Notes& notes_;
  std::map<int, int> done_;
  std::map<std::string, Texture8> files_;
  std::map<std::string, int> alpha_;
};

}  // namespace

Scene load_obj_scene(const std::string& path, std::vector<std::string>* notes_out) {
  const Notes notes{path, notes_out};
  note_input(path);
  std::string text = read_input_file(path, kModelFileLimit);
  strip_bom(text);
  const ObjTextSummary summary = check_obj_text(path, text);
  for (const std::string& n : summary.notes) notes.add(n);
  if (summary.triangles == 0) throw InputError(path, "the model has no triangles");

  // Parse with tinyobjloader (triangulating); MTLs resolve relative to the OBJ's folder.
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  MtlReader mtl_reader(path, fs::path(path).parent_path().string());
  bool ok = false;
  {
    std::istringstream in(std::move(text));
    ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &mtl_reader,
                          /*triangulate=*/true, /*default_vcols_fallback=*/false);
  }
  if (mtl_reader.failure) throw *mtl_reader.failure;
  if (!ok || !err.empty())
    throw InputError(path, "tinyobjloader: " + (err.empty() ? std::string("parse failed") : err));
  handle_tinyobj_warnings(path, warn, summary.has_mtllib, notes);

  // Meshes per (shape, material), welded.
  std::vector<MeshBuild> builds;
  for (const tinyobj::shape_t& shape : shapes) build_shape_meshes(shape, builds);
  size_t triangles = 0;
  for (const MeshBuild& b : builds) triangles += b.indices.size() / 3;
  if (triangles == 0) throw InputError(path, "the model has no triangles");
  if (triangles != summary.triangles)
    notes.add("triangulation gave " + std::to_string(triangles) +
              " triangles where the faces' corner counts imply " +
              std::to_string(summary.triangles) + " (degenerate polygons)");

  Scene scene;
  scene.name = fs::path(path).stem().string();
  MaterialBuilder mats(materials, mtl_reader.source_mtl, scene, notes);
  for (const MeshBuild& b : builds) {
    const int material = mats.index_of(b.material);
    const Material& mat = scene.materials[size_t(material)];
    const std::string name =
        (b.shape_name.empty() ? scene.name : b.shape_name) + (b.split ? "/" + mat.name : "");
    Mesh mesh = make_mesh(path, attrib, b, name, notes);
    mesh.material = material;
    if (mat.alpha_texture >= 0 && mesh.uvs.empty())
      throw InputError(path, "mesh '" + mesh.name + "' uses the alpha-textured material '" +
                                 mat.name + "' but has no texture coordinates");
    scene.meshes.push_back(std::move(mesh));
  }
  validate_scene(scene, path);
  return scene;
}

namespace {

// Edit distance of two short words, an adjacent swap counting as one edit (optimal string
// alignment; a typo check, so plain O(n·m)).
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// A view header line's keys must be spelled right, or its light or camera would be dropped
// without a word. Only lines holding a position "(x,y,z)" are view header lines (other
// comments are free text); in them every position must follow light, eye, target or up, and a
// word directly before a number that is within two edits of near, far or fov must be that key.
void check_view_header_line(const std::string& path, size_t line_no, const std::string& line) {
  static const char* const kVectorKeys[] = {"light", "eye", "target", "up"};
  static const char* const kNumberKeys[] = {"near", "far", "fov"};
  auto fail = [&](const std::string& what) {
    throw InputError(path, "line " + std::to_string(line_no) + " (view header): " + what);
  };
  auto is_vector_at = [&](size_t i) {  // "(" number "," number "," number ")"
    float x, y, z;
    char close = 0;
    return std::sscanf(line.c_str() + i, "( %f , %f , %f %c", &x, &y, &z, &close) == 4 && close == ')';
  };
  bool has_vector = false;
  for (size_t i = 0; i < line.size() && !has_vector; ++i) has_vector = line[i] == '(' && is_vector_at(i);
  // A "(" right after a position key (light, eye, target, up) must open a position, even on a
  // line with no valid one ("# light (0,4)" is a broken header line, not free text).
  {
    std::string w;
    for (size_t i = 0; i < line.size(); ++i) {
      const unsigned char c = static_cast<unsigned char>(line[i]);
      if (std::isalpha(c)) {
        if (i == 0 || !std::isalpha(static_cast<unsigned char>(line[i - 1]))) w.clear();
        w += char(std::tolower(c));
      } else if (c == '(') {
        if (std::any_of(std::begin(kVectorKeys), std::end(kVectorKeys), [&](const char* k) { return w == k; }) &&
            !is_vector_at(i))
          fail("'" + w + "' is followed by a malformed position (expected (x,y,z))");
        w.clear();
      } else if (c != ' ' && c != '\t') {
        w.clear();
      }
    }
  }
  if (!has_vector) return;
  std::string word;  // the last word, lower case, while only spaces follow it
  for (size_t i = 0; i < line.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(line[i]);
    if (std::isalpha(c)) {
      if (i == 0 || !std::isalpha(static_cast<unsigned char>(line[i - 1]))) word.clear();
      word += char(std::tolower(c));
      continue;
    }
    if (c == ' ' || c == '\t') continue;
    if (c == '(' && is_vector_at(i)) {
      if (std::none_of(std::begin(kVectorKeys), std::end(kVectorKeys), [&](const char* k) { return word == k; }))
        fail("a position follows '" + word + "', not light, eye, target or up");
    } else if ((std::isdigit(c) || c == '-' || c == '.') && !word.empty() &&
               (i == 0 || !std::isalnum(static_cast<unsigned char>(line[i - 1])))) {
      // The nearest key within two edits (ties: the first), unless the word is a key.
      const char* nearest = nullptr;
      size_t best = 3;
      for (const char* k : kNumberKeys) {
        const size_t dist = edit_distance(word, k);
        if (dist < best) best = dist, nearest = k;
      }
      if (nearest && best > 0) fail("'" + word + "' looks like a misspelled '" + nearest + "'");
    }
    word.clear();
  }
}

}  // namespace

ObjViewHeader read_obj_view_header(const std::string& path) {
  note_input(path);
  check_input_file(path, kModelFileLimit);
  std::ifstream in(path);
  if (!in) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  ObjViewHeader h;
  // Reads "(x,y,z)" after `key`; false when absent or malformed.
  auto vec_after = [](const std::string& line, const char* key, vec3& out) {
    const size_t k = line.find(key);
    if (k == std::string::npos) return false;
    const size_t open = line.find('(', k);
    if (open == std::string::npos) return false;
    return std::sscanf(line.c_str() + open, "( %f , %f , %f )", &out.x, &out.y, &out.z) == 3 &&
           is_finite(out);
  };
  auto float_after = [](const std::string& line, const char* key, float& out) {
    const size_t k = line.find(key);
    if (k == std::string::npos) return false;
    return std::sscanf(line.c_str() + k + std::strlen(key), " %f", &out) == 1 && std::isfinite(out);
  };
  std::string line;
  size_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    if (line[first] != '#') break;  // the header ends at the first statement
    check_view_header_line(path, line_no, line);
    // A line with a camera's positions must be a whole camera line: "camera eye (x,y,z) target
    // (x,y,z)" (a misspelled "camera" would drop the camera without a word).
    {
      std::string low = line;
      for (char& ch : low) ch = char(std::tolower(static_cast<unsigned char>(ch)));
      vec3 e, t;
      if ((vec_after(low, "eye", e) || vec_after(low, "target", t)) &&
          !(vec_after(low, "camera eye", e) && vec_after(low, "target", t)))
        throw InputError(path, "line " + std::to_string(line_no) +
                                   " (view header): a camera line reads 'camera eye (x,y,z) target "
                                   "(x,y,z)'");
    }
    vec3 p;
    if (line.find("light") != std::string::npos && vec_after(line, "light", p)) {
      PointLight l;
      l.position = p;
      l.radius = 0.0f;
      float v = 0.0f;
      if (float_after(line, "near", v)) l.near = v;
      if (float_after(line, "far", v)) l.far = v;
      h.light = l;
    }
    Camera c;
    if (vec_after(line, "camera eye", c.eye) && vec_after(line, "target", c.target)) {
      if (!vec_after(line, "up", c.up)) c.up = vec3(0.0f, 1.0f, 0.0f);
      float fov = 0.0f;
      if (float_after(line, "fov", fov)) c.fov_y_deg = fov;
      // "<W>x<H>": the first 'x' between digits.
      for (size_t i = 1; i + 1 < line.size(); ++i)
        if (line[i] == 'x' && std::isdigit((unsigned char)line[i - 1]) &&
            std::isdigit((unsigned char)line[i + 1])) {
          size_t b = i;
          while (b > 0 && std::isdigit((unsigned char)line[b - 1])) --b;
          int w = 0, hh = 0;
          if (std::sscanf(line.c_str() + b, "%dx%d", &w, &hh) == 2) {
            c.width = w;
            c.height = hh;
          }
          break;
        }
      h.camera = c;
    }
  }
  return h;
}

}  // namespace shadowlab
