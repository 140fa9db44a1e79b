#include "lab/provenance.h"

#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "core/error.h"
#include "core/notes.h"
#include "core/run_inputs.h"
#include "core/parallel.h"
#include "core/scene_hash.h"
#include "core/json_file.h"

#include "shadowlab_commit.h"  // SHADOWLAB_COMMIT, generated at build time

namespace shadowlab {
namespace {

std::string& program_storage() {
  static std::string p = "shadowlab";
  return p;
}
std::vector<std::string>& argument_storage() {
  static std::vector<std::string> a;
  return a;
}

std::map<std::string, std::string>& recorded_hashes() {
  static std::map<std::string, std::string> m;
  return m;
}

}  // namespace

void set_run_command(int argc, char** argv) {
  if (argc > 0) {
    std::string p = argv[0];
    const size_t slash = p.find_last_of('/');
    program_storage() = slash == std::string::npos ? p : p.substr(slash + 1);
  }
  argument_storage().assign(argv + (argc > 0 ? 1 : 0), argv + argc);
}
const std::string& run_program() { return program_storage(); }
const std::vector<std::string>& run_arguments() { return argument_storage(); }

const char* build_commit() { return SHADOWLAB_COMMIT; }
// Bumped with each wave of issues (docs/provenance.md).
const char* shadowlab_version() { return "0.2.0"; }

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) {
        std::string v = line.substr(colon + 1);
        while (!v.empty() && v.front() == ' ') v.erase(v.begin());
        return v;
      }
    }
  return "unknown";
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

nlohmann::json provenance_json(const std::vector<const Scene*>& scenes, int spp, int repeats) {
  nlohmann::json j;
  j["program"] = run_program();
  j["version"] = shadowlab_version();
  j["commit"] = build_commit();
  j["compiler"] = __VERSION__;
  j["cpu"] = cpu_model();
  j["date"] = utc_now();
  j["threads"] = thread_count();
  j["command"] = run_arguments();
  j["scenes"] = nlohmann::json::array();
  for (const Scene* s : scenes) {
    const vec3 p = s->light.position;
    j["scenes"].push_back({{"name", s->name},
                           {"hash", scene_hash(*s)},
                           {"width", s->camera.width},
                           {"height", s->camera.height},
                           {"light_position", {p.x, p.y, p.z}},
                           {"light_radius", s->light.radius},
                           {"seed", s->seed}});
  }
  j["spp"] = spp;
  j["repeats"] = repeats;
  // Every random choice is a hash of (pixel, sample, scene seed) (core/rng.h): no run seed.
  j["seeds"] = "per pixel and sample from the scene seed (core/rng.h rng_hash); no per-run or per-thread seed";
  return j;
}

std::vector<std::string> arguments_from_run(const std::string& program, const std::string& path,
                                            const std::vector<std::string>& overrides) {
  note_input(path);
  nlohmann::json j;
  try {
    j = read_json_file(path, kResultFileLimit);
  } catch (const InputError& e) {
    // Not JSON at all (an image, a CSV): say what --from wants.
    if (e.reason.rfind("JSON syntax error", 0) != 0) throw;
    throw InputError(path, "has no provenance to repeat (" + e.reason +
                               "; a timing.json, sweep.json or tune.json of shadowlab 0.2 or later)");
  }
  if (!j.is_object() || !j.contains("provenance") || !j["provenance"].is_object())
    throw InputError(path, "has no provenance to repeat (a timing.json, sweep.json or tune.json of shadowlab 0.2 or later)");
  const nlohmann::json& p = j["provenance"];
  if (!p.contains("program") || !p["program"].is_string() || !p.contains("command") || !p["command"].is_array())
    throw InputError(path, "its provenance has no program and command");
  if (p["program"].get<std::string>() != program)
    throw InputError("--from", path + " records a run of " + p["program"].get<std::string>() + ", not " + program);
  // Only --out and --threads may change: anything else would not repeat the run.
  std::map<std::string, std::string> over;
  for (size_t i = 0; i < overrides.size(); ++i) {
    const std::string& f = overrides[i];
    if ((f != "--out" && f != "--threads") || i + 1 >= overrides.size())
      throw InputError("--from", "only --out DIR and --threads N may be given with --from, got '" + f + "'");
    over[f] = overrides[++i];
  }
  std::vector<std::string> args;
  const nlohmann::json& cmd = p["command"];
  for (size_t i = 0; i < cmd.size(); ++i) {
    if (!cmd[i].is_string()) throw InputError(path, "its provenance command is not a list of strings");
    const std::string a = cmd[i].get<std::string>();
    if (over.count(a) && i + 1 < cmd.size()) {
      ++i;  // the recorded value is replaced below
      continue;
    }
    args.push_back(a);
  }
  for (const auto& [f, v] : over) {
    args.push_back(f);
    args.push_back(v);
  }
  recorded_hashes().clear();
  if (p.contains("scenes") && p["scenes"].is_array())
    for (const nlohmann::json& sc : p["scenes"])
      if (sc.is_object() && sc.contains("name") && sc.contains("hash") && sc["name"].is_string() && sc["hash"].is_string())
        recorded_hashes()[sc["name"].get<std::string>()] = sc["hash"].get<std::string>();
  if (p.contains("commit") && p["commit"].is_string() && p["commit"].get<std::string>() != build_commit())
    hold_note(program + ": note: " + path + " was recorded with commit " + p["commit"].get<std::string>() +
              ", this build is " + build_commit() + ": scores may differ");
  return args;
}

void check_recorded_scene(const Scene& scene) {
  const auto& m = recorded_hashes();
  if (m.empty()) return;
  const auto it = m.find(scene.name);
  if (it == m.end()) throw InputError("--from", "the recorded run has no scene '" + scene.name + "'");
  const std::string now = scene_hash(scene);
  if (now != it->second)
    throw InputError("--from", "scene '" + scene.name + "' is not the recorded one (hash " + it->second +
                                   ", now " + now + "): its files changed");
}

std::vector<std::string> command_without(const std::vector<std::string>& args,
                                         const std::vector<std::string>& flags) {
  std::vector<std::string> out;
  for (size_t i = 0; i < args.size(); ++i) {
    bool drop = false;
    for (const std::string& f : flags) {
      if (args[i] == f && i + 1 < args.size()) {
        ++i;  // and its value
        drop = true;
      } else if (args[i].rfind(f + "=", 0) == 0) {
        drop = true;
      }
      if (drop) break;
    }
    if (!drop) out.push_back(args[i]);
  }
  return out;
}

std::vector<std::pair<std::string, std::string>> provenance_attributes(const nlohmann::json& p) {
  std::vector<std::pair<std::string, std::string>> out;
  for (auto it = p.begin(); it != p.end(); ++it)
    out.emplace_back("shadowlab:" + it.key(),
                     it.value().is_string() ? it.value().get<std::string>() : it.value().dump());
  return out;
}

}  // namespace shadowlab
