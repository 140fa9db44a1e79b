#pragma once
// The built-in scenes: one row each of {name, description, builder} (scene_registry.cpp), from
// which make_builtin_scene, the names in error messages and the --scene help text come. Adding
// a scene is one file with its builder and one row. Units: metres; world right-handed, y up.
#include <string>
#include <vector>

#include "core/scene.h"

namespace shadowlab {

struct BuiltinScene {
  const char* name;
  const char* description;  // one line: what it is and what it stresses
  Scene (*build)();
};

// Every built-in scene, in the order of the help text and error messages.
const std::vector<BuiltinScene>& builtin_scenes();

// Names accepted by make_builtin_scene, in registry order.
std::vector<std::string> builtin_scene_names();

// A built-in scene by name, validated. Throws InputError("--scene", "unknown built-in scene 'x'
// (known: default, plane, ...)").
Scene make_builtin_scene(const std::string& name);

// "name: description" lines, one per scene (for --help and docs/programs/common_flags.md).
std::string builtin_scenes_text();

// Scene suites (--suite NAME): "hard" = grazing, contact, depth_range, cluttered (the cases
// that separate techniques); "all" = hard + default, foliage and bunny. Throws
// InputError(flag, ...) for another name.
std::vector<std::string> scene_suite(const std::string& name, const std::string& flag);

}  // namespace shadowlab
