#pragma once
// Shared command-line handling of the experiment mains: a strict flag parser (unknown flag or
// bad value → InputError naming the flag → one line on stderr, exit code 2), the common scene
// flags, and the main wrapper.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/scene.h"

namespace shadowlab {

struct FlagDef {
  std::string name;     // "--width"
  std::string value;    // value placeholder ("N"); empty for a switch
  std::string help;
  // Non-empty: a common flag this experiment does not use, and why. --help lists it as such
  // and giving it is an InputError with this reason (never silently ignored).
  std::string unused = {};
};

struct ParsedArgs {
  std::map<std::string, std::string> values;  // flag → value ("1" for switches)
  std::vector<std::string> positional;
  bool has(const std::string& flag) const { return values.count(flag) != 0; }
  std::string get(const std::string& flag, const std::string& fallback) const;
  int get_int(const std::string& flag, int fallback, int lo, int hi) const;
  double get_double(const std::string& flag, double fallback, double lo, double hi) const;
  std::vector<int> get_int_list(const std::string& flag, const std::vector<int>& fallback, int lo,
                                int hi) const;
  vec3 get_vec3(const std::string& flag, const vec3& fallback) const;
};

// Splits s at every `sep`, keeping empty items ("a,,b" and "a,b," hold an empty one).
std::vector<std::string> split(const std::string& s, char sep);

// The flags every experiment takes: --scene --width --height --threads --light-radius --out,
// plus camera/light overrides (--eye --target --fov --light-pos) and --help.
std::vector<FlagDef> common_flags();
// Marks the named flags of defs as not used by this experiment, for `reason`.
void mark_unused(std::vector<FlagDef>& defs, const std::vector<std::string>& names,
                 const std::string& reason);
// Every common flag but --threads, --help, --list-techniques and --version.
std::vector<std::string> common_scene_flags();

// Parses argv against `defs`; `max_positional` positional arguments are allowed.
ParsedArgs parse_args(int argc, char** argv, const std::vector<FlagDef>& defs,
                      size_t max_positional = 0);
// Usage text: synopsis line, one line per flag, then the technique registry.
std::string usage_text(const std::string& synopsis, const std::vector<FlagDef>& defs);

// Applies --threads, then builds the scene named by --scene (a built-in name or an .obj path)
// with every override applied, validated.
Scene scene_from_args(const ParsedArgs& args);

// With --slide: makes the scene's light a slide projector (pose from the scene, else from the
// light aimed at the camera target; --projector-* flags override). Without it, any
// --projector-* flag is an InputError.
void apply_projector_flags(const ParsedArgs& args, Scene& scene);

// The --max-memory limit in bytes (0: not given).
uint64_t max_memory_bytes(const ParsedArgs& args);

// Runs body; InputError → "<program>: <flag/file>: <reason>" on stderr and exit code 2; any
// other exception → exit code 1. --list-techniques anywhere prints the registry and exits 0.
int run_main(int argc, char** argv, const std::function<int(int, char**)>& body);

// Creates the folder (and parents) or throws InputError(flag, reason).
void make_output_dir(const std::string& dir, const std::string& flag);

// True when stderr is a terminal (progress lines are shown only then).
bool stderr_is_terminal();

}  // namespace shadowlab
