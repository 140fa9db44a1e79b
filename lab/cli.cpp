#include "lab/cli.h"
#include "lab/environment.h"
#include "lab/param_space.h"
#include "lab/provenance.h"
#include "lab/view_check.h"

#include <malloc.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "core/error.h"
#include "core/notes.h"
#include "core/light_fit.h"
#include "scenes/obj_loader.h"
#include "core/parallel.h"
#include "core/parse_number.h"
#include "core/repeats.h"
#include "core/temp_cleanup.h"
#include "scenes/gltf_loader.h"
#include "scenes/scene_file.h"
#include "scenes/scene_library.h"
#include "techniques/registry/technique.h"

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

template <class T>
T in_range(const std::string& flag, const std::string& text, T v, T lo, T hi) {
  if (v < lo || v > hi)
    throw InputError(flag, text + " is outside [" + number_text(double(lo)) + ", " +
                               number_text(double(hi)) + "]");
  return v;
}

int int_in(const std::string& flag, const std::string& s, int lo, int hi) {
  return int(in_range<long>(flag, s, parse_long(flag, s), lo, hi));
}

double double_in(const std::string& flag, const std::string& s, double lo, double hi) {
  return in_range(flag, s, parse_double(flag, s), lo, hi);
}

// A switch: an option that takes no value.
bool is_switch(const CLI::Option* o) { return o->get_expected_max() == 0; }

[[noreturn]] void throw_unused(const std::string& flag, const std::string& reason) {
  throw InputError(flag, "is not used by this experiment: " + reason);
}

// Registers `flag` taking one value; `set` receives it. CLI11 collects every occurrence
// (TakeAll) so that a second one is an error here instead of silently winning.
void add_valued(CommandLine& cl, const std::string& flag, const std::string& placeholder,
                const std::string& help, std::function<void(const std::string&)> set) {
  const CLI::callback_t take = [flag, set](const CLI::results_t& values) {
    if (values.size() > 1) throw InputError(flag, "given twice");
    // CLI11 takes the next word as the value whatever it looks like ("--out --no-alpha"); no
    // value of ours starts with "--", so such a word is a missing value, not a value.
    if (values.front().rfind("--", 0) == 0)
      throw InputError(flag, "expects a value, got the flag '" + values.front() + "'");
    set(values.front());
    return true;
  };
  CLI::Option* o = cl.app->add_option(flag, take, help);
  o->type_name(placeholder)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->expected(1);
}

// The option's name in a CLI11 message ("--eye: 1 required X,Y,Z missing"), else "".
std::string flag_in_message(const CLI::App& app, const std::string& message) {
  std::string best;
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& n : o->get_lnames()) {
      const std::string f = "--" + n;
      if (f.size() > best.size() && (message.find(f) != std::string::npos ||
                                     message.rfind(n + " ", 0) == 0))
        best = f;
    }
  }
  return best;
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

// docs/techniques/keys.md: the registry's key tables, then tune's default spaces.
static std::string keys_markdown() {
  std::string s = technique_keys_markdown() +
                  "\n## tune's default spaces\n\n"
                  "Without `--space`, `tune` searches these spaces: each technique's keys that declare "
                  "a domain (the column \"tune searches\" above; lab/param_space.h gives the "
                  "syntax).\n\n";
  for (const std::string& space : default_param_spaces()) s += "- `" + space + "`\n";
  return s;
}

// The programs --from repeats: their JSON outputs record the command (lab/provenance.h).
const std::string kRepeatable[] = {"render", "resolution_sweep", "tune"};

CommandLine make_command_line(const std::string& program, const std::string& synopsis) {
  CommandLine cl;
  cl.program = program;
  cl.app = std::make_shared<CLI::App>(program + " " + synopsis, program);
  CLI::App& app = *cl.app;
  app.set_help_flag("--help", "print this help (with the technique registry)");
  // run_main answers these three before parsing; listed here for --help.
  const std::string list_help = "print every technique with its keys and defaults, then exit";
  const std::string keys_help = "print every technique's key table (markdown: docs/techniques/keys.md), then exit";
  const std::string version_help = "print the program, shadowlab's commit and the compiler, then exit";
  app.add_flag("--list-techniques", list_help);
  app.add_flag("--list-keys", keys_help);
  app.add_flag("--version", version_help);
  // run_main replaces --from FILE by the recorded arguments before parsing, for the programs
  // whose outputs record their command (kRepeatable).
  if (std::find(std::begin(kRepeatable), std::end(kRepeatable), program) != std::end(kRepeatable))
    app.add_option("--from", "repeat the run recorded in FILE's provenance (a timing.json, sweep.json or tune.json this program wrote); only --out and --threads may be given beside it")
        ->type_name("FILE.json");
  // Unknown flags and positional arguments are collected and reported by parse_command_line
  // in shadowlab's one-line form.
  app.allow_extras(true);
  app.get_formatter()->column_width(28);
  app.footer("techniques (" + technique_naming_text() + ", or rt; spec NAME:key=value,...):\n" +
             technique_list_text());
  return cl;
}

void add_int(CommandLine& cl, const std::string& flag, const std::string& placeholder,
             const std::string& help, int& value, int lo, int hi) {
  add_valued(cl, flag, placeholder, help,
             [flag, &value, lo, hi](const std::string& s) { value = int_in(flag, s, lo, hi); });
}

void add_int(CommandLine& cl, const std::string& flag, const std::string& placeholder,
             const std::string& help, std::optional<int>& value, int lo, int hi) {
  add_valued(cl, flag, placeholder, help,
             [flag, &value, lo, hi](const std::string& s) { value = int_in(flag, s, lo, hi); });
}

void add_double(CommandLine& cl, const std::string& flag, const std::string& placeholder,
                const std::string& help, double& value, double lo, double hi) {
  add_valued(cl, flag, placeholder, help,
             [flag, &value, lo, hi](const std::string& s) { value = double_in(flag, s, lo, hi); });
}

void add_double(CommandLine& cl, const std::string& flag, const std::string& placeholder,
                const std::string& help, std::optional<double>& value, double lo, double hi) {
  add_valued(cl, flag, placeholder, help,
             [flag, &value, lo, hi](const std::string& s) { value = double_in(flag, s, lo, hi); });
}

void add_int_list(CommandLine& cl, const std::string& flag, const std::string& placeholder,
                  const std::string& help, std::vector<int>& value, int lo, int hi) {
  add_valued(cl, flag, placeholder, help, [flag, &value, lo, hi](const std::string& s) {
    value.clear();
    const std::vector<std::string> items = split(s, ',');
    for (const std::string& item : items) value.push_back(int_in(flag, item, lo, hi));
    reject_repeats(flag, value, items);
  });
}

void add_double_list(CommandLine& cl, const std::string& flag, const std::string& placeholder,
                     const std::string& help, std::vector<double>& value, double lo, double hi) {
  add_valued(cl, flag, placeholder, help, [flag, &value, lo, hi](const std::string& s) {
    value.clear();
    for (const std::string& item : split(s, ',')) {
      const double v = parse_double(flag, item);
      if (!(v >= lo && v <= hi))
        throw InputError(flag, item + " is outside [" + number_text(lo) + ", " + number_text(hi) + "]");
      value.push_back(v);
    }
    reject_repeats(flag, value, split(s, ','));
  });
}

void add_text_repeated(CommandLine& cl, const std::string& flag, const std::string& placeholder,
                       const std::string& help, std::vector<std::string>& values) {
  const CLI::callback_t take = [flag, &values](const CLI::results_t& given) {
    for (const std::string& v : given) {
      if (v.rfind("--", 0) == 0) throw InputError(flag, "expects a value, got the flag '" + v + "'");
      values.push_back(v);
    }
    return true;
  };
  CLI::Option* o = cl.app->add_option(flag, take, help);
  o->type_name(placeholder)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->expected(1);
}

void add_vec3(CommandLine& cl, const std::string& flag, const std::string& help,
              std::optional<vec3>& value) {
  add_valued(cl, flag, "X,Y,Z", help, [flag, &value](const std::string& s) {
    const std::vector<std::string> parts = split(s, ',');
    if (parts.size() != 3) throw InputError(flag, "expected x,y,z, got '" + s + "'");
    float xyz[3];
    for (int i = 0; i < 3; ++i) {
      const double v = parse_double(flag, parts[size_t(i)]);
      // Beyond float's range the conversion would give inf (formally undefined).
      if (!(std::fabs(v) <= double(std::numeric_limits<float>::max())))
        throw InputError(flag, parts[size_t(i)] + " is outside float's range");
      xyz[i] = float(v);
    }
    value = vec3(xyz[0], xyz[1], xyz[2]);
  });
}

void add_text(CommandLine& cl, const std::string& flag, const std::string& placeholder,
              const std::string& help, std::string& value, bool* given) {
  add_valued(cl, flag, placeholder, help, [&value, given](const std::string& s) {
    value = s;
    if (given) *given = true;
  });
}

void add_switch(CommandLine& cl, const std::string& flag, const std::string& help, bool& value) {
  cl.app
      ->add_flag_function(
          flag,
          [flag, &value](int64_t count) {
            if (count > 1) throw InputError(flag, "given twice");
            value = count > 0;
          },
          help)
      ->disable_flag_override();
}

void add_common_options(CommandLine& cl, CommonOptions& o) {
  o.out = "out/" + cl.program;
  std::string names;
  for (const std::string& n : builtin_scene_names()) names += (names.empty() ? "" : ", ") + n;
  add_text(cl, "--scene", "S", "built-in scene name (" + names + "), an .obj file, a .gltf/.glb file, or a .json scene file (default: default)", o.scene, &o.scene_given);
  add_switch(cl, "--ground", "add a ground quad under the scene (for a lone model: 2 x the bounds diagonal, at the bounds' bottom)", o.ground);
  add_int(cl, "--light", "N", "glTF scenes: which of the file's lights to use, in node order (default 0)", o.gltf_light, 0, 1 << 20);
  add_int(cl, "--camera", "N", "glTF scenes: which of the file's cameras to use, in node order (default 0)", o.gltf_camera, 0, 1 << 20);
  add_int(cl, "--width", "W", "image width in pixels (default: the scene's camera, 1024)", o.width, 1, kMaxImageSide);
  add_int(cl, "--height", "H", "image height in pixels (default: the scene's camera, 768)", o.height, 1, kMaxImageSide);
  // Applied as it is parsed, before any work.
  add_valued(cl, "--threads", "N", "worker threads (default: $SHADOWLAB_THREADS or all cores)",
             [](const std::string& s) { set_thread_count(int_in("--threads", s, 1, 1024)); });
  add_double(cl, "--light-radius", "R", "sphere-light radius in metres; 0 = hard point light (default: the scene's)", o.light_radius, 0.0, 1e4);
  add_vec3(cl, "--light-pos", "light position, metres (default: the scene's)", o.light_pos);
  add_vec3(cl, "--eye", "camera position, metres (default: the scene's)", o.eye);
  add_vec3(cl, "--target", "camera target, metres (default: the scene's)", o.target);
  add_double(cl, "--fov", "DEG", "vertical field of view in degrees (default: the scene's)", o.fov, 1.0, 170.0);
  add_double(cl, "--alpha-cutoff", "C", "alpha-test cutoff of every alpha-textured material, [0, 1] (default: the material's, 0.5)", o.alpha_cutoff, 0.0, 1.0);
  add_switch(cl, "--no-alpha", "ignore alpha textures: every material opaque (to measure the alpha path's cost)", o.no_alpha);
  add_text(cl, "--slide", "SLIDE", "make the light a slide projector casting SLIDE: spot, grid:amp=A,freq=F, or a .png/.exr file", o.slide, &o.slide_given);
  add_vec3(cl, "--projector-pos", "projector position, metres (default: the scene's pose, else the light)", o.projector_pos);
  add_vec3(cl, "--projector-target", "point the projector aims at (default: the scene's pose, else the camera target)", o.projector_target);
  add_double(cl, "--projector-fov", "DEG", "projector vertical field of view (default: the scene's pose, else 60)", o.projector_fov, 0.1, 169.0);
  add_double(cl, "--projector-aspect", "A", "projector slide width / height (default 1)", o.projector_aspect, 0.05, 20.0);
  add_double(cl, "--max-memory", "GB", "refuse runs estimated to need more memory (default: what the machine has available)", o.max_memory_gb, 1e-6, 1e6);
  add_text(cl, "--out", "DIR", "output folder (default " + o.out + ")", o.out);
}

void set_default_size(CommandLine& cl, CommonOptions& o, int width, int height, const std::string& why) {
  o.default_width = width;
  o.default_height = height;
  cl.app->get_option("--width")->description("image width in pixels (default " + std::to_string(width) + ": " + why + ")");
  cl.app->get_option("--height")->description("image height in pixels (default " + std::to_string(height) + ")");
}

void reject_scene_with_suite(const CommonOptions& o) {
  if (o.scene_given) throw InputError("--suite", "conflicts with --scene (the suite names its scenes)");
}

std::vector<std::string> common_scene_flags() {
  return {"--scene", "--light", "--camera", "--ground", "--width", "--height", "--light-radius", "--light-pos", "--eye", "--target",
          "--fov", "--alpha-cutoff", "--no-alpha", "--slide", "--projector-pos",
          "--projector-target", "--projector-fov", "--projector-aspect", "--max-memory", "--out"};
}

void add_repeats(CommandLine& cl, int& repeats, int lo, const std::string& extra) {
  add_int(cl, "--repeats", "N",
          "timed runs, the median reported" + (extra.empty() ? "" : "; " + extra) + " (default " +
              std::to_string(repeats) + (lo > 1 ? ", at least " + std::to_string(lo) : "") + ")",
          repeats, lo, 100000);
}

void mark_unused(CommandLine& cl, const std::vector<std::string>& flags, const std::string& reason) {
  const std::string group = "common flags not used here (an error if given; " + reason + ")";
  for (const std::string& flag : flags) {
    cl.unused[flag] = reason;
    CLI::Option* old = cl.app->get_option_no_throw(flag);
    SL_CHECK(old != nullptr);
    const std::string help = old->get_description();
    const std::string placeholder = old->get_type_name();
    const bool is_flag = is_switch(old);
    cl.app->remove_option(old);
    if (is_flag) {
      cl.app->add_flag_function(flag, [flag, reason](int64_t) { throw_unused(flag, reason); }, help)
          ->group(group);
      continue;
    }
    const CLI::callback_t reject = [flag, reason](const CLI::results_t&) -> bool {
      throw_unused(flag, reason);
    };
    cl.app->add_option(flag, reject, help)
        ->type_name(placeholder)
        ->group(group)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  }
}

bool parse_command_line(CommandLine& cl, int argc, char** argv, size_t max_positional) {
  CLI::App& app = *cl.app;
  auto not_used = [&](const std::string& flag) {
    if (const auto it = cl.unused.find(flag); it != cl.unused.end()) throw_unused(flag, it->second);
  };
  // Switches take no value: CLI11 would read "--no-alpha=true" (or "=") as a flag override.
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const size_t eq = a.find('=');
    if (a.rfind("--", 0) != 0 || eq == std::string::npos) continue;
    const CLI::Option* o = app.get_option_no_throw(a.substr(0, eq));
    if (o && is_switch(o)) {
      not_used(a.substr(0, eq));
      throw InputError(a.substr(0, eq), "takes no value");
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", app.help().c_str());
    return false;
  } catch (const CLI::ParseError& e) {
    const std::string message = e.what();
    const std::string flag = flag_in_message(app, message);
    if (flag.empty()) throw InputError(cl.program, message);
    not_used(flag);
    const CLI::Option* o = app.get_option_no_throw(flag);
    if (message.find("missing") != std::string::npos && o)
      throw InputError(flag, "expects a value " + o->get_type_name());
    if (message.find("flag override") != std::string::npos)
      throw InputError(flag, "takes no value");
    // CLI11's own text usually starts with the flag: not named twice.
    const std::string prefix = flag + ": ";
    throw InputError(flag, message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message);
  }
  for (const std::string& a : app.remaining()) {
    if (a == "--") throw InputError(a, "unexpected argument (see --help)");
    // "--name" and "-x": flags we do not have (a lone "-" or "-1" is an argument).
    if ((a.rfind("--", 0) == 0) ||
        (a.size() > 1 && a[0] == '-' && std::isalpha(static_cast<unsigned char>(a[1]))))
      throw InputError(a.substr(0, a.find('=')), "unknown flag (see --help)");
    if (cl.positional.size() >= max_positional) throw InputError(a, "unexpected argument (see --help)");
    cl.positional.push_back(a);
  }
  return true;
}

namespace {

// With a slide: makes the scene's light a slide projector (pose from the scene, else from the
// light aimed at the camera target; the --projector-* options override). Without one, any
// --projector-* option is an InputError.
void apply_projector_options(const CommonOptions& o, Scene& scene) {
  if (!o.slide_given) {
    if (o.projector_pos) throw InputError("--projector-pos", "needs --slide (the projector's slide)");
    if (o.projector_target) throw InputError("--projector-target", "needs --slide (the projector's slide)");
    if (o.projector_fov) throw InputError("--projector-fov", "needs --slide (the projector's slide)");
    if (o.projector_aspect) throw InputError("--projector-aspect", "needs --slide (the projector's slide)");
    return;
  }
  if (o.light_radius && scene.light.radius > 0.0f)
    throw InputError("--light-radius", "a slide projector is a point source; drop --light-radius or --slide");
  Projector p = scene.projector;
  vec3 target = scene.camera.target;
  if (p.posed) {
    target = p.position + p.direction;
  } else {
    p.position = scene.light.position;
    p.fov_y_deg = 60.0f;
  }
  if (o.light_pos && !o.projector_pos) p.position = scene.light.position;
  p.position = o.projector_pos.value_or(p.position);
  target = o.projector_target.value_or(target);
  p.direction = target - p.position;
  if (!(glm::length(p.direction) > 0.0f))
    throw InputError(o.projector_target ? "--projector-target" : "--projector-pos",
                     "the projector's target coincides with its position");
  // An aim straight up or down gets a horizontal up vector instead of +y.
  if (glm::length(glm::cross(glm::normalize(p.direction), p.up)) < 1e-3f) p.up = vec3(0.0f, 0.0f, -1.0f);
  if (o.projector_fov) p.fov_y_deg = float(*o.projector_fov);
  if (o.projector_aspect) p.aspect = float(*o.projector_aspect);
  p.slide = make_slide(o.slide, "--slide");
  set_projector(scene, std::move(p), "--slide");
}

// The light must fit the scene (core/light_fit.h); a problem is blamed on the flag that caused
// it, else left to validate_scene, which names the scene.
void check_light_fit(const CommonOptions& o, const Scene& scene) {
  const LightFitProblem fit = light_fit_problem(scene);
  std::vector<std::pair<bool, const char*>> suspects;  // (given, flag) in the order blamed
  switch (fit.kind) {
    case LightFitProblem::None:
      return;
    case LightFitProblem::Depth:
      suspects = {{bool(o.light_pos), "--light-pos"}, {bool(o.projector_pos), "--projector-pos"}};
      break;
    case LightFitProblem::Camera:
      suspects = {{bool(o.light_radius), "--light-radius"}, {bool(o.eye), "--eye"},
                  {bool(o.light_pos), "--light-pos"}};
      break;
    case LightFitProblem::Scene:
      suspects = {{bool(o.light_radius), "--light-radius"}, {bool(o.light_pos), "--light-pos"}};
      break;
  }
  for (const auto& [given, flag] : suspects)
    if (given) throw InputError(flag, fit.reason);
}

}  // namespace

Scene scene_from_options(const CommonOptions& o) {
  const std::string& name = o.scene;
  const bool is_file = name.find('/') != std::string::npos || name.find('.') != std::string::npos;
  if ((o.gltf_light || o.gltf_camera) && !is_gltf_path(name))
    throw InputError(o.gltf_light ? "--light" : "--camera", "picks among a glTF file's lights and cameras; --scene is not a .gltf/.glb file");
  GltfChoice choice;
  choice.light = o.gltf_light.value_or(0);
  choice.camera = o.gltf_camera.value_or(0);
  Scene scene = is_gltf_path(name)         ? make_gltf_scene(name, choice)
                : is_scene_file_path(name) ? load_scene_file(name)
                : is_file                  ? make_obj_scene(name)
                                           : make_builtin_scene(name);
  if (o.ground) add_ground_plane(scene);
  Camera& cam = scene.camera;
  cam.width = o.width.value_or(o.default_width > 0 ? o.default_width : cam.width);
  cam.height = o.height.value_or(o.default_height > 0 ? o.default_height : cam.height);
  cam.eye = o.eye.value_or(cam.eye);
  cam.target = o.target.value_or(cam.target);
  if (o.fov) cam.fov_y_deg = float(*o.fov);
  if (o.light_pos) {
    // A light the command line places gets the range scene files give theirs: it covers the
    // whole scene (the ground included), so no point lies beyond the light's far.
    scene.light.position = *o.light_pos;
    cover_scene_with_light_range(scene);
  }
  if (o.light_radius) scene.light.radius = float(*o.light_radius);
  if (o.alpha_cutoff && o.no_alpha) throw InputError("--alpha-cutoff", "conflicts with --no-alpha");
  for (Material& m : scene.materials) {
    if (o.no_alpha) m.alpha_texture = -1;
    if (o.alpha_cutoff) m.alpha_cutoff = float(*o.alpha_cutoff);
  }
  apply_projector_options(o, scene);
  check_light_fit(o, scene);
  const std::string where = is_file ? name : "--scene " + name;
  validate_scene(scene, where);
  // A view that sees nothing (lab/view_check.h), blamed on the view flag given.
  const std::string view_blame = o.eye ? "--eye" : o.target ? "--target" : o.fov ? "--fov" : where;
  check_view_sees_bounds(scene, view_blame);
  set_view_blame(scene.name, view_blame);
  check_recorded_scene(scene);  // --from: the scene must be the recorded one
  return scene;
}

int run_main(int argc, char** argv, const std::function<int(int, char**)>& body) {
  const std::string prog = std::filesystem::path(argv[0]).filename().string();
  // Before any thread starts: every thread then leaves SIGINT, SIGTERM and SIGHUP to the one
  // that removes the run's temporaries (core/temp_cleanup.h).
  install_interrupt_cleanup();
  // Keep freed large blocks in the heap instead of returning them to the kernel: on the VMs
  // we measure on, first-touch page faults of a 1024×768 GBuffer cost ~200 ms, ten times the
  // pass itself, and would otherwise be paid again by every timing repeat.
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  set_run_command(argc, argv);  // provenance of every output (lab/provenance.h)
  // --from FILE: the recorded run's arguments (provenance.h arguments_from_run) instead.
  std::vector<std::string> from_args;
  std::vector<char*> from_argv;
  try {
    check_environment();
    const bool repeatable =
        std::find(std::begin(kRepeatable), std::end(kRepeatable), prog) != std::end(kRepeatable);
    // --from FILE and --from=FILE alike (--flag=value works for every flag:
    // docs/programs/common_flags.md); the words beside it (--out, --threads) in either form too.
    std::vector<std::string> words;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      const size_t eq = a.find('=');
      const std::string name = a.substr(0, eq);
      if (repeatable && eq != std::string::npos && a.rfind("--", 0) == 0 &&
          (name == "--from" || name == "--out" || name == "--threads")) {
        words.push_back(name);
        words.push_back(a.substr(eq + 1));
      } else {
        words.push_back(a);
      }
    }
    for (size_t i = 0; i < words.size() && repeatable; ++i)
      if (words[i] == "--from") {
        if (i + 1 >= words.size() || words[i + 1].empty())
          throw InputError("--from", "needs a file (a timing.json, sweep.json or tune.json)");
        std::vector<std::string> rest;
        for (size_t k = 0; k < words.size(); ++k)
          if (k != i && k != i + 1) rest.push_back(words[k]);
        from_args = arguments_from_run(prog, words[i + 1], rest);
        from_args.insert(from_args.begin(), argv[0]);
        for (std::string& a : from_args) from_argv.push_back(a.data());
        from_argv.push_back(nullptr);
        argc = int(from_args.size());
        argv = from_argv.data();
        set_run_command(argc, argv);
        break;
      }
    for (int i = 1; i < argc; ++i) {
      if (std::string(argv[i]) == "--list-techniques") {
        std::printf("%s", technique_list_text().c_str());
        return 0;
      }
      if (std::string(argv[i]) == "--list-keys") {
        std::printf("%s", keys_markdown().c_str());
        return 0;
      }
      if (std::string(argv[i]) == "--version") {
        // The commit of the sources built (lab/CMakeLists.txt: "-dirty" for
        // uncommitted changes).
        std::printf("%s (shadowlab) commit %s, compiler %s\n", prog.c_str(), build_commit(),
                    __VERSION__);
        return 0;
      }
    }
    const int status = body(argc, argv);
    wait_for_interrupt_cleanup();
    print_notes();
    return status;
  } catch (const InputError& e) {
    wait_for_interrupt_cleanup();
    take_notes();  // the error is the only line
    // One prefix: an error whose source is the program itself ("metric") is not named twice.
    if (e.where == prog)
      std::fprintf(stderr, "%s: %s\n", prog.c_str(), e.reason.c_str());
    else
      std::fprintf(stderr, "%s: %s\n", prog.c_str(), e.what());
    return 2;
  } catch (const std::exception& e) {
    wait_for_interrupt_cleanup();
    take_notes();
    std::fprintf(stderr, "%s: error: %s\n", prog.c_str(), e.what());
    return 1;
  }
}

uint64_t max_memory_bytes(const CommonOptions& o) {
  return o.max_memory_gb ? uint64_t(*o.max_memory_gb * 1e9) : 0;
}

void parse_shard(const std::string& text, int& shard, int& shards) {
  const size_t slash = text.find('/');
  long i = 0, n = 0;
  if (slash == std::string::npos || !shadowlab::parse_long(text.substr(0, slash), i) ||
      !shadowlab::parse_long(text.substr(slash + 1), n))
    throw InputError("--shard", "expected i/N, got '" + text + "'");
  if (n < 1 || n > 100000 || i < 0 || i >= n)
    throw InputError("--shard", "expected 0 <= i < N <= 100000, got '" + text + "'");
  shard = int(i);
  shards = int(n);
}

void make_output_dir(const std::string& dir, const std::string& flag) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError(flag, "cannot create folder '" + dir + "': " + ec.message());
}

bool stderr_is_terminal() { return isatty(2) != 0; }

}  // namespace shadowlab
