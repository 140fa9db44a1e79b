#include "scenes/scene_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/light_fit.h"
#include "core/text.h"
#include "core/error.h"
#include "core/json_file.h"
#include "core/notes.h"
#include "core/run_inputs.h"
#include "scenes/mesh_builders.h"
#include "scenes/obj_loader.h"
#include "scenes/scene_library.h"
#include "core/slide.h"
#include "scenes/gltf_loader.h"
#include "scenes/scene_merge.h"

namespace shadowlab {
namespace {

using nlohmann::json;

// Reads the keys of one JSON object with their key path for errors ("camera.fov_deg").
class Reader {
 public:
  Reader(const std::string& file, const json& obj, std::string prefix)
      : file_(file), obj_(obj), prefix_(std::move(prefix)) {
    if (!obj_.is_object()) fail(prefix_.empty() ? "the file" : prefix_, "expected an object");
  }

  [[noreturn]] void fail(const std::string& key, const std::string& reason) const {
    throw InputError(file_, key + ": " + reason);
  }
  std::string path(const std::string& key) const { return prefix_.empty() ? key : prefix_ + "." + key; }

  // Every key of the object must be one of `known`.
  void only(const std::vector<std::string>& known) const {
    for (auto it = obj_.begin(); it != obj_.end(); ++it)
      if (std::find(known.begin(), known.end(), it.key()) == known.end()) {
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
        fail(path(it.key()), "unknown key (known: " + list + ")");
      }
  }
  bool has(const std::string& key) const { return obj_.contains(key); }
  const json& at(const std::string& key) const { return obj_.at(key); }

  double number(const std::string& key, double lo, double hi) const {
    const json& v = obj_.at(key);
    if (!v.is_number()) fail(path(key), "expected a number");
    const double d = v.get<double>();
    if (!(std::isfinite(d) && d >= lo && d <= hi))
      fail(path(key), "is " + v.dump() + ", outside [" + fmt_num(lo) + ", " + fmt_num(hi) + "]");
    return d;
  }
  int integer(const std::string& key, int lo, int hi) const {
    const json& v = obj_.at(key);
    if (!v.is_number_integer()) fail(path(key), "expected an integer");
    const long long i = v.get<long long>();
    if (i < lo || i > hi) fail(path(key), "is " + v.dump() + ", outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return int(i);
  }
  vec3 vector3(const std::string& key, double limit = 1e7) const {
    const json& v = obj_.at(key);
    if (!v.is_array() || v.size() != 3) fail(path(key), "expected [x, y, z]");
    vec3 out;
    for (int k = 0; k < 3; ++k) {
      if (!v[size_t(k)].is_number()) fail(path(key), "expected [x, y, z] of numbers");
      const double d = v[size_t(k)].get<double>();
      if (!(std::isfinite(d) && std::fabs(d) <= limit))
        fail(path(key), "component " + std::to_string(k) + " is " + v[size_t(k)].dump() + ", outside [-" + fmt_num(limit) + ", " + fmt_num(limit) + "]");
      out[k] = float(d);
    }
    return out;
  }
  std::string text(const std::string& key) const {
    const json& v = obj_.at(key);
    if (!v.is_string()) fail(path(key), "expected a string");
    return v.get<std::string>();
  }

 private:
  static std::string fmt_num(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }
  std::string file_;
  const json& obj_;
  std::string prefix_;
};

// Maps a model's geometry by `m`: positions, normals by the inverse transpose, and the winding
// reversed under a mirroring transform.
void transform_model(Scene& model, const mat4& m) {
  const glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(m)));
  const bool flip = glm::determinant(glm::mat3(m)) < 0.0f;
  for (Mesh& mesh : model.meshes) {
    for (vec3& p : mesh.positions) p = vec3(m * glm::vec4(p, 1.0f));
    for (vec3& n : mesh.normals) {
      const vec3 t = nm * n;
      const float len = glm::length(t);
      n = len > 0.0f ? t / len : n;
    }
    if (flip)
      for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  }
}

}  // namespace

bool is_scene_file_path(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  return dot != std::string::npos && ascii_lower(path.substr(dot + 1)) == "json";
}

Scene load_scene_file(const std::string& path, std::vector<std::string>* notes) {
  auto note = [&](const std::string& text) {
    if (notes) notes->push_back(text);
    else hold_note("note: " + path + ": " + text);
  };
  note_input(path);
  const json doc = read_json_file(path, kSceneFileLimit);
  const Reader top(path, doc, "");
  top.only({"base", "models", "camera", "light", "projector", "ground"});
  if (!top.has("base") && !top.has("models")) top.fail("the file", "names neither a base scene nor models");
  if (top.has("light") && top.has("projector")) top.fail("projector", "conflicts with light (the projector is the light)");

  Scene s;
  const bool base = top.has("base");
  if (base) {
    const std::string name = top.text("base");
    try {
      s = make_builtin_scene(name);
    } catch (const InputError& e) {
      top.fail("base", e.reason);
    }
  } else {
    const size_t slash = path.find_last_of('/');
    const std::string stem = slash == std::string::npos ? path : path.substr(slash + 1);
    s.name = stem.substr(0, stem.find_last_of('.'));
  }
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (top.has("models")) {
    const json& models = top.at("models");
    if (!models.is_array() || models.empty()) top.fail("models", "expected a non-empty array");
    for (size_t i = 0; i < models.size(); ++i) {
      const Reader m(path, models[i], "models[" + std::to_string(i) + "]");
      m.only({"file", "scale", "rotate_deg", "translate"});
      if (!m.has("file")) m.fail(m.path("file"), "is required");
      const std::string rel = m.text("file");
      const std::string file = (folder / rel).string();
      vec3 scale(1.0f);
      if (m.has("scale")) {
        if (m.at("scale").is_array()) scale = m.vector3("scale", 1e6);
        else scale = vec3(float(m.number("scale", -1e6, 1e6)));
        if (scale.x * scale.y * scale.z == 0.0f) m.fail(m.path("scale"), "has a zero component");
      }
      const vec3 rot = m.has("rotate_deg") ? m.vector3("rotate_deg", 1e4) : vec3(0.0f);
      const vec3 tr = m.has("translate") ? m.vector3("translate") : vec3(0.0f);
      mat4 xf = glm::translate(mat4(1.0f), tr);
      xf = glm::rotate(xf, glm::radians(rot.z), vec3(0, 0, 1));
      xf = glm::rotate(xf, glm::radians(rot.y), vec3(0, 1, 0));
      xf = glm::rotate(xf, glm::radians(rot.x), vec3(1, 0, 0));
      xf = glm::scale(xf, scale);
      Scene model;
      if (is_gltf_path(file)) {
        GltfContents c;
        model = load_gltf_scene(file, {}, &c, notes);
        if (c.lights || c.cameras)
          note(m.path("file") + ": the model's own lights and cameras are not used in a scene file");
      } else {
        model = load_obj_scene(file, notes);
      }
      transform_model(model, xf);
      append_scene(s, std::move(model));
    }
  }

  // Camera: the base's, or framed; then the file's keys.
  const bool camera_given = top.has("camera");
  bool frame_camera = !base && !(camera_given && top.at("camera").contains("eye") && top.at("camera").contains("target"));
  bool frame_light = !base && !(top.has("light") && top.at("light").contains("position")) && !top.has("projector");
  frame_from_bounds(s, frame_camera, frame_light, path);
  if (frame_camera) note("no camera eye and target in the file: framed from the bounds (as for OBJ)");
  if (frame_light) note("no light position in the file: framed from the bounds (as for OBJ)");
  if (camera_given) {
    const Reader c(path, top.at("camera"), "camera");
    c.only({"eye", "target", "up", "fov_deg", "width", "height", "near", "far"});
    Camera& cam = s.camera;
    if (c.has("eye")) cam.eye = c.vector3("eye");
    if (c.has("target")) cam.target = c.vector3("target");
    if (c.has("up")) cam.up = c.vector3("up");
    if (c.has("fov_deg")) cam.fov_y_deg = float(c.number("fov_deg", 1.0, 170.0));
    if (c.has("width")) cam.width = c.integer("width", 1, kMaxImageSide);
    if (c.has("height")) cam.height = c.integer("height", 1, kMaxImageSide);
    if (c.has("near")) cam.near = float(c.number("near", 1e-6, 1e6));
    if (c.has("far")) cam.far = float(c.number("far", 1e-6, 1e7));
  }
  bool far_given = false;
  if (top.has("light")) {
    const Reader l(path, top.at("light"), "light");
    l.only({"position", "radius", "near", "far"});
    if (l.has("position")) s.light.position = l.vector3("position");
    if (l.has("radius")) s.light.radius = float(l.number("radius", 0.0, 1e4));
    if (l.has("near")) s.light.near = float(l.number("near", 1e-6, 1e6));
    if (l.has("far")) {
      s.light.far = float(l.number("far", 1e-6, 1e7));
      far_given = true;
    }
  }
  // The ground before the far distance and the projector: both reach it.
  if (top.has("ground")) {
    const Reader g(path, top.at("ground"), "ground");
    g.only({"y", "size"});
    const Bounds b = scene_bounds(s);
    const float y = g.has("y") ? float(g.number("y", -1e7, 1e7)) : b.lo.y;
    const float side = g.has("size") ? float(g.number("size", 1e-3, 1e6))
                                     : std::max(2.0f * glm::length(b.extent()), 1e-3f);
    const vec3 c = b.centre();
    add_grid_quad(new_mesh(s, "ground", vec3(0.7f)), vec3(c.x - 0.5f * side, y, c.z - 0.5f * side),
                  vec3(0, 0, side), vec3(side, 0, 0), 8, 8);
  }
  if (!far_given && !top.has("projector")) {
    cover_scene_with_light_range(s);
  }
  if (top.has("projector")) {
    const Reader p(path, top.at("projector"), "projector");
    p.only({"position", "target", "up", "fov_deg", "aspect", "slide"});
    if (!p.has("position") || !p.has("target")) p.fail("projector", "needs position and target");
    Projector pr;
    pr.posed = true;
    pr.position = p.vector3("position");
    pr.direction = p.vector3("target") - pr.position;
    if (!(glm::length(pr.direction) > 0.0f)) p.fail("projector.target", "coincides with the position");
    if (p.has("up")) pr.up = p.vector3("up");
    if (p.has("fov_deg")) pr.fov_y_deg = float(p.number("fov_deg", 0.1, 169.0));
    if (p.has("aspect")) pr.aspect = float(p.number("aspect", 0.05, 20.0));
    const std::string slide = p.has("slide") ? p.text("slide") : "spot";
    pr.slide = make_slide(slide, path + ": projector.slide");
    set_projector(s, std::move(pr), path);
  }
  validate_scene(s, path);
  return s;
}

}  // namespace shadowlab
