// Bad technique specs fail with an InputError naming the flag, never a crash.
#include <gtest/gtest.h>

#include "core/error.h"
#include "test_scenes.h"

namespace shadowlab {
namespace {

void expect_input_error(const std::string& spec, const std::string& needle) {
  try {
    validate_technique(parse_technique_spec(spec, "--technique"), "--technique");
    ADD_FAILURE() << spec << " was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, "--technique");
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(TechniqueSpec, ParsesNameAndParams) {
  const TechniqueSpec s = parse_technique_spec("csm:res=1024,pcf=3", "--technique");
  EXPECT_EQ(s.name, "csm");
  EXPECT_EQ(s.params.at("res"), "1024");
  EXPECT_EQ(s.params.at("pcf"), "3");
  EXPECT_EQ(s.text, "csm:pcf=3,res=1024");
}

TEST(TechniqueSpec, SplitsListsWhoseSpecsHaveCommas) {
  const std::vector<std::string> v = split_spec_list("csm:pcf=3,bias=0.1,rt,csm");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0], "csm:pcf=3,bias=0.1");
  EXPECT_EQ(v[1], "rt");
  EXPECT_EQ(v[2], "csm");
}

TEST(TechniqueSpec, RejectsBadInput) {
  expect_input_error("nosuch", "unknown technique 'nosuch'");
  expect_input_error("csm:res=0", "res");
  expect_input_error("csm:res=100000", "res");
  expect_input_error("csm:res=abc", "expects an integer");
  expect_input_error("csm:pcf=2", "pcf");
  expect_input_error("csm:colour=red", "unknown parameter 'colour'");
  expect_input_error("csm:res", "key=value");
  expect_input_error("csm:res=1,res=2", "twice");
  expect_input_error("rt:spp=0", "spp");
  expect_input_error("csm:bias=nan", "number");
}

// A map must span at least 32 texels of the scene (core/light_fit.h): 2·asin(r/d)/(π/2)·res.
// Bounds of half-diagonal r = 1 seen from d = 2 span 2/3 of a face: res 48 gives exactly 32
// texels, which is enough, and res 47 is refused.
TEST(TechniqueSpec, MapsMustSpanAtLeast32TexelsOfTheScene) {
  Scene s;
  s.materials.resize(1);
  Mesh m;
  m.positions = {vec3(-1, 0, 0), vec3(1, 0, 0), vec3(0, 0, 0)};
  m.normals = {vec3(0, 1, 0), vec3(0, 1, 0), vec3(0, 1, 0)};
  m.indices = {0, 1, 2};
  s.meshes.push_back(m);
  s.light.position = vec3(0, 2, 0);
  EXPECT_NO_THROW(validate_technique_for_scene(parse_technique_spec("csm:res=48", "--technique"), s, "--technique"));
  try {
    validate_technique_for_scene(parse_technique_spec("csm:res=47", "--technique"), s, "--technique");
    ADD_FAILURE() << "res 47 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("at least 32 needed"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace shadowlab
