#pragma once
// The command line of the experiment mains, on CLI11: every option is bound to a typed field
// (int, double, vec3, list, text, switch) with its range, parsed by shadowlab's strict number
// rules (core/parse_number.h: decimal only); --help is generated (flags, defaults, the unused
// common flags with their reason, the technique registry). Any bad input is an InputError
// naming the flag: one line on stderr and exit code 2 (run_main).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"

namespace CLI {
class App;
}

namespace shadowlab {

// Splits s at every `sep`, keeping empty items ("a,,b" and "a,b," hold an empty one).
std::vector<std::string> split(const std::string& s, char sep);

// An experiment's command line: the CLI11 app and, after parsing, the positional arguments.
struct CommandLine {
  std::string program;                  // "render"
  std::shared_ptr<CLI::App> app;
  std::vector<std::string> positional;  // filled by parse_command_line
  std::map<std::string, std::string> unused;  // flag → why this experiment does not use it
};

// A command line with --help, --version and --list-techniques; `synopsis` is the usage line
// after the program name ("--technique SPEC [flags]").
CommandLine make_command_line(const std::string& program, const std::string& synopsis);

// Typed options. Each parses its value strictly, checks [lo, hi], and rejects a second
// occurrence ("given twice"); `placeholder` names the value in --help ("N", "X,Y,Z").
// An optional<> stays empty when the flag is absent.
void add_int(CommandLine& cl, const std::string& flag, const std::string& placeholder,
             const std::string& help, int& value, int lo, int hi);
void add_int(CommandLine& cl, const std::string& flag, const std::string& placeholder,
             const std::string& help, std::optional<int>& value, int lo, int hi);
void add_double(CommandLine& cl, const std::string& flag, const std::string& placeholder,
                const std::string& help, double& value, double lo, double hi);
void add_double(CommandLine& cl, const std::string& flag, const std::string& placeholder,
                const std::string& help, std::optional<double>& value, double lo, double hi);
// Comma-separated integers, each in [lo, hi]; no empty items, no value twice as parsed
// ("64,064": core/repeats.h).
void add_int_list(CommandLine& cl, const std::string& flag, const std::string& placeholder,
                  const std::string& help, std::vector<int>& value, int lo, int hi);
// Comma-separated numbers, each in [lo, hi]; no empty items, no value twice as parsed
// ("4,4.0": core/repeats.h).
void add_double_list(CommandLine& cl, const std::string& flag, const std::string& placeholder,
                     const std::string& help, std::vector<double>& value, double lo, double hi);
void add_vec3(CommandLine& cl, const std::string& flag, const std::string& help,
              std::optional<vec3>& value);
// A flag that may be given several times, each value appended in order.
void add_text_repeated(CommandLine& cl, const std::string& flag, const std::string& placeholder,
                       const std::string& help, std::vector<std::string>& values);
// Any text (specs, paths, names; the caller validates what it means). `given` (optional) is set
// when the flag appears, even with an empty value.
void add_text(CommandLine& cl, const std::string& flag, const std::string& placeholder,
              const std::string& help, std::string& value, bool* given = nullptr);
void add_switch(CommandLine& cl, const std::string& flag, const std::string& help, bool& value);

// The flags every experiment takes (docs/programs/common_flags.md), bound to one struct. Unset
// optionals keep the scene's own values.
struct CommonOptions {
  std::string scene = "default";
  bool scene_given = false;          // --scene appeared (even naming the default)
  std::optional<int> width, height;  // (--threads is applied as it is parsed)
  std::optional<int> gltf_light, gltf_camera;  // --light, --camera (glTF scenes)
  bool ground = false;                         // --ground
  std::optional<double> light_radius, fov, alpha_cutoff;
  std::optional<vec3> light_pos, eye, target;
  bool no_alpha = false;
  std::string slide;  // empty: no slide projector
  bool slide_given = false;
  std::optional<vec3> projector_pos, projector_target;
  std::optional<double> projector_fov, projector_aspect;
  std::optional<double> max_memory_gb;
  std::string out;  // out/PROGRAM unless given
  // The image size without --width/--height when the program has its own (set_default_size);
  // 0: the scene camera's.
  int default_width = 0, default_height = 0;
};
void add_common_options(CommandLine& cl, CommonOptions& o);
// The program's own image size without --width/--height (instead of the scene camera's): set
// in o, applied by scene_from_options, and stated as the default in --help.
void set_default_size(CommandLine& cl, CommonOptions& o, int width, int height, const std::string& why);
// --suite runs its own list of scenes: any --scene beside it (the default's name included) is an
// InputError("--suite", "conflicts with --scene").
void reject_scene_with_suite(const CommonOptions& o);
// Every common flag but --threads (the ones that describe a scene, its view, memory and output).
std::vector<std::string> common_scene_flags();

// The same meaning of --repeats everywhere: timed runs, the median reported.
void add_repeats(CommandLine& cl, int& repeats, int lo, const std::string& extra = "");

// Marks flags as not used by this experiment: --help lists them under that reason, and giving
// one is an InputError with it (never silently ignored).
void mark_unused(CommandLine& cl, const std::vector<std::string>& flags, const std::string& reason);

// Parses argv (at most max_positional positional arguments). Returns false when --help was
// printed (the main then returns 0). --threads takes effect as it is parsed.
bool parse_command_line(CommandLine& cl, int argc, char** argv, size_t max_positional = 0);

// The scene the common options describe: a built-in name or an .obj path, with every override
// applied and validated (a slide makes the light a projector). A light placed by --light-pos
// gets a far that covers the scene (core/light_fit.h cover_scene_with_light_range); a light that
// does not fit the scene (light_fit_problem) is an InputError naming the flag that placed or
// sized it; a view whose frustum misses the scene is one naming the view flag
// (lab/view_check.h).
Scene scene_from_options(const CommonOptions& o);

// The --max-memory limit in bytes (0: not given).
uint64_t max_memory_bytes(const CommonOptions& o);

// Runs body; InputError → "<program>: <flag/file>: <reason>" on stderr and exit code 2; any
// other exception → exit code 1. --list-techniques and --version anywhere print and exit 0.
// First the SHADOWLAB_ variables are checked (lab/environment.h); --from FILE (or
// --from=FILE) is replaced by the recorded arguments. Notes held while the inputs were read
// (core/notes.h) are printed after a successful body and dropped on an error.
int run_main(int argc, char** argv, const std::function<int(int, char**)>& body);

// --shard i/N: 0 <= i < N <= 100000, else InputError("--shard", …).
void parse_shard(const std::string& text, int& shard, int& shards);

// Creates the folder (and parents) or throws InputError(flag, reason).
void make_output_dir(const std::string& dir, const std::string& flag);

// True when stderr is a terminal (progress lines are shown only then).
bool stderr_is_terminal();

}  // namespace shadowlab
