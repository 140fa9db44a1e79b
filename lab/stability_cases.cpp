#include "lab/stability_cases.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "scenes/mesh_builders.h"
#include "scenes/scene_library.h"
#include "raster/gbuffer_pass.h"
#include "techniques/registry/technique.h"

namespace shadowlab {
namespace {

constexpr int kW = 160, kH = 120;

Scene sized(Scene s) {
  s.camera.width = kW;
  s.camera.height = kH;
  return s;
}

struct Prepared {
  Scene scene;
  GBuffer g;
  ImageF reference;  // Embree hard shadows at the GBuffer points
};

Prepared prepare(Scene scene) {
  Prepared p;
  p.scene = std::move(scene);
  p.scene.light.radius = 0.0f;
  render_gbuffer(p.scene, p.g);
  RunOptions opt;
  p.reference = run_technique(parse_technique_spec("rt:hard=1", "stability"), p.scene, p.g, opt).mask;
  return p;
}

// Which measured value a bound applies to.
enum class Check { Mismatch, LitLoss, ShadowLeak, NonFinite };

// The bound in words, from the numbers checked: what the table prints and docs/programs/
// stability.md lists, so a bound and its words cannot disagree.
std::string bound_text(Check check, double bound, double leak_bound) {
  std::string s;
  switch (check) {
    case Check::Mismatch: s = fmt::format("mismatch <= {:g}%", 100.0 * bound); break;
    case Check::LitLoss:
      s = bound == 0.0 ? "no lit pixel lost" : fmt::format("lit pixels lost <= {:g}%", 100.0 * bound);
      break;
    case Check::ShadowLeak: s = fmt::format("leak in its shadow <= {:g}", bound); break;
    case Check::NonFinite: s = "finite"; break;
  }
  if (leak_bound < 1.0) s += fmt::format("; leak <= {:g}", leak_bound);
  return s;
}

// One row: `note` (optional) says why a row is measured without a bound or what to expect.
StabilityRow measure(const Prepared& p, const std::string& case_name, const std::string& setting,
                     const std::string& spec, Check check, double bound, double leak_bound = 1.0,
                     const std::string& note = "") {
  RunOptions opt;
  opt.want_texels = false;
  const ShadowResult r = run_technique(parse_technique_spec(spec, "stability"), p.scene, p.g, opt);
  StabilityRow row{case_name, setting, spec,
                   bound_text(check, bound, leak_bound) + (note.empty() ? "" : " (" + note + ")")};
  size_t covered = 0, lit = 0, shadow = 0, diff = 0, lost = 0;
  double leak = 0.0;
  for (size_t i = 0; i < p.g.pixel_count(); ++i) {
    const float m = r.mask.data[i];
    if (!std::isfinite(m) || m < 0.0f || m > 1.0f) {
      ++row.nonfinite;
      continue;
    }
    if (!p.g.covered[i]) continue;
    ++covered;
    const bool ref_lit = p.reference.data[i] > 0.5f;
    diff += (m > 0.5f) != ref_lit;
    if (ref_lit) {
      ++lit;
      lost += m < 0.5f;
    } else if (faces_light(p.g, i, p.scene.light.position)) {  // shadowed by an occluder
      ++shadow;
      leak += m;
    }
  }
  row.mismatch = covered ? double(diff) / double(covered) : 0.0;
  row.lit_loss = lit ? double(lost) / double(lit) : 0.0;
  row.shadow_leak = shadow ? leak / double(shadow) : 0.0;
  row.bound = bound;
  switch (check) {
    case Check::Mismatch: row.checked = row.mismatch; break;
    case Check::LitLoss: row.checked = row.lit_loss; break;
    case Check::ShadowLeak: row.checked = row.shadow_leak; break;
    case Check::NonFinite: row.checked = 0.0; break;
  }
  row.leak_bound = leak_bound;
  row.pass = row.nonfinite == 0 && row.checked <= bound && row.shadow_leak <= leak_bound;
  return row;
}


}  // namespace

std::vector<StabilityRow> run_stability_cases() {
  std::vector<StabilityRow> rows;
  const char* const filtered[] = {"cvsm", "tvsm", "cesm", "tesm"};

  // 1. ESM exponent from 1 to 500, on the default range (far 20 m) and on a 1e4 m range. The
  //    log-space filter must stay finite everywhere (the naive fp32 exp(c·z) overflows for
  //    c·z > 88.7, i.e. for every c >= 89 at the far end). Leaks shrink as c grows: at
  //    c >= 80 on the default range the mask agrees with the reference except at edges.
  {
    const Prepared def = prepare(sized(make_builtin_scene("default")));
    for (double c : {1.0, 10.0, 80.0, 200.0, 500.0})
      for (const char* t : {"cesm", "tesm"}) {
        const std::string spec = std::string(t) + ":res=512,c=" + fmt::format("{:g}", c);
        const bool sharp = c >= 80.0;
        rows.push_back(measure(def, "esm_exponent", "far=20 c=" + fmt::format("{:g}", c), spec,
                               sharp ? Check::Mismatch : Check::NonFinite, sharp ? 0.05 : 0.0,
                               sharp ? 0.1 : 1.0, sharp ? "" : "leaks expected at small c"));
      }
    Scene s = sized(make_builtin_scene("default"));
    s.light.far = 1e4f;
    const Prepared wide = prepare(s);
    for (const char* t : {"cesm", "tesm"})
      rows.push_back(measure(wide, "esm_exponent", "far=1e4 c=500", std::string(t) + ":res=512,c=500",
                             Check::NonFinite, 0.0, 1.0,
                             "c·Δd is 500× the occluder gap / 1e4: ESM leaks by design"));
  }

  // 1b. EVSM exponents from 5 to 44 (the largest whose e^(2c) fits float is 44.36; larger ones
  //     are rejected when parsed), 2 and 4 moments. The stored moments must stay finite up to
  //     the edge. Measured: mismatch 0.13-0.33 %, leak 0.025-0.057 in every row,
  //     c = 5 included (this scene's occluder gaps are large against the warp's spread); bounds
  //     about 3x that.
  {
    const Prepared def = prepare(sized(make_builtin_scene("default")));
    for (double c : {5.0, 20.0, 40.0, 44.0})
      for (int moments : {2, 4})
        for (const char* t : {"cevsm", "tevsm"})
          rows.push_back(measure(def, "evsm_exponent", fmt::format("c_pos={:g} m={}", c, moments),
                                 fmt::format("{}:res=512,moments={},c_pos={:g}", t, moments, c),
                                 Check::Mismatch, 0.01, 0.15));
  }

  // 1c. MSM moment bias α from 0 to 1e-2 (Hamburger and Hausdorff with fp32 moments, and
  //     Hamburger through the 16-bit quantization), on the default range and on a 1e3 m range
  //     (depths crowd near 0, so a footprint's spread is small against the stored moments'
  //     rounding). Measured: α = 0 loses 0.32-0.34 % of the lit pixels (acne where
  //     rounding leaves the Hankel matrix singular or indefinite) against 0.05-0.07 % at
  //     3e-7 <= α <= 1e-3; α = 1e-2 leaks 0.074-0.088 with Hamburger against 0.028-0.029 at
  //     3e-6 (Hausdorff, clipped to [0, 1], stays at 0.033); the 16-bit store leaks 0.08-0.12 on
  //     the 1e3 m range at any α. Bounds about 3x those.
  {
    Scene s = sized(make_builtin_scene("default"));
    const Prepared def = prepare(s);
    s.light.far = 1e3f;
    const Prepared wide = prepare(s);
    struct Variant {
      const char* label;
      const char* keys;
    };
    for (const Prepared* p : {&def, &wide})
      for (double a : {0.0, 3e-7, 3e-6, 3e-5, 1e-3, 1e-2})
        for (const Variant v : {Variant{"hamburger", ""}, Variant{"hausdorff", "variant=hausdorff,"},
                                Variant{"16-bit", "quantize16=1,"}}) {
          const bool q16 = v.keys[0] == 'q';
          const std::string setting =
              fmt::format("far={:g} {} alpha={:g}", p->scene.light.far, v.label, a);
          const std::string spec = fmt::format("cmsm:{}res=512,alpha={:g}", v.keys, a);
          if (a == 0.0 && !q16)
            rows.push_back(measure(*p, "msm_alpha", setting, spec, Check::LitLoss, 0.01, 0.1,
                                   "acne: lit loss ~5x the biased rows"));
          else if (q16)
            rows.push_back(measure(*p, "msm_alpha", setting, spec, Check::Mismatch, 0.015, 0.35));
          else if (a >= 1e-2)
            rows.push_back(measure(*p, "msm_alpha", setting, spec, Check::Mismatch, 0.01, 0.25,
                                   "leaks grow with alpha"));
          else
            rows.push_back(measure(*p, "msm_alpha", setting, spec, Check::Mismatch, 0.005, 0.12));
        }
  }

  // 2. VSM over light ranges: near/far from 1e-3 / 20 to 1e-3 / 1e4, and a tight far (1.01 ×
  //    the farthest receiver), where stored depths approach 1 and fp32 E[d²] − E[d]² cancels.
  //    The default (double filter, centred storage) must keep acne (lit pixels lost) under 1%
  //    and light bleeding (mean visibility over the reference's shadowed pixels) under 0.1 in
  //    every range: Chebyshev's bound leaks only where the occluder-receiver gap is small
  //    against the filtered spread, i.e. along the shadow edges. The fp32 form is measured
  //    alongside.
  {
    float farthest = 0.0f;
    {
      const Prepared def = prepare(sized(make_builtin_scene("default")));
      for (size_t i = 0; i < def.g.pixel_count(); ++i)
        if (def.g.covered[i])
          farthest = std::max(farthest, glm::length(def.g.position[i] - def.scene.light.position));
    }
    // The setting names the range the scene was given (the tight far to the centimetre).
    struct Range { float near, far; bool tight; };
    for (const Range& rg : {Range{1e-3f, 20.0f, false}, Range{0.05f, 1e4f, false}, Range{1e-3f, 1e4f, false},
                            Range{0.05f, 1.01f * farthest, true}}) {
      Scene s = sized(make_builtin_scene("default"));
      s.light.near = rg.near;
      s.light.far = rg.far;
      const Prepared p = prepare(s);
      const float near = p.scene.light.near, far = p.scene.light.far;
      const std::string range_name = rg.tight ? fmt::format("near={:g} tight far={:.2f}", near, far)
                                              : fmt::format("near={:g} far={:g}", near, far);
      for (const char* t : {"cvsm", "tvsm"}) {
        rows.push_back(measure(p, "vsm_range", range_name, std::string(t) + ":res=512", Check::LitLoss,
                               0.01, 0.1));
        rows.push_back(measure(p, "vsm_range", range_name, std::string(t) + ":res=512,fp32=1",
                               Check::NonFinite, 0.0, 1.0, "fp32 moments: measured, no bound"));
        rows.push_back(measure(p, "vsm_range", range_name, std::string(t) + ":res=512,min_variance=0",
                               Check::LitLoss, 0.01));
        rows.push_back(measure(p, "vsm_range", range_name,
                               std::string(t) + ":res=512,min_variance=0,fp32=1", Check::NonFinite,
                               0.0, 1.0, "fp32 moments: measured, no bound"));
      }
    }
  }

  // 3. Light 1 mm above an unoccluded floor (near plane 0.5 mm): every floor point is lit, at
  //    N·L from 1e-4 to 0.03. The default slope bias caps tan θ at 10 (N·L >= 0.1), so depth
  //    maps show acne there (measured, no bound); normal offset (normal=1) must remove it
  //    (<= 1% lost). Filtered maps need no bias.
  // 4. Grazing receivers: the floor at N·L between 0.009 and 0.026 (light 4 cm above it, the
  //    camera looking at the floor 2-4 m away): the same expectations.
  for (int grazing = 0; grazing < 2; ++grazing) {
    Scene s = sized(make_builtin_scene("plane"));
    if (grazing) {
      s.light.position = vec3(-4.0f, 0.04f, 0.0f);
      s.camera.eye = vec3(-1.0f, 3.0f, 0.0f);
      s.camera.target = vec3(-1.0f, 0.0f, 0.0f);
      s.camera.fov_y_deg = 40.0f;
    } else {
      s.light.position = vec3(0.3f, 0.001f, -0.2f);
      s.light.near = 5e-4f;
    }
    const Prepared p = prepare(s);
    const std::string name = grazing ? "grazing" : "light_1mm";
    // The setting is measured from the scene: the range of N·L over the floor's covered
    // pixels, or the light's height above the floor.
    std::string setting = fmt::format("h={:g}mm", 1000.0 * double(p.scene.light.position.y));
    if (grazing) {
      double lo = 1.0, hi = 0.0;
      for (size_t i = 0; i < p.g.pixel_count(); ++i)
        if (p.g.covered[i]) {
          const double nl = glm::dot(p.g.geo_normal[i], glm::normalize(p.scene.light.position - p.g.position[i]));
          lo = std::min(lo, nl);
          hi = std::max(hi, nl);
        }
      setting = fmt::format("N.L={:.3f}-{:.3f}", lo, hi);
    }
    for (const char* t : {"csm", "tsm"}) {
      rows.push_back(measure(p, name, setting, std::string(t) + ":res=1024", Check::NonFinite, 0.0, 1.0,
                             "acne expected: slope bias capped at N.L=0.1"));
      rows.push_back(measure(p, name, setting, std::string(t) + ":res=1024,normal=1",
                             Check::LitLoss, 0.01));
      // Receiver-plane depth bias: exact on a plane down to its cosine clamp (N·L >= 0.001).
      for (const char* k : {":res=1024,rpdb=1", ":res=1024,pcf=5,rpdb=1"}) {
        if (grazing)
          rows.push_back(measure(p, name, setting, std::string(t) + k, Check::LitLoss, 0.01));
        else
          rows.push_back(measure(p, name, setting, std::string(t) + k, Check::NonFinite, 0.0, 1.0,
                                 "acne expected: N.L below rpdb's clamp 0.001"));
      }
      rows.push_back(measure(p, name, setting, std::string(t) + ":res=1024,pcf=5", Check::NonFinite,
                             0.0, 1.0, "slope bias for PCF: acne where N.L < 0.1"));
    }
    // PCSS (rpdb by default) with the light 1 mm above the floor or grazing it: the search and
    // kernel radii are clamped to half a face; the plane finds no blocker, so the floor stays
    // lit (measured: 0.01-0.02 % lost at 1 mm, 0 grazing).
    for (const char* t : {"cpcss", "tpcss"})
      rows.push_back(measure(p, name, setting, std::string(t) + ":res=1024,light_size=0.1",
                             Check::LitLoss, 0.001));
    for (const char* t : filtered)
      rows.push_back(measure(p, name, setting, std::string(t) + ":res=1024", Check::LitLoss, 0.01));
  }

  // 4b. PCSS with a blocker touching the receiver: a 0.5 m box standing on the floor under the
  //     light (light radius 0.1 m from the spec, the reference hard). The penumbra shrinks to
  //     nothing at the contact, so the shadow stays attached; the 50 % contour keeps the hard
  //     edge's place (for a flat blocker parallel to the floor PCSS's penumbra is symmetric
  //     about it). Measured: mismatch 0.09-0.10 %, leak 0.051-0.053.
  {
    Scene s = sized(make_builtin_scene("plane"));
    add_box(new_mesh(s, "box", vec3(0.5f)),
            glm::translate(mat4(1.0f), vec3(0.6f, 0.25f, 0.3f)) * glm::scale(mat4(1.0f), vec3(0.5f)));
    s.camera.eye = vec3(2.5f, 2.0f, 2.0f);
    s.camera.target = vec3(0.6f, 0.0f, 0.3f);
    s.camera.fov_y_deg = 40.0f;
    const Prepared p = prepare(s);
    for (const char* t : {"cpcss", "tpcss"})
      rows.push_back(measure(p, "pcss_contact", "box on floor",
                             std::string(t) + ":res=1024,light_size=0.1", Check::Mismatch, 0.003,
                             0.15));
  }

  // 4c. DPSM with one triangle spanning the whole hemisphere below the light: a 2 km triangle
  //     1 m under the light (its corners 89.9° from the nadir, near the paraboloid's rim) over
  //     the plane scene's floor, which it shadows entirely; the camera looks at the floor from
  //     under it. Without tess the triangle's image is the chord triangle between three rim
  //     points and 1/r is interpolated linearly across it, far from the true 1/r ∝ (1 − ρ²)/
  //     (1 + ρ²): its stored distances come out far too large and the floor leaks. tess=N
  //     splits it until every image edge is at most N texels. Measured: without
  //     tess mismatch 68 %, leak 1.0 (the floor entirely lit); tess=64 and tess=8 mismatch 0,
  //     leak 0 (so does csm).
  {
    Scene s = sized(make_builtin_scene("plane"));
    Mesh big;
    big.name = "hemisphere_triangle";
    big.positions = {vec3(-1000.0f, 1.0f, 600.0f), vec3(1000.0f, 1.0f, 600.0f),
                     vec3(0.0f, 1.0f, -1150.0f)};
    big.normals = {vec3(0, 1, 0), vec3(0, 1, 0), vec3(0, 1, 0)};
    big.indices = {0, 1, 2};  // front +y, towards the light
    s.meshes.push_back(big);
    s.camera.eye = vec3(2.5f, 0.8f, 2.0f);
    s.camera.target = vec3(0.0f, 0.0f, 0.0f);
    s.camera.fov_y_deg = 50.0f;
    const Prepared p = prepare(s);
    rows.push_back(measure(p, "dpsm_hemisphere", "1 triangle", "dsm:res=1024", Check::NonFinite,
                           0.0, 1.0, "leaks expected: the floor comes out lit"));
    for (const char* spec : {"dsm:res=1024,tess=64", "dsm:res=1024,tess=8", "csm:res=1024"})
      rows.push_back(measure(p, "dpsm_hemisphere", "1 triangle", spec, Check::Mismatch, 0.005, 0.01));
  }

  // 5. A thin occluder: a pole 6 mm wide, 1.5-2.5 m from the light, about one texel of a 512
  //    cube face there (2/512 × 1.5 m = 5.9 mm per texel at the axis), over a floor 2 m below
  //    the light; the camera looks at its shadow 2.5-3.5 m out (a pixel is ~9 mm, the shadow
  //    ~1.4 cm wide). The pole's shadow is the only shadow in view (1.7 % of the image), so a
  //    bound on the mismatch alone cannot see the pole go missing; every row also bounds the
  //    leak, the mean visibility inside the reference's shadow, which is 1 without the pole.
  //    Measured leaks: csm 0.00, tsm 0.20, cvsm 0.33, cesm 0.34, tvsm 0.57,
  //    tesm 0.58 (filters thin a one-texel occluder; tetrahedral texels are coarser there).
  {
    Scene s = sized(make_builtin_scene("plane"));
    s.camera.eye = vec3(3.0f, 1.5f, 0.0f);
    s.camera.target = vec3(3.0f, 0.0f, 0.0f);
    s.camera.up = vec3(0.0f, 0.0f, -1.0f);
    s.camera.fov_y_deg = 40.0f;
    s.meshes.push_back(Mesh{});
    s.meshes.back().name = "pole";
    add_cylinder(s.meshes.back(), vec3(1.5f, 0.0f, 0.0f), 0.003f, 1.95f, 12);
    const Prepared p = prepare(s);
    rows.push_back(measure(p, "thin_occluder", "1 texel", "csm:res=512", Check::Mismatch, 0.03, 0.1));
    rows.push_back(measure(p, "thin_occluder", "1 texel", "tsm:res=512", Check::Mismatch, 0.03, 0.4));
    for (const char* t : filtered) {
      const bool cube = t[0] == 'c';
      rows.push_back(measure(p, "thin_occluder", "1 texel", std::string(t) + ":res=512",
                             Check::ShadowLeak, cube ? 0.5 : 0.75));
    }
  }

  // 6. Every face boundary and corner: a closed 4 m box around an off-centre light, with
  //    receivers on its walls in a dense Fibonacci set of directions (0.7° apart, about a texel
  //    of a res-256 map), leaving out points within 0.4 m of the box's own concave edges (where
  //    filtered maps darken legitimately). Everything is lit: no lit pixel may be lost.
  {
    BoxRoom room = make_box_room();
    Prepared p;
    p.scene = std::move(room.scene);
    p.g = std::move(room.g);
    RunOptions opt;
    p.reference = run_technique(parse_technique_spec("rt:hard=1", "stability"), p.scene, p.g, opt).mask;
    for (const char* spec : {"csm:res=256,pcf=5", "tsm:res=256,pcf=5", "cvsm:res=256,blur=7",
                             "tvsm:res=256,blur=7", "cesm:res=256,blur=7", "tesm:res=256,blur=7"})
      rows.push_back(measure(p, "face_boundaries", "box, 90k dirs", spec, Check::LitLoss, 0.0));
  }

  // 7. PCF and blur kernels reaching over face boundaries and map borders on an unoccluded
  //    floor at a coarse map: nothing may darken.
  {
    const Prepared p = prepare(sized(make_builtin_scene("plane")));
    for (const char* spec : {"csm:res=16,pcf=7", "tsm:res=16,pcf=7", "cvsm:res=16,blur=9",
                             "tvsm:res=16,blur=9", "cesm:res=16,blur=9", "tesm:res=16,blur=9"})
      rows.push_back(measure(p, "kernel_at_borders", "res=16", spec, Check::LitLoss, 0.0));
  }
  return rows;
}

std::string stability_table(const std::vector<StabilityRow>& rows) {
  std::string s = fmt::format("{:<18} {:<20} {:<30} {:>6} {:>8} {:>8} {:>8}  {:<6} {}\n", "case",
                              "setting", "spec", "nonfin", "mismatch", "lit lost", "leak",
                              "result", "expected");
  for (const StabilityRow& r : rows)
    s += fmt::format("{:<18} {:<20} {:<30} {:6} {:8.4f} {:8.4f} {:8.4f}  {:<6} {}\n", r.case_name,
                     r.setting, r.spec, r.nonfinite, r.mismatch, r.lit_loss, r.shadow_leak,
                     r.pass ? "ok" : "FAIL", r.expectation);
  return s;
}

}  // namespace shadowlab
