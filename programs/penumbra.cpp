// penumbra: the penumbra-width model (techniques/filters/pcss/penumbra_model.h) against penumbrae measured
// on the Embree soft reference (docs/techniques/pcss.md). Each case is a line of
// floor points crossing one shadow edge, from the shadow out into the light; the reference and
// PCSS (classic and estimate=model) are evaluated at exactly those points (a one-row GBuffer),
// and the 10 %–90 % transition of each profile (measured_transition) is compared with the
// model's (penumbra_transition). Cases: a sphere over a plane under the light (where the model's
// geometry is the scene's), and the default scene's pole and box edge, at light radii 0.03, 0.1
// and 0.3 m. Table on stdout; penumbra.csv in --out.
#include <array>
#include <cmath>
#include <map>
#include <cstdio>
#include <limits>

#include "core/error.h"
#include "core/output_file.h"
#include "lab/cli.h"
#include "lab/output_folder.h"
#include "lab/memory_check.h"
#include "scenes/mesh_builders.h"
#include "scenes/scene_library.h"
#include "techniques/filters/pcss/penumbra_model.h"
#include "techniques/registry/technique.h"

using namespace shadowlab;

namespace {

struct Case {
  std::string name;
  Scene scene;
  vec3 start, dir;  // the line: start (inside the shadow) + s·dir, s in [0, length], on the floor
  double length = 0.0;
  double inside = 0.0;  // the line starts this far into the shadow from `start`
  double edge_depth = 0.0;  // the occluder depth that sets the line's length (0: the model's z_m)
  vec3 centre;      // the model's axis: from the light through this point to the receiver
  double z_min = 0.0, z_max = 0.0;  // occluder depths along the axis, metres from the light
  std::string occluder;             // how z_min, z_max were chosen
};

// A one-row GBuffer of n floor points (normal +y) along the case's line.
GBuffer line_gbuffer(const Case& c, int n) {
  GBuffer g;
  g.resize(n, 1);
  for (int i = 0; i < n; ++i) {
    const float s = float(c.length * i / (n - 1));
    g.position[size_t(i)] = c.start + c.dir * s;
    g.normal[size_t(i)] = g.geo_normal[size_t(i)] = vec3(0.0f, 1.0f, 0.0f);
    g.depth[size_t(i)] = 1.0f;
    g.mesh_id[size_t(i)] = 0;
    g.prim_id[size_t(i)] = 0;
    g.covered[size_t(i)] = 1;
  }
  return g;
}

// Where the ray from the light through p meets the floor y = 0.
vec3 floor_hit(vec3 light, vec3 p) { return light + (p - light) * (light.y / (light.y - p.y)); }

// Entry and exit distances from `o` along unit `d` of the infinite vertical cylinder of radius
// r around (cx, ·, cz).
void cylinder_chord(vec3 o, vec3 d, float cx, float cz, float r, double& t0, double& t1) {
  const double ox = o.x - cx, oz = o.z - cz;
  const double a = double(d.x) * d.x + double(d.z) * d.z, b = 2.0 * (ox * d.x + oz * d.z);
  const double c = ox * ox + oz * oz - double(r) * r;
  const double q = std::sqrt(std::max(0.0, b * b - 4.0 * a * c));
  t0 = (-b - q) / (2.0 * a);
  t1 = (-b + q) / (2.0 * a);
}

std::vector<Case> make_cases(double radius) {
  std::vector<Case> cases;
  {
    // A sphere of radius 0.25 m centred 1 m above the plane scene's floor, the light 3 m above
    // the floor straight over it: z_f = 3, the sphere between depths 1.75 and 2.25.
    Case c;
    c.name = "sphere over a plane";
    c.scene = make_builtin_scene("plane");
    add_uv_sphere(new_mesh(c.scene, "ball", vec3(0.5f)), vec3(0.0f, 1.0f, 0.0f), 0.25f, 128, 64);
    c.scene.light.position = vec3(0.0f, 3.0f, 0.0f);
    c.centre = vec3(0.0f, 1.0f, 0.0f);
    c.z_min = 1.75;
    c.z_max = 2.25;
    c.start = vec3(0.0f);
    c.dir = vec3(1.0f, 0.0f, 0.0f);
    c.occluder = "the sphere (exact)";
    cases.push_back(c);
  }
  const Scene def = make_builtin_scene("default");
  const vec3 L = def.light.position;
  {
    // The pole (radius 0.035 m at x = -0.8, z = 0.5) at height 0.5 m: its shadow's centre S on
    // the floor, the line across the stripe; the occluder range is the chord of the ray L -> S
    // through the pole.
    Case c;
    c.name = "default: pole";
    c.scene = def;
    const vec3 p(-0.8f, 0.5f, 0.5f);
    const vec3 s = floor_hit(L, p);
    const vec3 along = glm::normalize(vec3(p.x - L.x, 0.0f, p.z - L.z));
    c.dir = vec3(-along.z, 0.0f, along.x);
    c.start = s;
    c.centre = p;
    const vec3 d = glm::normalize(s - L);
    cylinder_chord(L, d, -0.8f, 0.5f, 0.035f, c.z_min, c.z_max);
    c.occluder = "the ray's chord through the pole";
    cases.push_back(c);
  }
  for (int variant = 0; variant < 2; ++variant) {
    // The box (0.9 m, centre (-1.8, 0.45, -1.2), turned 30 deg about y): the midpoint E of the
    // top edge of its face turned away from the light (normal -x'), its shadow S on the floor,
    // the line from 0.6 m inside the shadow outward along -x'. Occluder range: the edge alone
    // (a thin occluder), or the whole box (its corners' nearest and farthest distance from the
    // light: what a blocker search over the box sees).
    Case c;
    c.name = variant == 0 ? "default: box edge" : "default: box as a sphere";
    c.scene = def;
    const float a = glm::radians(30.0f);
    const vec3 xp(std::cos(a), 0.0f, -std::sin(a)), zp(std::sin(a), 0.0f, std::cos(a));
    const vec3 top(-1.8f, 0.9f, -1.2f);
    const vec3 e = top - 0.45f * xp;
    const vec3 s = floor_hit(L, e);
    c.dir = -xp;
    c.start = s;
    c.inside = 0.6;
    c.centre = e;
    c.edge_depth = glm::length(e - L);  // both variants sample the same line
    if (variant == 0) {
      c.z_min = c.z_max = glm::length(e - L);
      c.occluder = "the edge (z_min = z_max)";
    } else {
      c.z_min = 1e30;
      c.z_max = 0.0;
      for (int i = 0; i < 8; ++i) {
        const vec3 corner = vec3(-1.8f, 0.45f, -1.2f) + 0.45f * ((i & 1 ? 1.0f : -1.0f) * xp +
                                                                 (i & 2 ? 1.0f : -1.0f) * vec3(0, 1, 0) +
                                                                 (i & 4 ? 1.0f : -1.0f) * zp);
        const double dist = glm::length(corner - L);
        c.z_min = std::min(c.z_min, dist);
        c.z_max = std::max(c.z_max, dist);
      }
      c.occluder = "the box's corner distances";
    }
    cases.push_back(c);
  }
  for (Case& c : cases) c.scene.light.radius = float(radius);
  return cases;
}

}  // namespace

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("penumbra", "[flags]");
    CommonOptions common;
    add_common_options(cl, common);
    std::vector<std::string> unused;
    for (const std::string& n : common_scene_flags())
      if (n != "--out") unused.push_back(n);
    mark_unused(cl, unused, "the cases fix their scenes, lights and receiver lines");
    std::vector<double> radii{0.03, 0.1, 0.3};
    int spp = 4096, points = 800, res = 2048;
    add_double_list(cl, "--radii", "LIST", "light radii, metres (default 0.03,0.1,0.3)", radii, 1e-4, 1.0);
    add_int(cl, "--spp", "N", "reference samples per point (default 4096)", spp, 16, 1 << 20);
    add_int(cl, "--points", "N", "points per line (default 800)", points, 16, 100000);
    add_int(cl, "--res", "N", "PCSS map resolution (default 2048)", res, 64, 4096);
    if (!parse_command_line(cl, argc, argv)) return 0;
    // Checked before any work: the reference's rays per profile, and PCSS's map.
    if (uint64_t(points) * uint64_t(spp) > (uint64_t(1) << 31))
      throw InputError("--spp", std::to_string(points) + " points x " + std::to_string(spp) +
                                    " samples is over 2^31 rays per profile");
    check_run_memory(make_builtin_scene("default"),
                     {parse_spec("cpcss:res=" + std::to_string(res), "--res")}, 0);
    RunOutputs outputs(common.out, "--out");
    outputs.check_names({"penumbra.csv"});
    std::printf("%-26s %6s %8s %8s %8s | %8s %8s %7s | %8s %8s\n", "case", "R m", "model", "x_a",
                "x_b", "measured", "model", "error", "pcss", "pcss:mod");
    std::string csv = "case,radius,z_f,z_min,z_max,x_a,x_b,model_full,model_1090,measured_1090,rel_error,pcss_1090,pcss_model_1090,occluder\n";
    std::map<std::string, std::array<PenumbraTransition, 3>> measured;  // reference, PCSS, PCSS model
    for (double radius : radii)
      for (Case c : make_cases(radius)) {
        const vec3 L = c.scene.light.position;
        // The model in the frame of its axis: z_f from the light to the axis's floor point.
        const vec3 axis_floor = floor_hit(L, c.centre);
        const double z_f = glm::length(axis_floor - L);
        const PenumbraModel m = penumbra_model(radius, z_f, c.z_min, c.z_max);
        const PenumbraTransition pt = penumbra_transition(m, radius, z_f);
        // The model's lateral distances are across its axis; the floor line's step δ·dir moves
        // a point across the axis (projected along it, as the light's rays run) by
        // δ·√(1 − (dir·axis)²), so a width w across the axis is w/√(1 − (dir·axis)²) along the
        // line (1 for the sphere and the pole, whose lines cross the axis at right angles). The
        // tilt of the floor against the model's receiver plane is ignored (second order).
        const vec3 ax = glm::normalize(axis_floor - L);
        const double cos_da = double(glm::dot(ax, c.dir));
        const double to_floor = 1.0 / std::sqrt(std::max(1e-12, 1.0 - cos_da * cos_da));
        // Sample from the line's start (the shadow's centre, or inside it) past the edge by 3
        // classic widths 2R·(z_f − z_m)/z_m (the sphere's and the pole's edges end at x_b).
        const double zd = c.edge_depth > 0.0 ? c.edge_depth : m.z_m;
        const double classic_w = 2.0 * radius * (z_f - zd) / zd * to_floor;
        const double edge_at = c.inside > 0.0 ? c.inside : std::max(0.0, m.x_b) * to_floor;
        c.start -= c.dir * float(c.inside);
        c.length = edge_at + 3.0 * classic_w + 0.05;
        const GBuffer g = line_gbuffer(c, points);
        RunOptions opt;
        opt.want_texels = false;
        auto profile = [&](const std::string& spec) {
          const ImageF mask = run_technique(parse_spec(spec, "--spp"), c.scene, g, opt).mask;
          std::vector<double> x(static_cast<size_t>(points)), v(static_cast<size_t>(points));
          for (int i = 0; i < points; ++i) {
            x[size_t(i)] = c.length * i / (points - 1);
            v[size_t(i)] = mask.data[size_t(i)];
          }
          return measured_transition(x.data(), v.data(), points);
        };
        // The box's two variants share their line: its profiles are measured once.
        const std::string line_key = std::to_string(radius) + " " + std::to_string(c.start.x) + " " +
                                     std::to_string(c.start.z) + " " + std::to_string(c.length);
        if (!measured.count(line_key)) {
          const std::string pcss = "cpcss:res=" + std::to_string(res) + ",taps=128,search=64";
          measured[line_key] = {profile("rt:spp=" + std::to_string(spp)), profile(pcss),
                                profile(pcss + ",estimate=model")};
        }
        const auto& [ref, classic, model] = measured[line_key];
        const double predicted = pt.width * to_floor;
        // A profile that never reaches its 90 % level (a line too short for its transition)
        // has no width: n/a in the table, NaN in the CSV, never a match.
        const double nan = std::numeric_limits<double>::quiet_NaN();
        auto width_of = [&](const PenumbraTransition& t) { return t.width > 0.0 ? t.width : nan; };
        const double rel = ref.width > 0.0 ? (predicted - ref.width) / ref.width : nan;
        auto cell = [](double v, const char* fmt) {
          char b[32];
          if (std::isnan(v)) return std::string("n/a");
          std::snprintf(b, sizeof b, fmt, v);
          return std::string(b);
        };
        std::printf("%-26s %6.3f %8.4f %8.4f %8.4f | %8s %8.4f %7s | %8s %8s\n", c.name.c_str(),
                    radius, m.width * to_floor, m.x_a, m.x_b, cell(width_of(ref), "%.4f").c_str(),
                    predicted, cell(100.0 * rel, "%+.1f%%").c_str(),
                    cell(width_of(classic), "%.4f").c_str(), cell(width_of(model), "%.4f").c_str());
        char line[1024];
        std::snprintf(line, sizeof line, "\"%s\",%g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,\"%s\"\n",
                      c.name.c_str(), radius, z_f, c.z_min, c.z_max, m.x_a, m.x_b, m.width * to_floor,
                      predicted, width_of(ref), rel, width_of(classic), width_of(model),
                      c.occluder.c_str());
        csv += line;
      }
    write_text_file(outputs.dir() + "/penumbra.csv", csv);
    outputs.commit();
    std::printf("widths in metres along each floor line (model: x_a + x_b, then its 10-90 %% transition); "
                "wrote %s/penumbra.csv\n", common.out.c_str());
    return 0;
  });
}
