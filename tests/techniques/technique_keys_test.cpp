// Every declared key of every technique against what parsing does: the declared range is exactly
// what validation accepts (each end accepted, one step beyond refused), the declared default is
// accepted and equals leaving the key out, and a spec's messages are the ones its keys' order
// and rules give.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parse_number.h"
#include "techniques/pipeline/map_filter.h"
#include "techniques/pipeline/map_params.h"
#include "techniques/nsm/nsm_technique.h"
#include "techniques/rt/ray_traced.h"
#include "techniques/rt/rt_denoised.h"
#include "techniques/registry/technique.h"

namespace shadowlab {
namespace {

// The naming rule: a layout letter + the suffix of a filter of map_filters().
bool layout_filter(const std::string& name, FaceLayoutKind& layout, MapFilter& filter) {
  const std::pair<char, FaceLayoutKind> layouts[] = {{'c', FaceLayoutKind::Cube},
                                                     {'t', FaceLayoutKind::Tetrahedron},
                                                     {'p', FaceLayoutKind::Projector},
                                                     {'d', FaceLayoutKind::DualParaboloid}};
  bool found_layout = false, found_filter = false;
  for (const auto& [c, l] : layouts)
    if (name[0] == c) layout = l, found_layout = true;
  for (const MapFilterOps* f : map_filters())
    if (name.substr(1) == f->suffix) filter = f->id, found_filter = true;
  return found_layout && found_filter;
}

// Every field parsing sets, as text: two specs mean the same when these agree.
std::string params_text(const std::string& name, const std::string& spec_text) {
  const TechniqueSpec spec = parse_technique_spec(spec_text, "t");
  if (name == "rt") {
    const RayTracedParams p = parse_ray_traced(spec, "t");
    return std::to_string(p.spp) + " " + std::to_string(p.hard) + " " + std::to_string(p.seed);
  }
  if (name == "rts") {
    const RtDenoisedParams p = parse_rt_denoised(spec, "t");
    char buf[256];
    std::snprintf(buf, sizeof buf, "%d %d %d %.9g %d %.9g %d %d", p.spp, int(p.denoise),
                  p.atrous.iterations, double(p.atrous.sigma_z), p.atrous.normal_power,
                  double(p.atrous.sigma_v), int(p.hard), p.seed);
    return buf;
  }
  if (name == "nsm") {
    const NsmParams p = parse_nsm(spec, "t");
    return p.weights + " " + std::to_string(p.res) + " " + std::to_string(int(p.layout)) + " " +
           std::to_string(int(p.precision));
  }
  FaceLayoutKind layout{};
  MapFilter filter{};
  if (!layout_filter(name, layout, filter)) ADD_FAILURE() << name;
  const MapParams p = parse_map_params(spec, layout, filter, "t");
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "res=%d depth=%d bias=%.9g slope=%.9g normal=%.9g pcf=%d kind=%d taps=%d rpdb=%d "
                "seams=%d tess=%d blur=%d vsm=%.17g,%.17g,%.17g,%d,%d esm=%.17g "
                "evsm=%d,%.17g,%.17g,%.17g,%.17g msm=%d,%d,%.17g pcss=%.17g,%d,%d,%.17g,%d",
                p.res, int(p.depth), double(p.bias), double(p.slope), double(p.normal), p.pcf,
                int(p.pcf_kind), p.taps, int(p.rpdb), int(p.seams), p.tess, p.blur,
                p.vsm.min_variance, p.vsm.bleed, p.vsm.maxdepth_eps, int(p.vsm.slope_moment),
                int(p.vsm.fp32), p.esm.c, p.evsm.moments, p.evsm.c_pos, p.evsm.c_neg,
                p.evsm.min_variance, p.evsm.bleed, int(p.msm.hausdorff), int(p.msm.quantize16),
                p.msm.alpha, p.pcss.light_size, p.pcss.search, p.pcss.taps, p.pcss.search_near,
                int(p.pcss.model));
  return buf;
}

// "" when the spec validates, else the InputError's message.
std::string refusal(const std::string& spec_text) {
  try {
    validate_technique(parse_technique_spec(spec_text, "--technique"), "--technique");
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

// A number as spec text: shortest round trip, no '+' (specs refuse it).
std::string value_text(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  std::string s = buf;
  if (const size_t plus = s.find('+'); plus != std::string::npos) s.erase(plus, 1);
  return s;
}

// Keys some other key's rule constrains: what the spec needs beside them for the key alone to
// decide (Poisson taps, and so pcf_kind=poisson, need pcf >= 3; an explicit slope is refused where rpdb=1 is the default).
std::string context_for(const KeyInfo& k, const std::vector<KeyInfo>& keys) {
  std::string c = k.needs;
  if ((k.name == "taps" && k.needs == "pcf_kind=poisson") || k.name == "pcf_kind")
    c += std::string(c.empty() ? "" : ",") + "pcf=3";
  bool has_rpdb = false;
  for (const KeyInfo& o : keys) has_rpdb |= o.name == "rpdb";
  if (k.name == "slope" && has_rpdb) c += std::string(c.empty() ? "" : ",") + "rpdb=0";
  return c;
}

std::string spec_with(const std::string& name, const std::string& context, const std::string& key,
                      const std::string& value) {
  return name + ":" + (context.empty() ? "" : context + ",") + key + "=" + value;
}

TEST(TechniqueKeys, DeclaredRangesAreWhatParsingAccepts) {
  size_t checked = 0;
  for (const auto& entry : technique_list()) {
    const std::string name = entry.first;  // a plain variable: lambdas below capture it
    const std::vector<KeyInfo> keys = technique_keys(name, "t");
    ASSERT_FALSE(keys.empty()) << name;
    for (const KeyInfo& k : keys) {
      const std::string ctx = context_for(k, keys);
      auto accepted = [&](const std::string& v) {
        const std::string s = spec_with(name, ctx, k.name, v);
        const std::string why = refusal(s);
        EXPECT_EQ(why, "") << s;
      };
      auto refused = [&](const std::string& v) {
        const std::string s = spec_with(name, ctx, k.name, v);
        EXPECT_NE(refusal(s), "") << s << " was accepted";
      };
      if (k.text) {  // a file: the default names a file that exists, another name none
        accepted(k.def);
        refused("no_such_file_here.nsmw");
        ++checked;
        continue;
      }
      std::string range = k.range;
      std::string word;
      if (const size_t o = range.find(" or "); o != std::string::npos) {
        word = range.substr(o + 4);
        range = range.substr(0, o);
        accepted(word);
      }
      if (range.front() == '[') {  // a number in [lo, hi]
        double lo = 0, hi = 0;
        ASSERT_EQ(std::sscanf(range.c_str(), "[%lf, %lf]", &lo, &hi), 2) << name << " " << range;
        const double eps_lo = std::max(std::fabs(lo) * 1e-6, 1e-9);
        const double eps_hi = std::max(std::fabs(hi) * 1e-6, 1e-9);
        accepted(value_text(lo));
        accepted(value_text(hi));
        refused(value_text(lo - eps_lo));
        refused(value_text(hi + eps_hi));
      } else if (range.find("..") != std::string::npos) {  // an integer lo..hi
        long lo = 0, hi = 0;
        ASSERT_EQ(std::sscanf(range.c_str(), "%ld..%ld", &lo, &hi), 2) << name << " " << range;
        accepted(std::to_string(lo));
        accepted(std::to_string(hi));
        refused(std::to_string(lo - 1));
        refused(std::to_string(hi + 1));
      } else {  // a choice (a flag is the choice 0|1)
        for (size_t at = 0; at <= range.size();) {
          const size_t bar = std::min(range.find('|', at), range.size());
          accepted(range.substr(at, bar - at));
          at = bar + 1;
        }
        refused("bogus");
        refused("3");
      }
      // The declared default is accepted and means the same as leaving the key out.
      EXPECT_EQ(params_text(name, spec_with(name, ctx, k.name, k.def)),
                params_text(name, ctx.empty() ? name : name + ":" + ctx))
          << name << " " << k.name << "=" << k.def;
      ++checked;
    }
  }
  EXPECT_GT(checked, 200u);  // 24 light-map techniques × 6..11 keys + rt's 3 + nsm's 3
}

// A key that needs another key's word is unknown without it.
TEST(TechniqueKeys, KeysThatNeedAWordAreUnknownWithoutIt) {
  EXPECT_EQ(refusal("csm:taps=8"),
            "--technique: csm: unknown parameter 'taps' (known: res, bias, slope, normal, depth, "
            "pcf, pcf_kind, rpdb, seams)");
  EXPECT_EQ(refusal("csm:pcf=3,pcf_kind=poisson,taps=8"), "");
}

// Messages follow the declared reading order: the first bad key read is the one named, and each
// key's rule is checked as the key is read.
TEST(TechniqueKeys, MessagesFollowTheReadingOrder) {
  EXPECT_EQ(refusal("csm:pcf=2,pcf_kind=bogus"), "--technique: csm: 'pcf' must be 1 or odd, got 2");
  EXPECT_EQ(refusal("csm:pcf=1,pcf_kind=poisson,taps=1000"),
            "--technique: csm: 'taps' = 1000 is outside [4, 64]");
  EXPECT_EQ(refusal("csm:pcf=1,pcf_kind=poisson,taps=8"),
            "--technique: csm: 'pcf_kind=poisson' needs pcf >= 3 (the disk's diameter in texels)");
  EXPECT_EQ(refusal("tsm:pcf=3,pcf_kind=poisson,seams=cross"),
            "--technique: tsm: 'seams=cross' serves the grid PCF only; Poisson taps use the guard band");
  EXPECT_EQ(refusal("csm:rpdb=1,slope=2"),
            "--technique: csm: 'rpdb=1' replaces the slope bias; drop 'slope' or set it to 0");
  EXPECT_EQ(refusal("cevsm:c_pos=50,c_neg=1e5"),
            "--technique: cevsm: 'c_pos' = 50 overflows the stored moments: e^(2c) exceeds "
            "float's range above c = 44.36");
  EXPECT_EQ(refusal("cevsm:c_neg=2e4"), "--technique: cevsm: 'c_neg' = 2e4 is outside [0.01, 10000]");
  EXPECT_EQ(refusal("cvsm:blur=4"), "--technique: cvsm: 'blur' must be odd, got 4");
  // light_size is read as its word, then as a number: the reader lists it twice.
  EXPECT_EQ(refusal("cpcss:light_size=2,x=1"),
            "--technique: cpcss: unknown parameter 'x' (known: res, bias, slope, normal, depth, "
            "light_size, light_size, search, taps, search_near, estimate, rpdb)");
  const std::string tess = refusal("dsm:res=4096,tess=1");
  EXPECT_EQ(tess.rfind("--technique: dsm: 'tess=1' at res=4096 would split each face into ~", 0), 0u) << tess;
  EXPECT_NE(tess.find("M triangles (limit 32M): raise tess or lower res"), std::string::npos) << tess;
}

// Defaults that depend on other keys: msm's alpha with quantize16, the cube depth compare's
// seams with Poisson taps or rpdb.
TEST(TechniqueKeys, DependentDefaults) {
  auto msm = [](const std::string& s) {
    return parse_map_params(parse_technique_spec(s, "t"), FaceLayoutKind::Cube, MapFilter::Moment, "t");
  };
  EXPECT_EQ(msm("cmsm").msm.alpha, 3e-6);
  EXPECT_EQ(msm("cmsm:quantize16=1").msm.alpha, 3e-5);
  EXPECT_EQ(msm("cmsm:quantize16=1,alpha=1e-4").msm.alpha, 1e-4);
  auto sm = [](const std::string& s, FaceLayoutKind l) {
    return parse_map_params(parse_technique_spec(s, "t"), l, MapFilter::Depth, "t");
  };
  EXPECT_EQ(sm("csm", FaceLayoutKind::Cube).seams, SeamMode::Cross);
  EXPECT_EQ(sm("csm:rpdb=1", FaceLayoutKind::Cube).seams, SeamMode::Guard);
  EXPECT_EQ(sm("csm:pcf=3,pcf_kind=poisson", FaceLayoutKind::Cube).seams, SeamMode::Guard);
  EXPECT_EQ(sm("tsm", FaceLayoutKind::Tetrahedron).seams, SeamMode::Guard);
  const MapParams pcss = default_map_params(FaceLayoutKind::Cube, MapFilter::Pcss);
  EXPECT_TRUE(pcss.rpdb);
  EXPECT_EQ(pcss.slope, 0.0f);
  EXPECT_EQ(pcss.bias, 0.01f);
  EXPECT_LT(pcss.pcss.light_size, 0.0);  // the scene light's radius
  const MapParams vsm = default_map_params(FaceLayoutKind::Cube, MapFilter::Variance);
  EXPECT_EQ(vsm.bias, 0.0f);
  EXPECT_EQ(vsm.slope, 0.0f);
  EXPECT_EQ(vsm.blur, 3);
}

}  // namespace
}  // namespace shadowlab
