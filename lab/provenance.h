#pragma once
// Provenance of every output (docs/provenance.md): what ran, on what, from which source. The
// mains record their command line through run_main (lab/cli.h); the writers put
// provenance_json into every JSON and CSV they write and, as string attributes, into EXR headers.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene.h"

namespace shadowlab {

// The program name and arguments of this process (argv[1..]), set once by run_main.
void set_run_command(int argc, char** argv);
const std::string& run_program();
const std::vector<std::string>& run_arguments();

// The commit the build was configured from ("unknown" outside a git checkout), shadowlab's
// version, the compiler, the CPU model (/proc/cpuinfo "model name", "unknown" elsewhere) and the
// current UTC date and time (ISO 8601).
const char* build_commit();
const char* shadowlab_version();
std::string cpu_model();
std::string utc_now();

// {"program", "version", "commit", "compiler", "cpu", "date", "threads", "command": [args],
//  "scenes": [{"name", "hash" (core/scene_hash.h), "width", "height", "light_position",
//  "light_radius", "seed"}], "spp", "repeats", "seeds"}. spp: the reference's samples per pixel, 0 when the output
// compares with no reference (render: the technique's spec says all).
nlohmann::json provenance_json(const std::vector<const Scene*>& scenes, int spp, int repeats);
// --from FILE (run_main): the arguments of the run recorded in FILE's "provenance" (a JSON file
// this program wrote: timing.json, sweep.json, tune.json), with the recorded --out and
// --threads replaced when `overrides` gives them; any other flag beside --from is an
// InputError. Also arms check_recorded_scene: until the process ends, every scene built must
// have the recorded content hash. A different commit is reported on stderr (scores may differ).
std::vector<std::string> arguments_from_run(const std::string& program, const std::string& path,
                                            const std::vector<std::string>& overrides);
// Throws InputError("--from", …) when a run is being repeated and `scene` is not the recorded
// scene of that name (its file changed, or the build makes it differently).
void check_recorded_scene(const Scene& scene);

// args without the given flags and their values ("--out DIR" and "--out=DIR" alike): the part of
// a recorded command that shards of one run share (merge), or that repeats the whole run.
std::vector<std::string> command_without(const std::vector<std::string>& args,
                                         const std::vector<std::string>& flags);

// The same as flat text pairs, for EXR header attributes ("shadowlab:commit", …).
std::vector<std::pair<std::string, std::string>> provenance_attributes(const nlohmann::json& p);

}  // namespace shadowlab
