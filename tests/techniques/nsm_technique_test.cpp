// `nsm` as a registered technique (techniques/nsm/nsm_technique.h): its mask convention, what it
// feeds the network, its work counts, its determinism and its refusals. Networks are written by
// the tests' own .nsmw writer (nsm_weights_writer.h): a constant network whose output is known
// in closed form, and random ones whose output is compared with the network run by hand on the
// features of a base map built by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include <unistd.h>

#include "core/error.h"
#include "core/parallel.h"
#include "raster/gbuffer_pass.h"
#include "scenes/mesh_builders.h"
#include "scenes/scene_registry.h"
#include "techniques/nsm/nsm_features.h"
#include "techniques/nsm/nsm_technique.h"
#include "techniques/pipeline/light_map.h"
#include "tests/techniques/nsm_weights_writer.h"

namespace shadowlab {
// A named namespace: the unity build compiles several test files in one translation unit.
namespace nsm_technique_test {

using test::NsmwDraft;

// The plane scene with a square occluder, small enough for a quick forward pass; part of the
// view is sky (uncovered) and the occluder's top faces away from the eye-side light test below.
Scene scene_with_occluder() {
  Scene s = make_builtin_scene("plane");
  s.camera.width = 72;
  s.camera.height = 40;
  add_quad_mesh(s, vec3(-0.6f, 1, -0.6f), vec3(-0.6f, 1, 0.6f), vec3(0.6f, 1, 0.6f),
                vec3(0.6f, 1, -0.6f));
  s.light.radius = 0.12f;
  return s;
}

std::string temp_file(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("shadowlab_nsm_technique_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

std::string save(const NsmwDraft& d, const std::string& name) {
  const std::string path = temp_file(name);
  test::nsmw_save(path, test::nsmw_bytes(d));
  return path;
}

NsmArch tiny() {
  NsmArch a;
  EXPECT_TRUE(nsm_named_arch("tiny", a));
  return a;
}

ShadowResult run(const std::string& spec_text, const Scene& s, const GBuffer& g, int repeats = 1) {
  RunOptions o;
  o.repeats = repeats;
  return run_technique(parse_technique_spec(spec_text, "--technique"), s, g, o);
}

// Every weight 0 and the head's bias b: the network's output is sigmoid(b) at every pixel
// whatever its input, so the mask is sigmoid(b) where the surface faces the light, 0 where it
// faces away and 1 where nothing is covered (docs/design.md §4).
TEST(NsmTechnique, ConstantNetworkGivesTheMaskConvention) {
  NsmwDraft d = test::nsmw_draft(tiny(), 3);
  for (auto& t : d.tensors) std::fill(t.begin(), t.end(), 0.0f);
  d.tensors.back() = {0.75f};  // head.conv1.bias
  const std::string path = save(d, "constant.nsmw");
  Scene s = scene_with_occluder();
  s.light.position = vec3(0.3f, 2.0f, 0.2f);
  const GBuffer g = render_gbuffer(s);
  const ShadowResult r = run("nsm:weights=" + path + ",res=256", s, g);
  const float expect = float(1.0L / (1.0L + std::exp(-0.75L)));
  size_t lit = 0, away = 0, sky = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i) {
    if (!g.covered[i]) {
      ++sky;
      ASSERT_EQ(r.mask.data[i], 1.0f) << i;
    } else if (glm::dot(g.geo_normal[i], s.light.position - g.position[i]) <= 0.0f) {
      ++away;
      ASSERT_EQ(r.mask.data[i], 0.0f) << i;
    } else {
      ++lit;
      ASSERT_NEAR(r.mask.data[i], expect, 1e-7f) << i;
    }
  }
  EXPECT_GT(lit, 100u);
  EXPECT_GT(sky, 100u);
  std::filesystem::remove(path);
}

// A camera below the occluder's plane sees its underside, which faces away from the light.
TEST(NsmTechnique, SurfacesFacingAwayFromTheLightAreZero) {
  NsmwDraft d = test::nsmw_draft(tiny(), 4);
  const std::string path = save(d, "away.nsmw");
  Scene s = scene_with_occluder();
  s.camera.eye = vec3(0.0f, 0.5f, 2.5f);
  s.camera.target = vec3(0.0f, 1.0f, 0.0f);
  const GBuffer g = render_gbuffer(s);
  const ShadowResult r = run("nsm:weights=" + path + ",res=256", s, g);
  size_t away = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i)
    if (g.covered[i] && glm::dot(g.geo_normal[i], s.light.position - g.position[i]) <= 0.0f) {
      ++away;
      ASSERT_EQ(r.mask.data[i], 0.0f);
    } else if (g.covered[i]) {
      ASSERT_GT(r.mask.data[i], 0.0f);
      ASSERT_LT(r.mask.data[i], 1.0f);
    }
  EXPECT_GT(away, 50u);
  std::filesystem::remove(path);
}

// The network's inputs are the features the weights name, in their order, at the scene's scale
// and the light's size code: the mask equals the forward pass run by hand on them. The weights
// name a non-default subset in a non-default order, so a technique that fed the default four,
// or swapped the scale and the size code, would differ.
TEST(NsmTechnique, FeedsTheNamedFeaturesAtTheScenesScaleAndSizeCode) {
  NsmArch a = tiny();
  a.features = 3;
  NsmwDraft d = test::nsmw_draft(a, 5);
  d.header["features"] = {"c_e_r", "d", "z_minus_zf"};
  const std::string path = save(d, "subset.nsmw");
  Scene s = scene_with_occluder();
  s.light.position = vec3(0.2f, 2.4f, -0.1f);  // scale s ≠ 1
  const GBuffer g = render_gbuffer(s);
  const ShadowResult r = run("nsm:weights=" + path + ",res=256", s, g);

  const NsmWeights w = read_nsm_weights(path);
  LightMap map;
  build_nsm_base_map(s, g, 256, map);
  const float scale = glm::length(s.light.position - s.camera.target) / 3.12f;
  const float code = 4.0f * 0.12f / 0.3f;
  const NsmFeatures f = compute_nsm_features(s, g, 256, map, scale, code, {"c_e_r", "d", "z_minus_zf"});
  std::vector<float> planes;
  for (const auto& p : f.planes) planes.insert(planes.end(), p.begin(), p.end());
  std::vector<float> out(g.pixel_count());
  nsm_forward(nsm_network(w), planes.data(), g.width, g.height, out.data());
  size_t compared = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i)
    if (g.covered[i] && glm::dot(g.geo_normal[i], s.light.position - g.position[i]) > 0.0f) {
      ASSERT_EQ(std::memcmp(&r.mask.data[i], &out[i], 4), 0) << i;
      ++compared;
    }
  EXPECT_GT(compared, 500u);
  // The light's size reaches the network: another radius gives another mask.
  s.light.radius = 0.24f;
  const ShadowResult r2 = run("nsm:weights=" + path + ",res=256", s, g);
  size_t differ = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i) differ += r.mask.data[i] != r2.mask.data[i];
  EXPECT_GT(differ, compared / 2);
  std::filesystem::remove(path);
}

// Work counts from the architecture by hand: Σ k²·ic·oc over the convolutions, each at its
// level's pixel count (level l of the padded 72 × 40 image is 72/2^l × 40/2^l; tiny's 3 levels
// need multiples of 4, which 72 × 40 is), and the base map's rendered texels at 4 B each.
TEST(NsmTechnique, WorkCountsFollowTheArchitecture) {
  const NsmwDraft d = test::nsmw_draft(tiny(), 6);
  const std::string path = save(d, "work.nsmw");
  const Scene s = scene_with_occluder();
  const GBuffer g = render_gbuffer(s);
  const ShadowResult r = run("nsm:weights=" + path + ",res=128", s, g);
  // tiny: F = 4, C = {4, 8}, B = 16, head 16. Levels: enc0 (0), enc1 (1), mid (2), dec1 (1),
  // dec0 and the head (0).
  const double px[3] = {72.0 * 40, 36.0 * 20, 18.0 * 10};
  const double macs = px[0] * (9 * 4 * 4 + 4 * 4) + px[1] * (9 * 4 * 8 + 8 * 8) +
                      px[2] * (9 * 8 * 16 + 16 * 8) + px[1] * (9 * 8 * 8 + 8 * 4) +
                      px[0] * (9 * 4 * 4 + 4 * 16 + 16 * 1);
  EXPECT_EQ(double(r.work.multiply_adds), macs);
  EXPECT_EQ(r.work.bytes_written, 4 * r.work.texels_rendered);
  EXPECT_EQ(r.work.texels_rendered % (128u * 128u), 0u);  // whole faces (no guard: pcf=1)
  EXPECT_GT(r.work.activation_bytes, uint64_t(72 * 40 * 5 * 4));  // at least input and output
  EXPECT_EQ(r.work.bytes_touched(),
            r.work.bytes_written + r.work.bytes_read + r.work.activation_bytes);
  EXPECT_GT(r.network_ms, 0.0);
  EXPECT_DOUBLE_EQ(r.lookup_ms, r.features_ms + r.network_ms);  // one repeat: no medians mixed
  std::filesystem::remove(path);
}

// The memory estimate (the registry's bytes, checked against the memory budget before a run):
// the base map plus the tensors the forward stores at the GBuffer's size, counted by hand for
// tiny (F = 4, C = {4, 8}, L = 3) at 72 × 40 (levels of 2880, 720 and 180 pixels): the input
// and output planes 2880·(4 + 1), the pooled outputs 720·4 and 180·8, the skip 720·8, the
// bottleneck 180·8 and the decoder's output 720·4, 4 B a value.
TEST(NsmTechnique, MemoryEstimateCountsTheStoredTensors) {
  const NsmwDraft d = test::nsmw_draft(tiny(), 3);
  const std::string path = save(d, "estimate.nsmw");
  const Scene s = scene_with_occluder();
  const GBuffer g = render_gbuffer(s);
  const uint64_t values = 2880 * 5 + 720 * 4 + 180 * 8 + 720 * 8 + 180 * 8 + 720 * 4;
  const uint64_t map = light_map_bytes(nsm_base_map_params(128), s);
  EXPECT_EQ(nsm_technique_bytes(parse_technique_spec("nsm:weights=" + path + ",res=128", "--technique"),
                                s, &g, "--technique"),
            map + 4 * values);
  std::filesystem::remove(path);
}

// The forward's per-pass figures (nsm_forward --layers) add up to its totals, pass by pass in
// the network's order: input, enc0, enc1, mid, dec1, dec0+head for tiny's 3 levels.
TEST(NsmTechnique, ForwardPassesAddUpToTheTotals) {
  const NsmwDraft d = test::nsmw_draft(tiny(), 9);
  const std::string path = save(d, "passes.nsmw");
  const NsmNetwork net = nsm_network(read_nsm_weights(path));
  const int w = 40, h = 24;
  std::vector<float> planes(size_t(w) * h * 4, 0.5f), out(size_t(w) * h);
  NsmForwardStats st;
  nsm_forward(net, planes.data(), w, h, out.data(), NsmPrecision::f32, &st);
  std::vector<std::string> names;
  double macs = 0;
  uint64_t written = 0;
  for (const NsmPassStats& p : st.passes) {
    names.push_back(p.name);
    macs += p.macs;
    written += p.bytes_written;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"input", "enc0", "enc1", "mid", "dec1", "dec0+head"}));
  EXPECT_EQ(macs, st.macs);
  EXPECT_EQ(written, st.activation_bytes);
  // enc1 reads pool0: 20 × 12 pixels of C0 = 4 channels; mid runs 9·8·16 + 16·8 MACs at 10 × 6.
  EXPECT_EQ(st.passes[2].bytes_read, uint64_t(20 * 12 * 4 * 4));
  EXPECT_EQ(st.passes[3].macs, double(10 * 6) * (9 * 8 * 16 + 16 * 8));
  std::filesystem::remove(path);
}

TEST(NsmTechnique, SameBytesAt1And2And7Threads) {
  const NsmwDraft d = test::nsmw_draft(tiny(), 7);
  const std::string path = save(d, "threads.nsmw");
  const Scene s = scene_with_occluder();
  const GBuffer g = render_gbuffer(s);
  std::vector<float> first;
  const int before = thread_count();
  for (int t : {1, 2, 7}) {
    set_thread_count(t);
    const ShadowResult r = run("nsm:weights=" + path + ",res=256,precision=f16", s, g);
    if (first.empty()) first = r.mask.data;
    ASSERT_EQ(std::memcmp(first.data(), r.mask.data.data(), first.size() * 4), 0) << t;
  }
  set_thread_count(before);
  std::filesystem::remove(path);
}

TEST(NsmTechnique, RefusesMissingWeightsUnknownFeaturesAndBadKeys) {
  const Scene s = scene_with_occluder();
  auto message = [&](const std::string& spec) {
    try {
      validate_technique_for_scene(parse_technique_spec(spec, "--technique"), s, "--technique");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string missing = temp_file("missing.nsmw");
  EXPECT_NE(message("nsm:weights=" + missing).find(missing), std::string::npos);
  NsmwDraft d = test::nsmw_draft(tiny(), 8);
  d.header["features"] = {"z_over_zf", "z_minus_zf", "c_e_r", "albedo"};
  const std::string unknown = save(d, "unknown.nsmw");
  const std::string m = message("nsm:weights=" + unknown);
  EXPECT_NE(m.find(unknown), std::string::npos) << m;
  EXPECT_NE(m.find("'albedo'"), std::string::npos) << m;
  EXPECT_NE(message("nsm:weights=").find("expected key=value"), std::string::npos);
  EXPECT_NE(message("nsm:precision=f8").find("precision"), std::string::npos);
  EXPECT_NE(message("nsm:res=32").find("res"), std::string::npos);
  EXPECT_NE(message("nsm:levels=3").find("levels"), std::string::npos);
  std::filesystem::remove(unknown);
}

}  // namespace nsm_technique_test
}  // namespace shadowlab
