#include "experiments/cli.h"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/obj_loader.h"
#include "core/parallel.h"
#include "core/parse_number.h"
#include "core/scene_library.h"
#include "techniques/technique.h"

namespace shadowlab {
namespace {

double parse_double(const std::string& flag, const std::string& s) {
  double v = 0.0;
  if (!shadowlab::parse_double(s, v)) throw InputError(flag, "expected a number, got '" + s + "'");
  return v;
}

long parse_long(const std::string& flag, const std::string& s) {
  long v = 0;
  if (!shadowlab::parse_long(s, v)) throw InputError(flag, "expected an integer, got '" + s + "'");
  return v;
}

}  // namespace

std::vector<std::string> split(const std::string& s, char sep) {
  // Every item, empty ones included ("1,,2" and "1,2," have an empty item), so that callers
  // reject them instead of silently dropping them.
  std::vector<std::string> out(1);
  for (char c : s) {
    if (c == sep)
      out.emplace_back();
    else
      out.back() += c;
  }
  return out;
}

std::string ParsedArgs::get(const std::string& flag, const std::string& fallback) const {
  const auto it = values.find(flag);
  return it == values.end() ? fallback : it->second;
}

int ParsedArgs::get_int(const std::string& flag, int fallback, int lo, int hi) const {
  if (!has(flag)) return fallback;
  const long v = parse_long(flag, get(flag, ""));
  if (v < lo || v > hi)
    throw InputError(flag, get(flag, "") + " is outside [" + number_text(lo) + ", " +
                               number_text(hi) + "]");
  return int(v);
}

double ParsedArgs::get_double(const std::string& flag, double fallback, double lo,
                              double hi) const {
  if (!has(flag)) return fallback;
  const double v = parse_double(flag, get(flag, ""));
  if (v < lo || v > hi)
    throw InputError(flag, get(flag, "") + " is outside [" + number_text(lo) + ", " +
                               number_text(hi) + "]");
  return v;
}

std::vector<int> ParsedArgs::get_int_list(const std::string& flag, const std::vector<int>& fallback,
                                          int lo, int hi) const {
  if (!has(flag)) return fallback;
  std::vector<int> out;
  for (const std::string& item : split(get(flag, ""), ',')) {
    const long v = parse_long(flag, item);
    if (v < lo || v > hi)
      throw InputError(flag, item + " is outside [" + number_text(lo) + ", " +
                                 number_text(hi) + "]");
    out.push_back(int(v));
  }
  if (out.empty()) throw InputError(flag, "expected a comma-separated list of integers");
  return out;
}

vec3 ParsedArgs::get_vec3(const std::string& flag, const vec3& fallback) const {
  if (!has(flag)) return fallback;
  const std::vector<std::string> parts = split(get(flag, ""), ',');
  if (parts.size() != 3) throw InputError(flag, "expected x,y,z, got '" + get(flag, "") + "'");
  return vec3(float(parse_double(flag, parts[0])), float(parse_double(flag, parts[1])),
              float(parse_double(flag, parts[2])));
}

std::vector<FlagDef> common_flags() {
  return {
      {"--scene", "S", "built-in scene name (default, plane, room100k, room1m, bunny, foliage) or an .obj file (default: default)"},
      {"--width", "W", "image width in pixels (default: the scene's camera, 1024)"},
      {"--height", "H", "image height in pixels (default: the scene's camera, 768)"},
      {"--threads", "N", "worker threads (default: $SHADOWLAB_THREADS or all cores)"},
      {"--light-radius", "R", "sphere-light radius in metres; 0 = hard point light (default: the scene's)"},
      {"--light-pos", "X,Y,Z", "light position, metres (default: the scene's)"},
      {"--eye", "X,Y,Z", "camera position, metres (default: the scene's)"},
      {"--target", "X,Y,Z", "camera target, metres (default: the scene's)"},
      {"--fov", "DEG", "vertical field of view in degrees (default: the scene's)"},
      {"--alpha-cutoff", "C", "alpha-test cutoff of every alpha-textured material, [0, 1] (default: the material's, 0.5)"},
      {"--no-alpha", "", "ignore alpha textures: every material opaque (to measure the alpha path's cost)"},
      {"--slide", "SLIDE", "make the light a slide projector casting SLIDE: spot, grid:amp=A,freq=F, or a .png/.exr file"},
      {"--projector-pos", "X,Y,Z", "projector position, metres (default: the scene's pose, else the light)"},
      {"--projector-target", "X,Y,Z", "point the projector aims at (default: the scene's pose, else the camera target)"},
      {"--projector-fov", "DEG", "projector vertical field of view (default: the scene's pose, else 60)"},
      {"--projector-aspect", "A", "projector slide width / height (default 1)"},
      {"--max-memory", "GB", "refuse runs estimated to need more memory (default: what the machine has available)"},
      {"--out", "DIR", "output folder (default out/EXPERIMENT, e.g. out/render)"},
      {"--help", "", "print this help (with the technique registry)"},
      {"--list-techniques", "", "print every technique with its keys and defaults, then exit"},
      {"--version", "", "print the program, shadowlab's commit and the compiler, then exit"},
  };
}

void mark_unused(std::vector<FlagDef>& defs, const std::vector<std::string>& names,
                 const std::string& reason) {
  for (const std::string& n : names) {
    bool found = false;
    for (FlagDef& d : defs)
      if (d.name == n) {
        d.unused = reason;
        found = true;
      }
    SL_CHECK(found);
  }
}

std::vector<std::string> common_scene_flags() {
  std::vector<std::string> names;
  for (const FlagDef& d : common_flags())
    if (d.name != "--threads" && d.name != "--help" && d.name != "--list-techniques" &&
        d.name != "--version")
      names.push_back(d.name);
  return names;
}

ParsedArgs parse_args(int argc, char** argv, const std::vector<FlagDef>& defs,
                      size_t max_positional) {
  ParsedArgs args;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--", 0) != 0 || a == "--") {
      if (args.positional.size() >= max_positional)
        throw InputError(a, "unexpected argument (see --help)");
      args.positional.push_back(a);
      continue;
    }
    std::string value;
    bool inline_value = false;
    if (const size_t eq = a.find('='); eq != std::string::npos) {
      value = a.substr(eq + 1);
      a = a.substr(0, eq);
      inline_value = true;
    }
    const FlagDef* def = nullptr;
    for (const FlagDef& d : defs)
      if (d.name == a) def = &d;
    if (!def) throw InputError(a, "unknown flag (see --help)");
    if (!def->unused.empty()) throw InputError(a, "is not used by this experiment: " + def->unused);
    if (def->value.empty()) {
      if (inline_value) throw InputError(a, "takes no value");
      args.values.insert_or_assign(a, std::string(1, '1'));  // (not = "1": GCC 12 -Wrestrict false positive)
      continue;
    }
    if (!inline_value) {
      if (i + 1 >= argc) throw InputError(a, "expects a value " + def->value);
      value = argv[++i];
    }
    if (args.values.count(a)) throw InputError(a, "given twice");
    args.values[a] = value;
  }
  return args;
}

std::string usage_text(const std::string& synopsis, const std::vector<FlagDef>& defs) {
  std::string s = "usage: " + synopsis + "\n";
  // Unused common flags grouped by reason, after the flags in use.
  std::vector<std::pair<std::string, std::string>> unused;  // reason, flags
  for (const FlagDef& d : defs) {
    if (!d.unused.empty()) {
      auto it = std::find_if(unused.begin(), unused.end(),
                             [&](const auto& u) { return u.first == d.unused; });
      if (it == unused.end())
        unused.emplace_back(d.unused, d.name);
      else
        it->second += " " + d.name;
      continue;
    }
    std::string left = "  " + d.name + (d.value.empty() ? "" : " " + d.value);
    if (left.size() < 26) left.resize(26, ' ');
    s += left + " " + d.help + "\n";
  }
  for (const auto& [reason, flags] : unused)
    s += "common flags not used here (an error if given; " + reason + "):\n  " + flags + "\n";
  s += "techniques (a layout letter c/t/p + a filter sm/vsm/esm; spec NAME:key=value,...):\n";
  s += technique_list_text();
  return s;
}

void apply_projector_flags(const ParsedArgs& args, Scene& scene) {
  const char* projector_flags[] = {"--projector-pos", "--projector-target", "--projector-fov",
                                   "--projector-aspect"};
  if (!args.has("--slide")) {
    for (const char* f : projector_flags)
      if (args.has(f)) throw InputError(f, "needs --slide (the projector's slide)");
    return;
  }
  if (args.has("--light-radius") && scene.light.radius > 0.0f)
    throw InputError("--light-radius", "a slide projector is a point source; drop --light-radius or --slide");
  Projector p = scene.projector;
  vec3 target = scene.camera.target;
  if (p.posed) {
    target = p.position + p.direction;
  } else {
    p.position = scene.light.position;
    p.fov_y_deg = 60.0f;
  }
  if (args.has("--light-pos") && !args.has("--projector-pos")) p.position = scene.light.position;
  p.position = args.get_vec3("--projector-pos", p.position);
  target = args.get_vec3("--projector-target", target);
  p.direction = target - p.position;
  if (!(glm::length(p.direction) > 0.0f))
    throw InputError(args.has("--projector-target") ? "--projector-target" : "--projector-pos",
                     "the projector's target coincides with its position");
  // An aim straight up or down gets a horizontal up vector instead of +y.
  if (glm::length(glm::cross(glm::normalize(p.direction), p.up)) < 1e-3f) p.up = vec3(0.0f, 0.0f, -1.0f);
  p.fov_y_deg = float(args.get_double("--projector-fov", p.fov_y_deg, 0.1, 169.0));
  p.aspect = float(args.get_double("--projector-aspect", p.aspect, 0.05, 20.0));
  p.slide = make_slide(args.get("--slide", ""), "--slide");
  set_projector(scene, std::move(p), "--slide");
}

Scene scene_from_args(const ParsedArgs& args) {
  if (args.has("--threads")) set_thread_count(args.get_int("--threads", 1, 1, 1024));
  const std::string name = args.get("--scene", "default");
  const bool is_file = name.find('/') != std::string::npos || name.find('.') != std::string::npos;
  Scene scene = is_file ? make_obj_scene(name) : make_builtin_scene(name);
  Camera& cam = scene.camera;
  cam.width = args.get_int("--width", cam.width, 1, kMaxImageSide);
  cam.height = args.get_int("--height", cam.height, 1, kMaxImageSide);
  cam.eye = args.get_vec3("--eye", cam.eye);
  cam.target = args.get_vec3("--target", cam.target);
  cam.fov_y_deg = float(args.get_double("--fov", cam.fov_y_deg, 1.0, 170.0));
  scene.light.position = args.get_vec3("--light-pos", scene.light.position);
  scene.light.radius = float(args.get_double("--light-radius", scene.light.radius, 0.0, 1e4));
  if (args.has("--alpha-cutoff") && args.has("--no-alpha"))
    throw InputError("--alpha-cutoff", "conflicts with --no-alpha");
  const float cutoff = float(args.get_double("--alpha-cutoff", 0.5, 0.0, 1.0));
  for (Material& m : scene.materials) {
    if (args.has("--no-alpha")) m.alpha_texture = -1;
    if (args.has("--alpha-cutoff")) m.alpha_cutoff = cutoff;
  }
  apply_projector_flags(args, scene);
  validate_scene(scene, is_file ? name : "--scene " + name);
  return scene;
}

int run_main(int argc, char** argv, const std::function<int(int, char**)>& body) {
  const std::string prog = std::filesystem::path(argv[0]).filename().string();
  // Keep freed large blocks in the heap instead of returning them to the kernel: on the VMs
  // we measure on, first-touch page faults of a 1024×768 GBuffer cost ~200 ms, ten times the
  // pass itself, and would otherwise be paid again by every timing repeat.
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  try {
    for (int i = 1; i < argc; ++i) {
      if (std::string(argv[i]) == "--list-techniques") {
        std::printf("%s", technique_list_text().c_str());
        return 0;
      }
      if (std::string(argv[i]) == "--version") {
        // The commit is the one the build was configured from (a later commit needs a cmake
        // re-run to show).
        std::printf("%s (shadowlab) commit %s, compiler %s\n", prog.c_str(), SHADOWLAB_COMMIT,
                    __VERSION__);
        return 0;
      }
    }
    return body(argc, argv);
  } catch (const InputError& e) {
    // One prefix: an error whose source is the program itself ("metric") is not named twice.
    if (e.where == prog)
      std::fprintf(stderr, "%s: %s\n", prog.c_str(), e.reason.c_str());
    else
      std::fprintf(stderr, "%s: %s\n", prog.c_str(), e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", prog.c_str(), e.what());
    return 1;
  }
}

uint64_t max_memory_bytes(const ParsedArgs& args) {
  if (!args.has("--max-memory")) return 0;
  return uint64_t(args.get_double("--max-memory", 0.0, 1e-6, 1e6) * 1e9);
}

void make_output_dir(const std::string& dir, const std::string& flag) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError(flag, "cannot create folder '" + dir + "': " + ec.message());
}

bool stderr_is_terminal() { return isatty(2) != 0; }

}  // namespace shadowlab
