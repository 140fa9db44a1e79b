#pragma once
// Provenance of every output (README "Provenance"): what ran, on what, from which source. The
// mains record their command line through run_main (experiments/cli.h); the writers put
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
//  "light_radius", "seed"}], "spp", "repeats", "seeds"}. spp 0: no reference in this output.
nlohmann::json provenance_json(const std::vector<const Scene*>& scenes, int spp, int repeats);
// The same as flat text pairs, for EXR header attributes ("shadowlab:commit", …).
std::vector<std::pair<std::string, std::string>> provenance_attributes(const nlohmann::json& p);

}  // namespace shadowlab
