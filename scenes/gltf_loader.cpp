#include "scenes/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <memory>
#include <vector>

#include <sys/stat.h>

#include <glm/gtc/quaternion.hpp>
#include <fmt/format.h>
#include <stb_image.h>
#include <tiny_gltf.h>

#include "core/text.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/json_check.h"
#include "core/notes.h"
#include "core/run_inputs.h"
#include "core/parse_number.h"
#include "scenes/scene_library.h"
#include "core/slide.h"
#include "core/texture.h"

namespace shadowlab {
namespace {

constexpr int kMaxTextureSide = 16384;

using tinygltf::Accessor;
using tinygltf::Model;

// First line of a tinygltf message (its errors can run over several lines).
std::string first_line(const std::string& s) {
  std::string t = s.substr(0, s.find('\n'));
  while (!t.empty() && (t.back() == '\r' || t.back() == ' ')) t.pop_back();
  return t;
}

// The image decoder given to tinygltf: stb_image, with the size checked from the header first
// (an image claiming 10⁵ × 10⁵ texels is refused before any allocation). 8-bit RGBA out.
bool load_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int,
                int, const unsigned char* bytes, int size, void*) {
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(bytes, size, &w, &h, &comp)) {
    if (err) *err = "image " + std::to_string(index) + " cannot be decoded (not a PNG/JPEG?)";
    return false;
  }
  if (w < 1 || h < 1 || w > kMaxTextureSide || h > kMaxTextureSide) {
    if (err)
      *err = "image " + std::to_string(index) + " is " + std::to_string(w) + "x" +
             std::to_string(h) + " texels (at most " + std::to_string(kMaxTextureSide) + " per side)";
    return false;
  }
  unsigned char* px = stbi_load_from_memory(bytes, size, &w, &h, &comp, 4);
  if (!px) {
    if (err) *err = "image " + std::to_string(index) + " cannot be decoded: " + stbi_failure_reason();
    return false;
  }
  image->width = w;
  image->height = h;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image.assign(px, px + size_t(w) * size_t(h) * 4);
  // Remember whether the file had alpha (comp 2 or 4) in `name`'s place would be a hack; the
  // alpha channel of a file without alpha is 255, which is what MASK then reads.
  stbi_image_free(px);
  return true;
}

class Loader {
 public:
  Loader(const std::string& path, std::vector<std::string>* notes) : path_(path), notes_(notes) {}

  Scene load(const GltfChoice& choice, GltfContents* contents) {
    read_model();
    Scene s;
    const size_t slash = path_.find_last_of('/');
    std::string stem = slash == std::string::npos ? path_ : path_.substr(slash + 1);
    s.name = stem.substr(0, stem.find_last_of('.'));
    if (model_.scenes.empty()) fail("the file has no scene (nothing to render)");
    const int scene_index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (scene_index >= int(model_.scenes.size()))
      fail("the default scene " + std::to_string(scene_index) + " does not exist");
    visited_.assign(model_.nodes.size(), 0);
    for (int root : model_.scenes[size_t(scene_index)].nodes) visit(s, root);
    if (s.meshes.empty()) fail("the scene has no triangles");
    for (Mesh& m : s.meshes)
      if (m.material < 0) m.material = default_material(s);
    pick_light(s, choice, contents);
    pick_camera(s, choice, contents);
    return s;
  }

 private:
  using dmat4 = glm::dmat4;
  using dvec3 = glm::dvec3;

  [[noreturn]] void fail(const std::string& reason) const { throw InputError(path_, reason); }
  void note(const std::string& text) {
    if (notes_) notes_->push_back(text);
    else hold_note("warning: " + path_ + ": " + text);
  }

  void read_model() {
    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(load_image, nullptr);
    // Buffers and images named by URI are read through the same checks as the file itself.
    ExternalFiles files{path_, nullptr};
    gltf.SetFsCallbacks({&external_file_exists, &external_path, &read_external_file,
                         &refuse_write, &files});
    const std::vector<unsigned char> bytes = read_input_bytes(path_, kModelFileLimit);
    const size_t slash = path_.find_last_of('/');
    const std::string base_dir = slash == std::string::npos ? "" : path_.substr(0, slash);
    std::string err, warn;
    const std::string ext = ascii_lower(path_.substr(path_.find_last_of('.') + 1));
    bool ok = false;
    note_input(path_);
    // The JSON is checked (syntax, nesting, keys) before tinygltf, whose conversion of
    // "extras" and "extensions" recurses once per level, parses it.
    if (ext == "glb") {
      check_glb_json(bytes);
      ok = gltf.LoadBinaryFromMemory(&model_, &err, &warn, bytes.data(), unsigned(bytes.size()), base_dir);
    } else {
      check_json_text(reinterpret_cast<const char*>(bytes.data()), bytes.size(), path_);
      ok = gltf.LoadASCIIFromString(&model_, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                    unsigned(bytes.size()), base_dir);
    }
    if (files.failure) throw *files.failure;
    if (!ok || !err.empty())
      fail(err.empty() ? "cannot be read as glTF 2.0" : first_line(err));
    if (!warn.empty()) note(first_line(warn));
    // The files it refers to are inputs of the run too (core/run_inputs.h).
    const std::string folder = path_.find('/') == std::string::npos ? "." : path_.substr(0, path_.rfind('/'));
    for (const tinygltf::Buffer& b : model_.buffers)
      if (!b.uri.empty() && b.uri.rfind("data:", 0) != 0) note_input(folder + "/" + b.uri);
    for (const tinygltf::Image& im : model_.images)
      if (!im.uri.empty() && im.uri.rfind("data:", 0) != 0) note_input(folder + "/" + im.uri);
    if (model_.asset.version.rfind("2", 0) != 0)
      fail("asset version '" + model_.asset.version + "' is not glTF 2.x");
  }

  // The JSON chunk of a GLB (header: magic, version, length; then the chunk's length and
  // type), as far as the file holds it; tinygltf refuses a malformed header itself.
  void check_glb_json(const std::vector<unsigned char>& bytes) const {
    if (bytes.size() < 20 || std::memcmp(bytes.data(), "glTF", 4) != 0) return;
    uint32_t chunk_length = 0;
    std::memcpy(&chunk_length, bytes.data() + 12, 4);  // little-endian in the file and on x86-64
    const size_t n = std::min<size_t>(chunk_length, bytes.size() - 20);
    check_json_text(reinterpret_cast<const char*>(bytes.data()) + 20, n, path_);
  }

  // tinygltf's file access for URIs: existence only (the reader says what is wrong with a
  // file that exists), paths as given (no expansion), reads checked as every input is; the
  // first failure is kept whole and thrown after tinygltf returns, naming the file.
  struct ExternalFiles {
    std::string gltf_path;
    std::unique_ptr<InputError> failure;
  };
  static bool external_file_exists(const std::string& path, void*) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0;
  }
  static std::string external_path(const std::string& path, void*) { return path; }
  static bool read_external_file(std::vector<unsigned char>* out, std::string* err,
                                 const std::string& path, void* user) {
    auto* files = static_cast<ExternalFiles*>(user);
    // Images go to stb_image through tinygltf as an int length: the PNG/JPEG limit.
    const std::string ext = ascii_lower(path.substr(path.find_last_of('.') + 1));
    const bool image = ext == "png" || ext == "jpg" || ext == "jpeg";
    try {
      *out = read_input_bytes(path, image ? kTextureFileLimit : kModelFileLimit);
      return true;
    } catch (const InputError& e) {
      if (!files->failure)
        files->failure = std::make_unique<InputError>(path, e.reason + " (a URI of " + files->gltf_path + ")");
      if (err) *err = e.reason;
      return false;
    }
  }
  static bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err = "writing is not supported";
    return false;
  }

  // Local transform of a node: its matrix, or T·R·S.
  dmat4 local(const tinygltf::Node& n, int index) const {
    if (n.matrix.size() == 16) {
      dmat4 m;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[size_t(4 * c + r)];
      return m;
    }
    dmat4 m(1.0);
    if (n.translation.size() == 3)
      m = glm::translate(m, dvec3(n.translation[0], n.translation[1], n.translation[2]));
    if (n.rotation.size() == 4) {
      const glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);  // w, x, y, z
      if (!(glm::length(q) > 0.0)) fail("node " + std::to_string(index) + " has a zero rotation quaternion");
      m = m * glm::mat4_cast(glm::normalize(q));
    }
    if (n.scale.size() == 3) m = glm::scale(m, dvec3(n.scale[0], n.scale[1], n.scale[2]));
    return m;
  }

  // Walks the hierarchy under `root` depth first, parents before children and children in
  // order, with an explicit stack: a chain of nodes as deep as the file allows costs heap, not
  // call stack. Every node is reached at most once (visited_), so the walk ends.
  void visit(Scene& s, int root) {
    struct Pending {
      int index;
      dmat4 parent;
    };
    std::vector<Pending> stack{{root, dmat4(1.0)}};
    while (!stack.empty()) {
      const Pending p = stack.back();
      stack.pop_back();
      const int index = p.index;
      if (index < 0 || index >= int(model_.nodes.size()))
        fail("node " + std::to_string(index) + " does not exist");
      if (visited_[size_t(index)])
        fail("node " + std::to_string(index) + " is reached twice (a cycle, or two parents)");
      visited_[size_t(index)] = 1;
      const tinygltf::Node& n = model_.nodes[size_t(index)];
      const dmat4 world = p.parent * local(n, index);
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
          if (!std::isfinite(world[c][r]))
            fail("node " + std::to_string(index) + " has a transform that is not finite");
      if (n.mesh >= 0) add_mesh(s, n.mesh, world);
      if (n.camera >= 0) placed_cameras_.push_back({n.camera, world});
      const auto ext = n.extensions.find("KHR_lights_punctual");
      if (ext != n.extensions.end() && ext->second.Has("light")) {
        const tinygltf::Value& l = ext->second.Get("light");
        if (!l.IsInt() && !l.IsNumber()) fail("node " + std::to_string(index) + ": KHR_lights_punctual.light is not a number");
        placed_lights_.push_back({l.GetNumberAsInt(), world});
      }
      for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.push_back({*c, world});
    }
  }

  // Element bytes of an accessor component type; 0 when unknown.
  static int component_bytes(int type) {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_BYTE:
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
      case TINYGLTF_COMPONENT_TYPE_SHORT:
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
      default: return 0;
    }
  }

  // The bytes of accessor `index` checked against its view and buffer: element e's components
  // start at data + e·stride. `what` names it in errors.
  struct View {
    const unsigned char* data = nullptr;
    size_t stride = 0, count = 0;
    int component_type = 0, components = 0;
    bool normalized = false;
  };
  View view(int index, const std::string& what) const {
    if (index < 0 || index >= int(model_.accessors.size()))
      fail(what + ": accessor " + std::to_string(index) + " does not exist");
    const Accessor& a = model_.accessors[size_t(index)];
    if (a.sparse.isSparse) fail(what + ": sparse accessors are not supported");
    View v;
    v.component_type = a.componentType;
    v.normalized = a.normalized;
    v.count = a.count;
    v.components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    const int cb = component_bytes(a.componentType);
    if (v.components <= 0 || cb == 0) fail(what + ": accessor " + std::to_string(index) + " has an unknown type");
    const size_t elem = size_t(cb) * size_t(v.components);
    if (a.bufferView < 0 || a.bufferView >= int(model_.bufferViews.size()))
      fail(what + ": accessor " + std::to_string(index) + " has no valid bufferView");
    const tinygltf::BufferView& bv = model_.bufferViews[size_t(a.bufferView)];
    if (bv.buffer < 0 || bv.buffer >= int(model_.buffers.size()))
      fail(what + ": bufferView " + std::to_string(a.bufferView) + " names no valid buffer");
    const std::vector<unsigned char>& buf = model_.buffers[size_t(bv.buffer)].data;
    v.stride = bv.byteStride ? bv.byteStride : elem;
    if (v.stride < elem) fail(what + ": byteStride " + std::to_string(bv.byteStride) + " is below the element size");
    // Every element inside the view, the view inside the buffer (64-bit sums of values that
    // the JSON bounds to below 2⁵³; no overflow).
    const uint64_t view_end = uint64_t(bv.byteOffset) + uint64_t(bv.byteLength);
    if (view_end > buf.size())
      fail(what + ": bufferView " + std::to_string(a.bufferView) + " ends at byte " +
           std::to_string(view_end) + " of a " + std::to_string(buf.size()) + "-byte buffer");
    if (v.count > 0) {
      const uint64_t need = uint64_t(a.byteOffset) + uint64_t(v.stride) * (uint64_t(v.count) - 1) + elem;
      if (v.count > (1ull << 32) || need > uint64_t(bv.byteLength))
        fail(what + ": accessor " + std::to_string(index) + " reads past its bufferView (" +
             std::to_string(v.count) + " elements)");
    }
    v.data = buf.data() + bv.byteOffset + a.byteOffset;
    return v;
  }

  static float read_component(const unsigned char* p, int type, bool normalized) {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? float(*p) / 255.0f : float(*p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t u; std::memcpy(&u, p, 2); return normalized ? float(u) / 65535.0f : float(u);
      }
      default: return 0.0f;
    }
  }

  // Float vectors of `n` components (FLOAT, or normalized unsigned byte/short when allowed).
  std::vector<float> floats(int index, int n, bool allow_normalized, const std::string& what) const {
    const View v = view(index, what);
    if (v.components != n) fail(what + ": expected " + std::to_string(n) + " components per element");
    const bool ok = v.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                    (allow_normalized && v.normalized &&
                     (v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                      v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
    if (!ok) fail(what + ": unsupported component type " + std::to_string(v.component_type));
    const int cb = component_bytes(v.component_type);
    std::vector<float> out(v.count * size_t(n));
    for (size_t e = 0; e < v.count; ++e)
      for (int c = 0; c < n; ++c)
        out[e * size_t(n) + size_t(c)] =
            read_component(v.data + e * v.stride + size_t(c * cb), v.component_type, v.normalized);
    return out;
  }

  std::vector<uint32_t> indices(int index, const std::string& what) const {
    const View v = view(index, what);
    if (v.components != 1) fail(what + ": indices must be scalars");
    std::vector<uint32_t> out(v.count);
    for (size_t e = 0; e < v.count; ++e) {
      const unsigned char* p = v.data + e * v.stride;
      switch (v.component_type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[e] = *p; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t u; std::memcpy(&u, p, 2); out[e] = u; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&out[e], p, 4); break;
        default: fail(what + ": indices of component type " + std::to_string(v.component_type));
      }
    }
    return out;
  }

  void add_mesh(Scene& s, int mesh_index, const dmat4& world) {
    if (mesh_index >= int(model_.meshes.size()))
      fail("mesh " + std::to_string(mesh_index) + " does not exist");
    const tinygltf::Mesh& gm = model_.meshes[size_t(mesh_index)];
    const std::string base = gm.name.empty() ? "mesh#" + std::to_string(mesh_index) : gm.name;
    const glm::dmat3 nmat = glm::transpose(glm::inverse(glm::dmat3(world)));
    const bool flip = glm::determinant(glm::dmat3(world)) < 0.0;
    for (size_t pi = 0; pi < gm.primitives.size(); ++pi) {
      const tinygltf::Primitive& p = gm.primitives[pi];
      const std::string name = base + "/" + std::to_string(pi);
      const std::string what = "mesh '" + name + "'";
      if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES)
        fail(what + ": primitive mode " + std::to_string(p.mode) + " (only triangles, mode 4, are supported)");
      const auto pos_it = p.attributes.find("POSITION");
      if (pos_it == p.attributes.end()) fail(what + ": no POSITION attribute");
      Mesh m;
      m.name = name;
      const std::vector<float> pos = floats(pos_it->second, 3, false, what + " POSITION");
      const size_t nv = pos.size() / 3;
      m.positions.resize(nv);
      for (size_t v = 0; v < nv; ++v) {
        const glm::dvec4 w = world * glm::dvec4(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2], 1.0);
        m.positions[v] = vec3(w);
        if (!is_finite(m.positions[v]))
          fail(what + ": vertex " + std::to_string(v) + " is not finite");
      }
      bool normals_ok = false;
      const auto nrm_it = p.attributes.find("NORMAL");
      if (nrm_it != p.attributes.end()) {
        const std::vector<float> nrm = floats(nrm_it->second, 3, false, what + " NORMAL");
        if (nrm.size() != pos.size()) fail(what + ": NORMAL and POSITION counts differ");
        m.normals.resize(nv);
        normals_ok = true;
        for (size_t v = 0; v < nv; ++v) {
          const dvec3 n = nmat * dvec3(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2]);
          const double len = glm::length(n);
          if (!(len > 0.0) || !std::isfinite(len)) normals_ok = false;
          else m.normals[v] = vec3(n / len);
        }
        if (!normals_ok) {
          note(what + ": zero or non-finite normals; recomputed");
          m.normals.clear();
        }
      }
      if (p.indices >= 0) {
        m.indices = indices(p.indices, what + " indices");
      } else {
        m.indices.resize(nv);
        for (size_t v = 0; v < nv; ++v) m.indices[v] = uint32_t(v);
      }
      if (m.indices.size() % 3 != 0)
        fail(what + ": " + std::to_string(m.indices.size()) + " indices is not a multiple of 3");
      for (size_t i = 0; i < m.indices.size(); ++i)
        if (m.indices[i] >= nv)
          fail(what + ": index " + std::to_string(i) + " is " + std::to_string(m.indices[i]) +
               ", past the " + std::to_string(nv) + " vertices");
      if (flip)
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
      if (m.indices.empty()) continue;
      m.material = p.material >= 0 ? material(s, p.material, what) : -1;
      // Texture coordinates of the material's base-colour texture (v flipped to point up).
      const int set = p.material >= 0 ? texcoord_set_[size_t(p.material)] : 0;
      const auto uv_it = p.attributes.find("TEXCOORD_" + std::to_string(set));
      if (uv_it != p.attributes.end()) {
        const std::vector<float> uv = floats(uv_it->second, 2, true, what + " TEXCOORD_" + std::to_string(set));
        if (uv.size() / 2 != nv) fail(what + ": TEXCOORD and POSITION counts differ");
        m.uvs.resize(nv);
        for (size_t v = 0; v < nv; ++v) m.uvs[v] = vec2(uv[2 * v], 1.0f - uv[2 * v + 1]);
      }
      if (m.material >= 0 && s.materials[size_t(m.material)].alpha_texture >= 0 && m.uvs.empty()) {
        if (constant_alpha_[size_t(p.material)])
          m.uvs.assign(nv, vec2(0.0f));  // a 1×1 alpha texture: every coordinate reads it
        else
          fail(what + ": an alpha-masked material needs TEXCOORD_" + std::to_string(set));
      }
      if (!normals_ok) compute_vertex_normals(m);
      s.meshes.push_back(std::move(m));
    }
  }

  int default_material(Scene& s) {
    if (default_material_ < 0) {
      Material m;
      m.name = "default";
      s.materials.push_back(m);
      default_material_ = int(s.materials.size()) - 1;
    }
    return default_material_;
  }

  // Scene material of glTF material `index` (made on first use).
  int material(Scene& s, int index, const std::string& what) {
    if (index >= int(model_.materials.size()))
      fail(what + ": material " + std::to_string(index) + " does not exist");
    if (material_map_.empty()) {
      material_map_.assign(model_.materials.size(), -1);
      texcoord_set_.assign(model_.materials.size(), 0);
      constant_alpha_.assign(model_.materials.size(), 0);
    }
    int& slot = material_map_[size_t(index)];
    if (slot >= 0) return slot;
    const tinygltf::Material& gm = model_.materials[size_t(index)];
    const std::string mwhat = "material " + std::to_string(index) + (gm.name.empty() ? "" : " '" + gm.name + "'");
    Material m;
    m.name = gm.name.empty() ? "material#" + std::to_string(index) : gm.name;
    const std::vector<double>& f = gm.pbrMetallicRoughness.baseColorFactor;
    vec4 factor(1.0f);
    if (f.size() == 4) factor = vec4(float(f[0]), float(f[1]), float(f[2]), float(f[3]));
    if (!is_finite(vec3(factor)) || !std::isfinite(factor.w))
      fail(mwhat + ": baseColorFactor is not finite");
    m.albedo = vec3(factor);
    const tinygltf::TextureInfo& ti = gm.pbrMetallicRoughness.baseColorTexture;
    Texture8 tex;
    bool has_tex = false;
    if (ti.index >= 0) {
      if (ti.index >= int(model_.textures.size())) fail(mwhat + ": texture " + std::to_string(ti.index) + " does not exist");
      const int src = model_.textures[size_t(ti.index)].source;
      if (src < 0 || src >= int(model_.images.size()) || model_.images[size_t(src)].image.empty())
        fail(mwhat + ": texture " + std::to_string(ti.index) + " has no loaded image");
      const tinygltf::Image& im = model_.images[size_t(src)];
      if (im.component != 4 || im.bits != 8 ||
          im.image.size() != size_t(im.width) * size_t(im.height) * 4)
        fail(mwhat + ": image " + std::to_string(src) + " is not 8-bit RGBA after decoding");
      tex.width = im.width;
      tex.height = im.height;
      tex.file_channels = 4;
      tex.rgba = im.image;
      has_tex = true;
      texcoord_set_[size_t(index)] = ti.texCoord;
      // Albedo: the factor times the texture's mean linear colour.
      double sum[3] = {0, 0, 0};
      const size_t n = size_t(tex.width) * size_t(tex.height);
      for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) sum[c] += srgb8_to_linear(tex.rgba[4 * i + size_t(c)]);
      for (int c = 0; c < 3; ++c) m.albedo[c] *= float(sum[c] / double(n));
      m.color_factor = vec3(factor);
      s.textures.push_back(texture_to_linear_rgba(tex));
      m.color_texture = int(s.textures.size()) - 1;
    }
    std::string mode = gm.alphaMode.empty() ? "OPAQUE" : gm.alphaMode;
    float cutoff = float(gm.alphaCutoff);
    if (mode == "BLEND") {
      note(mwhat + ": alphaMode BLEND is taken as MASK at cutoff 0.5 (shadowlab has no translucency)");
      mode = "MASK";
      cutoff = 0.5f;
    }
    if (mode == "MASK") {
      if (!(cutoff >= 0.0f && cutoff <= 1.0f)) fail(mwhat + ": alphaCutoff is outside [0, 1]");
      m.alpha_cutoff = cutoff;
      if (!has_tex) {
        tex.width = tex.height = 1;
        tex.file_channels = 4;
        tex.rgba = {255, 255, 255, 255};
        constant_alpha_[size_t(index)] = 1;
      }
      ImageF rgba = texture_to_linear_rgba(tex);
      // Alpha × baseColorFactor.a, in the plane of channel 3.
      const size_t n = rgba.pixel_count();
      for (size_t i = 0; i < n; ++i) rgba.data[3 * n + i] *= factor.w;
      s.textures.push_back(std::move(rgba));
      m.alpha_texture = int(s.textures.size()) - 1;
    } else if (mode != "OPAQUE") {
      fail(mwhat + ": unknown alphaMode '" + mode + "'");
    }
    s.materials.push_back(m);
    slot = int(s.materials.size()) - 1;
    return slot;
  }

  void pick_light(Scene& s, const GltfChoice& choice, GltfContents* contents) {
    contents->lights = int(placed_lights_.size());
    if (placed_lights_.empty()) {
      if (choice.light != 0) fail("--light " + std::to_string(choice.light) + ": the file places no light");
      return;
    }
    if (choice.light < 0 || choice.light >= int(placed_lights_.size()))
      throw InputError("--light", std::to_string(choice.light) + " is not a light of " + path_ + " (it places " +
                                      std::to_string(placed_lights_.size()) + ")");
    const auto& [li, world] = placed_lights_[size_t(choice.light)];
    if (li < 0 || li >= int(model_.lights.size())) fail("light " + std::to_string(li) + " does not exist");
    const tinygltf::Light& l = model_.lights[size_t(li)];
    const vec3 pos = vec3(world * glm::dvec4(0, 0, 0, 1));
    const std::string name = "light " + std::to_string(choice.light) + (l.name.empty() ? "" : " '" + l.name + "'");
    if (l.type == "point") {
      s.light.position = pos;
      s.light.radius = 0.0f;
      if (l.extras.Has("radius")) {
        const tinygltf::Value& r = l.extras.Get("radius");
        if (!r.IsNumber() && !r.IsInt()) fail(name + ": extras.radius is not a number");
        const double rv = r.GetNumberAsDouble();
        if (!(rv >= 0.0 && rv < 1e6)) fail(name + ": extras.radius " + std::to_string(rv) + " is outside [0, 1e6) m");
        s.light.radius = float(rv);
      }
      // KHR_lights_punctual: range > 0, or absent (tinygltf's 0) for no limit.
      if (l.range < 0.0 || std::isnan(l.range))
        fail(name + ": range " + fmt::format("{}", l.range) + " is not positive (give range > 0, or none for no limit)");
      if (l.range > 0.0) {
        if (!(l.range < 1e9)) fail(name + ": range is too large");
        s.light.far = float(l.range);
        s.light.near = std::min(s.light.near, 1e-3f * s.light.far);
      } else {
        far_from_bounds_ = true;
      }
      contents->light_text = name + " (point, radius " + fmt::format("{}", s.light.radius) + " m)";
    } else if (l.type == "spot") {
      Projector p;
      p.posed = true;
      p.position = pos;
      p.direction = vec3(glm::dmat3(world) * dvec3(0, 0, -1));
      p.up = vec3(glm::dmat3(world) * dvec3(0, 1, 0));
      const double outer = l.spot.outerConeAngle;
      if (!(outer > 0.0 && outer < 1.48)) fail(name + ": outerConeAngle must be in (0, 1.48) rad");
      p.fov_y_deg = float(2.0 * outer * 180.0 / 3.14159265358979323846);
      p.aspect = 1.0f;
      p.slide = make_slide("spot", path_);
      s.light.position = pos;
      set_projector(s, std::move(p), path_);
      contents->light_text = name + " (spot, made the slide projector with the spot slide)";
    } else {
      fail(name + ": a " + l.type + " light is not supported (point and spot are)");
    }
    contents->light_used = true;
  }

  void pick_camera(Scene& s, const GltfChoice& choice, GltfContents* contents) {
    contents->cameras = int(placed_cameras_.size());
    if (placed_cameras_.empty()) {
      if (choice.camera != 0) fail("--camera " + std::to_string(choice.camera) + ": the file places no camera");
      return;
    }
    if (choice.camera < 0 || choice.camera >= int(placed_cameras_.size()))
      throw InputError("--camera", std::to_string(choice.camera) + " is not a camera of " + path_ +
                                       " (it places " + std::to_string(placed_cameras_.size()) + ")");
    const auto& [ci, world] = placed_cameras_[size_t(choice.camera)];
    if (ci < 0 || ci >= int(model_.cameras.size())) fail("camera " + std::to_string(ci) + " does not exist");
    const tinygltf::Camera& c = model_.cameras[size_t(ci)];
    const std::string name = "camera " + std::to_string(choice.camera) + (c.name.empty() ? "" : " '" + c.name + "'");
    if (c.type != "perspective") fail(name + ": a " + c.type + " camera is not supported (perspective is)");
    const tinygltf::PerspectiveCamera& pc = c.perspective;
    if (!(pc.yfov > 0.0 && pc.yfov < 3.1)) fail(name + ": yfov must be in (0, 3.1) rad");
    Camera& cam = s.camera;
    cam.eye = vec3(world * glm::dvec4(0, 0, 0, 1));
    cam.target = cam.eye + vec3(glm::normalize(glm::dmat3(world) * dvec3(0, 0, -1)));
    cam.up = vec3(glm::normalize(glm::dmat3(world) * dvec3(0, 1, 0)));
    cam.fov_y_deg = float(pc.yfov * 180.0 / 3.14159265358979323846);
    if (pc.znear > 0.0) cam.near = float(pc.znear);
    if (pc.zfar > pc.znear) cam.far = float(pc.zfar);
    if (pc.aspectRatio > 0.0) {
      if (!(pc.aspectRatio < 20.0)) fail(name + ": aspectRatio must be below 20");
      cam.height = 768;
      cam.width = std::max(1, int(std::lround(768.0 * pc.aspectRatio)));
    }
    contents->camera_text = name;
    contents->camera_used = true;
  }

 public:
  bool far_from_bounds_ = false;  // a point light without range: its far comes from the bounds

 private:
  std::string path_;
  std::vector<std::string>* notes_;
  Model model_;
  std::vector<uint8_t> visited_;
  std::vector<std::pair<int, dmat4>> placed_lights_, placed_cameras_;
  std::vector<int> material_map_, texcoord_set_;
  std::vector<uint8_t> constant_alpha_;
  int default_material_ = -1;
};

}  // namespace

bool is_gltf_path(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos) return false;
  const std::string ext = ascii_lower(path.substr(dot + 1));
  return ext == "gltf" || ext == "glb";
}

Scene load_gltf_scene(const std::string& path, const GltfChoice& choice, GltfContents* contents,
                      std::vector<std::string>* notes) {
  GltfContents local;
  Loader loader(path, notes);
  Scene s = loader.load(choice, contents ? contents : &local);
  return s;
}

Scene make_gltf_scene(const std::string& path, const GltfChoice& choice,
                      std::vector<std::string>* notes) {
  GltfContents c;
  Loader loader(path, notes);
  Scene s = loader.load(choice, &c);
  auto say = [&](const std::string& text) {
    if (notes) notes->push_back(text);
    else hold_note("note: " + path + ": " + text);
  };
  const vec3 light_pos = s.light.position;
  const float radius = s.light.radius;
  frame_from_bounds(s, !c.camera_used, !c.light_used, path);
  if (c.light_used && !s.projector.enabled && loader.far_from_bounds_) {
    // A point light without range: far reaches the farthest corner of the bounds.
    s.light.position = light_pos;
    s.light.radius = radius;
    s.light.far = std::max(1e-3f, 1.02f * farthest_corner_distance(scene_bounds(s), light_pos));
    s.light.near = std::min(s.light.near, 1e-3f * s.light.far);
  }
  say(c.light_used ? "using " + c.light_text + " of " + std::to_string(c.lights)
                   : "no light in the file: framed from the bounds (as for OBJ)");
  say(c.camera_used ? "using " + c.camera_text + " of " + std::to_string(c.cameras)
                    : "no camera in the file: framed from the bounds (as for OBJ)");
  validate_scene(s, path);
  return s;
}

}  // namespace shadowlab
