#include "lab/flicker_run.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include "core/error.h"
#include "core/repeats.h"
#include "core/rng.h"
#include "lab/contact_sheet.h"
#include "lab/view_check.h"
#include "raster/gbuffer_pass.h"
#include "techniques/registry/technique.h"

namespace shadowlab {

const char* flicker_path_name(FlickerPath p) {
  switch (p) {
    case FlickerPath::LightLine: return "light-line";
    case FlickerPath::LightCircle: return "light-circle";
    case FlickerPath::LightJitter: return "light-jitter";
    case FlickerPath::CameraPan: return "camera-pan";
  }
  return "?";
}

FlickerPath parse_flicker_path(const std::string& name, const char* flag) {
  for (FlickerPath p : {FlickerPath::LightLine, FlickerPath::LightCircle, FlickerPath::LightJitter,
                        FlickerPath::CameraPan})
    if (name == flicker_path_name(p)) return p;
  throw InputError(flag, "unknown path '" + name +
                             "' (known: light-line, light-circle, light-jitter, camera-pan)");
}

namespace {

bool light_path(FlickerPath p) { return p != FlickerPath::CameraPan; }

// Distance from the light to the camera target (metres), at least 1 mm.
double light_target_distance(const Scene& s) {
  return std::max(1e-3, double(glm::length(s.camera.target - s.light.position)));
}

// The line's direction: horizontal and perpendicular to the light–target direction (world x
// when that direction is vertical).
vec3 line_direction(const Scene& s) {
  const vec3 to = s.camera.target - s.light.position;
  const vec3 d = glm::cross(to, vec3(0.0f, 1.0f, 0.0f));
  const float len = glm::length(d);
  return len > 1e-6f * std::max(1.0f, glm::length(to)) ? d / len : vec3(1.0f, 0.0f, 0.0f);
}

vec3 camera_right(const Camera& cam) {
  const vec3 f = glm::normalize(cam.target - cam.eye);
  return glm::normalize(glm::cross(f, cam.up));
}

std::string with_res(const std::string& text, int res) {
  TechniqueSpec s = parse_technique_spec(text, "--techniques");
  s.params["res"] = std::to_string(res);
  return spec_text(s);
}

std::string reference_spec(const FlickerConfig& c) { return "rt:spp=" + std::to_string(c.spp); }

// One technique run's mask on a frame's scene.
ImageF frame_mask(const Scene& frame, const std::string& spec, const GBuffer& g) {
  RunOptions opt;
  opt.want_texels = false;
  opt.flag = "--techniques";
  return run_technique(parse_technique_spec(spec, "--techniques"), frame, g, opt).mask;
}

// |a − b| per pixel.
ImageF abs_difference(const ImageF& a, const ImageF& b) {
  ImageF d(a.width, a.height);
  for (size_t i = 0; i < d.data.size(); ++i) d.data[i] = std::fabs(a.data[i] - b.data[i]);
  return d;
}

// Per-row running sums.
struct Acc {
  double change = 0.0, ref_change = 0.0, flips = 0.0, pairs = 0.0;
  std::vector<double> frame_excess;  // per frame t (index t − 1)
};

// Frame t's differences of mask m against the previous one, with the reference's, over the
// pixels covered in both GBuffers, added to acc (pixel order: deterministic).
void accumulate(const ImageF& prev, const ImageF& cur, const ImageF& ref_prev, const ImageF& ref_cur,
                const GBuffer& g_prev, const GBuffer& g_cur, Acc& acc) {
  double change = 0.0, ref_change = 0.0, flips = 0.0, n = 0.0;
  for (size_t i = 0; i < cur.pixel_count(); ++i) {
    if (!g_prev.covered[i] || !g_cur.covered[i]) continue;
    n += 1.0;
    change += std::fabs(double(cur.data[i]) - double(prev.data[i]));
    ref_change += std::fabs(double(ref_cur.data[i]) - double(ref_prev.data[i]));
    const bool flips_here = (cur.data[i] >= 0.5f) != (prev.data[i] >= 0.5f);
    const bool ref_flips = (ref_cur.data[i] >= 0.5f) != (ref_prev.data[i] >= 0.5f);
    if (flips_here && !ref_flips) flips += 1.0;
  }
  acc.change += change;
  acc.ref_change += ref_change;
  acc.flips += flips;
  acc.pairs += n;
  acc.frame_excess.push_back(n > 0.0 ? (change - ref_change) / n : 0.0);
}

struct RowPlan {
  std::string spec, technique;
  int res = 0;
  double snap = 0.0;
};

std::vector<RowPlan> plan_rows(const Scene& scene, const FlickerConfig& c) {
  std::vector<RowPlan> rows;
  for (const std::string& t : c.techniques) {
    if (parse_technique_spec(t, "--techniques").name == "rt") {
      // The reference itself, one row: its excess is 0 by definition (a check of the sums).
      RowPlan r;
      r.spec = reference_spec(c);
      r.technique = "rt";
      rows.push_back(r);
      continue;
    }
    for (int res : c.resolutions) {
      RowPlan r;
      r.spec = with_res(t, res);
      r.technique = spec_text(parse_technique_spec(t, "--techniques"));
      r.res = res;
      rows.push_back(r);
      if (c.jitter) {
        r.snap = flicker_snap(scene, res);
        rows.push_back(r);
      }
    }
  }
  return rows;
}

}  // namespace

double flicker_snap(const Scene& base, int res) {
  return 2.0 * light_target_distance(base) / double(std::max(1, res));
}

double flicker_default_step(const Scene& scene, const FlickerConfig& c) {
  if (light_path(c.path)) {
    const int max_res = *std::max_element(c.resolutions.begin(), c.resolutions.end());
    return 0.25 * flicker_snap(scene, max_res);
  }
  const Camera& cam = scene.camera;
  const double d = std::max(1e-3, double(glm::length(cam.target - cam.eye)));
  const double pixel = 2.0 * d * std::tan(double(cam.fov_y_deg) * M_PI / 360.0) / double(cam.height);
  return 0.25 * pixel;
}

Scene flicker_frame_scene(const Scene& base, const FlickerConfig& c, double step, int frame,
                          double snap) {
  Scene s = base;
  const double t = double(frame) * step;
  if (c.path == FlickerPath::CameraPan) {
    const vec3 shift = camera_right(base.camera) * float(t);
    s.camera.eye += shift;
    s.camera.target += shift;
    return s;
  }
  vec3 p = base.light.position;
  if (c.path == FlickerPath::LightJitter) {
    // Frame f's offset: each axis uniform in [−step, step) from a counter-based hash of (f, axis).
    for (int a = 0; a < 3; ++a)
      p[a] += float(step * (2.0 * double(rng_float(rng_hash(uint64_t(frame), 0, 0xf11c4e5ull, uint64_t(a)))) - 1.0));
  } else if (c.path == FlickerPath::LightLine) {
    p += line_direction(base) * float(t);
  } else {
    // A horizontal circle through the base position that closes after the N frames: radius
    // N·step/(2π), centred one radius away along the line direction's opposite.
    const double radius = double(c.frames) * step / (2.0 * M_PI);
    const double angle = radius > 0.0 ? t / radius : 0.0;
    const vec3 u = line_direction(base);
    const vec3 v = glm::normalize(glm::cross(u, vec3(0.0f, 1.0f, 0.0f)));
    const vec3 centre = base.light.position - u * float(radius);
    p = centre + u * float(radius * std::cos(angle)) + v * float(radius * std::sin(angle));
  }
  // The snap grid is anchored at the base position (any origin works; this one keeps the base
  // light exact, so a jitter below half a cell snaps to one position).
  if (snap > 0.0)
    for (int a = 0; a < 3; ++a) {
      const double o = double(base.light.position[a]);
      p[a] = float(o + std::round((double(p[a]) - o) / snap) * snap);
    }
  const vec3 moved = p - base.light.position;
  s.light.position = p;
  // The light's range grows by the path's reach, the same in every frame (a range per frame
  // would change every stored normalised distance from frame to frame).
  const double reach = c.path == FlickerPath::LightLine     ? double(c.frames - 1) * step
                       : c.path == FlickerPath::LightCircle ? double(c.frames) * step / M_PI
                                                            : std::sqrt(3.0) * step;
  s.light.far = float(double(base.light.far) + reach);
  if (s.projector.enabled) s.projector.position = base.projector.position + moved;
  return s;
}

void validate_flicker(const Scene& scene, const FlickerConfig& c) {
  if (c.techniques.empty()) throw InputError("--techniques", "no technique given");
  if (c.resolutions.empty()) throw InputError("--resolutions", "no resolution given");
  if (c.frames < 2) throw InputError("--frames", "needs at least 2 frames (a change needs two)");
  if (c.jitter && !light_path(c.path))
    throw InputError("--jitter", "texel snapping applies to the light paths: a point light's maps do not follow the camera");
  reject_repeats("--resolutions", c.resolutions);
  std::vector<TechniqueSpec> specs;
  for (const std::string& t : c.techniques) {
    const TechniqueSpec s = parse_technique_spec(t, "--techniques");
    specs.push_back(s);
    reject_repeated_specs("--techniques", specs, c.techniques);
    if (s.name == "rt") {
      if (!s.params.empty())
        throw InputError("--techniques", "rt is the reference (--spp sets its samples); give it without keys");
      continue;
    }
    if (s.params.count("res")) throw InputError("--techniques", "'" + t + "': give resolutions with --resolutions");
    for (int res : c.resolutions) {
      const TechniqueSpec full = parse_technique_spec(with_res(t, res), "--techniques");
      validate_technique(full, "--techniques");
      validate_technique_for_scene(full, scene, "--techniques");
    }
  }
  validate_technique(parse_technique_spec(reference_spec(c), "--spp"), "--spp");
}

FlickerResult measure_flicker(const Scene& scene, const FlickerConfig& c) {
  validate_flicker(scene, c);
  FlickerResult result;
  result.step = c.step >= 0.0 ? c.step : flicker_default_step(scene, c);
  const std::vector<RowPlan> plan = plan_rows(scene, c);
  std::vector<Acc> acc(plan.size());
  std::vector<ImageF> prev(plan.size());
  ImageF ref_prev;
  GBuffer g_prev, g;
  for (int f = 0; f < c.frames; ++f) {
    const Scene fs = flicker_frame_scene(scene, c, result.step, f);
    // The light paths keep the camera, so one GBuffer serves every frame.
    if (f == 0 || !light_path(c.path)) render_gbuffer(fs, g);
    if (f == 0) require_covered_view(fs, g);  // before the first reference
    const ImageF ref = frame_mask(fs, reference_spec(c), g);
    // The frame's scene once per snap grid (one per resolution with --jitter).
    std::map<double, Scene> snapped;
    for (const RowPlan& p : plan)
      if (p.snap > 0.0 && !snapped.count(p.snap))
        snapped.emplace(p.snap, flicker_frame_scene(scene, c, result.step, f, p.snap));
    for (size_t r = 0; r < plan.size(); ++r) {
      // The reference's own row is the reference (traced once per frame).
      ImageF m = plan[r].technique == "rt"
                     ? ref
                     : frame_mask(plan[r].snap > 0.0 ? snapped.at(plan[r].snap) : fs, plan[r].spec, g);
      if (f > 0) accumulate(prev[r], m, ref_prev, ref, light_path(c.path) ? g : g_prev, g, acc[r]);
      prev[r] = std::move(m);
    }
    ref_prev = ref;
    if (!light_path(c.path)) std::swap(g_prev, g);
  }
  for (size_t r = 0; r < plan.size(); ++r) {
    FlickerRow row;
    row.spec = plan[r].spec;
    row.technique = plan[r].technique;
    row.res = plan[r].res;
    row.snapped = plan[r].snap > 0.0;
    const Acc& a = acc[r];
    if (a.pairs > 0.0) {
      row.change = a.change / a.pairs;
      row.ref_change = a.ref_change / a.pairs;
      row.excess = (a.change - a.ref_change) / a.pairs;
      row.flip_share = a.flips / a.pairs;
    }
    const auto worst = std::max_element(a.frame_excess.begin(), a.frame_excess.end());
    row.worst_frame = int(worst - a.frame_excess.begin()) + 1;
    row.worst_excess = *worst;
    result.rows.push_back(row);
  }
  return result;
}

ImageF flicker_strip(const Scene& scene, const FlickerConfig& c, double step, const FlickerRow& row,
                     int count, int factor) {
  const int first = std::clamp(row.worst_frame - count / 2, 1, std::max(1, c.frames - count));
  const int last = std::min(c.frames - 1, first + count - 1);
  const double snap = row.snapped ? flicker_snap(scene, row.res) : 0.0;
  // The frame differences, technique's and reference's, then laid out as a labelled contact
  // sheet: the row labels say which strip is which.
  std::vector<ImageF> technique_diffs, reference_diffs;
  std::vector<std::string> col_labels;
  GBuffer g;
  ImageF m_prev, r_prev;
  for (int f = first - 1; f <= last; ++f) {
    const Scene fs = flicker_frame_scene(scene, c, step, f);
    render_gbuffer(fs, g);
    ImageF m = frame_mask(row.snapped ? flicker_frame_scene(scene, c, step, f, snap) : fs, row.spec, g);
    ImageF r = frame_mask(fs, reference_spec(c), g);
    if (f >= first) {
      technique_diffs.push_back(abs_difference(m, m_prev));
      reference_diffs.push_back(abs_difference(r, r_prev));
      col_labels.push_back("FRAME " + std::to_string(f));
    }
    m_prev = std::move(m);
    r_prev = std::move(r);
  }
  std::vector<std::vector<const ImageF*>> cells(2);
  for (size_t k = 0; k < technique_diffs.size(); ++k) {
    cells[0].push_back(&technique_diffs[k]);
    cells[1].push_back(&reference_diffs[k]);
  }
  std::string label = row.spec + (row.snapped ? " snapped" : "");
  for (char& ch : label) ch = char(std::toupper(static_cast<unsigned char>(ch)));
  ContactSheetStyle style;
  style.max_cell_width = (scene.camera.width + factor - 1) / factor;
  return contact_sheet({"TECHNIQUE " + label, "REFERENCE"}, col_labels, cells, nullptr, style);
}

}  // namespace shadowlab
