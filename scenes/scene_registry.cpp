#include "scenes/scene_registry.h"

#include "core/error.h"
#include "scenes/bunny_scene.h"
#include "scenes/default_scene.h"
#include "scenes/foliage_scene.h"
#include "scenes/hard_scenes.h"
#include "scenes/room_scenes.h"

namespace shadowlab {

const std::vector<BuiltinScene>& builtin_scenes() {
  static const std::vector<BuiltinScene> rows = {
      {"default",
       "a Kluczek-style closed 10 x 4 x 10 m room with a box, a sphere, a thin pole, a table on "
       "thin legs and a slanted ramp around one 0.03 m sphere light; every cube face sees "
       "geometry; shadows from contact to room-long",
       make_default_scene},
      {"plane", "one 10 x 10 m floor quad, light 2 m above its centre, camera straight down; "
                "nothing occludes (analytic tests)",
       make_plane_scene},
      {"room100k", "the benchmark room (60 x 60 m ground, 20 x 8 x 20 m room, 32 spheres, 32 tori; "
                   "99,852 triangles) with its light and camera",
       make_room100k_scene},
      {"room1m", "the benchmark room tessellated finer: 999,436 triangles", make_room1m_scene},
      {"bunny", "the Stanford bunny on a ground quad before a wall, with a posed slide projector",
       [] { return make_bunny_scene(); }},
      {"foliage", "a palm tree and four plants (alpha-cut leaf cards) on a ground beside a wall, "
                  "one hard point light",
       [] { return make_foliage_scene(); }},
      {"grazing", "a light 0.6 m over one end of a 40 m floor with posts and a fence of 2 cm "
                  "slats: long shadows at 1-6 degree incidence (aliasing, acne)",
       make_grazing_scene},
      {"contact", "a chair on 3 cm legs, touching boxes, a 4 mm wire and an alpha-textured "
                  "chain-link fence: peter-panning, leaks, thin occluders",
       make_contact_scene},
      {"depth_range", "a light with a 1 cm near plane over a 2.4 km ground, boxes 1 m to 1 km "
                      "away: depth precision",
       make_depth_range_scene},
      {"cluttered", "room100k under its own name in the suite: every cube face used",
       [] {
         Scene s = make_room100k_scene();
         s.name = "cluttered";
         return s;
       }},
  };
  return rows;
}

std::vector<std::string> builtin_scene_names() {
  std::vector<std::string> names;
  for (const BuiltinScene& s : builtin_scenes()) names.push_back(s.name);
  return names;
}

Scene make_builtin_scene(const std::string& name) {
  for (const BuiltinScene& row : builtin_scenes())
    if (name == row.name) {
      Scene s = row.build();
      validate_scene(s, "built-in scene '" + name + "'");
      return s;
    }
  std::string known;
  for (const std::string& n : builtin_scene_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("--scene", "unknown built-in scene '" + name + "' (known: " + known + ")");
}

std::vector<std::string> scene_suite(const std::string& name, const std::string& flag) {
  const std::vector<std::string> hard = {"grazing", "contact", "depth_range", "cluttered"};
  if (name == "hard") return hard;
  if (name == "all") {
    std::vector<std::string> all = {"default", "foliage", "bunny"};
    all.insert(all.end(), hard.begin(), hard.end());
    return all;
  }
  throw InputError(flag, "unknown suite '" + name + "' (known: hard, all)");
}

std::string builtin_scenes_text() {
  std::string out;
  for (const BuiltinScene& s : builtin_scenes())
    out += std::string("  ") + s.name + ": " + s.description + "\n";
  return out;
}

}  // namespace shadowlab
