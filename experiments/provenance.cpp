#include "experiments/provenance.h"

#include <ctime>
#include <fstream>

#include <fmt/format.h>

#include "core/parallel.h"
#include "core/scene_hash.h"

#ifndef SHADOWLAB_COMMIT
#define SHADOWLAB_COMMIT "unknown"
#endif

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
// Bumped with each wave of issues (README "Provenance").
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

std::vector<std::pair<std::string, std::string>> provenance_attributes(const nlohmann::json& p) {
  std::vector<std::pair<std::string, std::string>> out;
  for (auto it = p.begin(); it != p.end(); ++it)
    out.emplace_back("shadowlab:" + it.key(),
                     it.value().is_string() ? it.value().get<std::string>() : it.value().dump());
  return out;
}

}  // namespace shadowlab
