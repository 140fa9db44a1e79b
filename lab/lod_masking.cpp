#include "lab/lod_masking.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "scenes/bunny_scene.h"
#include "core/error.h"
#include "core/repeats.h"
#include "core/gbuffer_shading.h"
#include "core/image_io.h"
#include "scenes/mesh_lod.h"
#include "core/output_file.h"
#include "scenes/scene_library.h"
#include "core/texture.h"
#include "core/timer.h"
#include "lab/view_check.h"
#include "lab/contact_sheet.h"
#include "metric/image_error.h"
#include "metric/ssim.h"
#include "raster/gbuffer_pass.h"
#include "techniques/shading/projector_shading.h"
#include "techniques/registry/technique.h"

namespace shadowlab {
namespace {

std::string level_label(size_t target) {
  return target == 0 ? "full" : std::to_string(target);
}

// Display values: sRGB-encoded luminance, clamped to [0, 1] (what a viewer sees).
ImageF display_encode(const ImageF& luma) {
  ImageF out = luma;
  for (float& v : out.data) v = linear_to_srgb(std::clamp(v, 0.0f, 1.0f));
  return out;
}

std::string file_safe(std::string s) {
  for (char& ch : s)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '.') ch = '_';
  return s;
}

}  // namespace

MaskingResult run_lod_masking(const Scene& base, const MaskingConfig& c) {
  SL_CHECK(base.projector.posed && base.meshes.size() > size_t(kBunnyMesh));
  std::vector<Slide> slides;
  for (const std::string& s : c.slides) slides.push_back(make_slide(s, "--slides"));
  if (slides.empty()) throw InputError("--slides", "needs at least one slide");
  const TechniqueSpec spec = parse_technique_spec(c.technique, "--technique");
  validate_technique(spec, "--technique");
  // The full mesh is the reference of every comparison: it always comes first.
  std::vector<size_t> levels = c.levels;
  levels.erase(std::remove(levels.begin(), levels.end(), size_t(0)), levels.end());
  // Each level once, and each below the full mesh: a target at or above its triangle count
  // would be the full mesh again, not a level of detail.
  reject_repeats("--levels", levels);
  const size_t full = base.meshes[kBunnyMesh].triangle_count();
  for (size_t target : levels)
    if (target >= full)
      throw InputError("--levels", std::to_string(target) + " is not below the mesh's " +
                                       std::to_string(full) +
                                       " triangles (the full mesh is always the reference)");
  levels.insert(levels.begin(), 0);

  MaskingResult out;
  out.width = base.camera.width;
  out.height = base.camera.height;
  out.slides = c.slides;
  std::vector<ImageF> reference(slides.size());
  GBuffer g;
  for (size_t target : levels) {
    MaskingLevel level;
    level.target = target;
    Scene scene = base;
    if (target > 0)
      scene.meshes[kBunnyMesh] = simplify_mesh_cached(base.meshes[kBunnyMesh], target, c.cache_dir,
                                                      &level.from_cache, "--levels");
    level.triangles = scene.meshes[kBunnyMesh].triangle_count();
    level.camera_ms = median_ms(c.repeats, [&] { render_gbuffer(scene, g); });
    require_covered_view(scene, g);
    fill_shading_attributes(scene, g);  // for every slide's picture (untimed)
    std::vector<double> shadow_ms;
    for (size_t k = 0; k < slides.size(); ++k) {
      Projector p = base.projector;
      p.slide = slides[k];
      set_projector(scene, p, "--slides");
      RunOptions opt;
      opt.repeats = c.repeats;
      opt.want_texels = false;
      opt.cache_dir = c.cache_dir;
      opt.flag = "--technique";
      const ShadowResult r = run_technique(spec, scene, g, opt);
      shadow_ms.push_back(r.shadow_ms());
      ProjectorShading shading;
      shading.ambient = c.ambient;
      const ImageF shaded = shade_projector(scene, g, r.mask, shading);
      MaskingCell cell;
      cell.shaded_luma = luminance(shaded);
      const ImageF display = display_encode(cell.shaded_luma);
      if (target == 0) reference[k] = display;
      cell.ssim = ssim(reference[k], display);
      cell.rmse = rmse(reference[k], display);
      cell.visible = visible_difference(reference[k], display);
      if (!c.out_dir.empty())
        write_png_rgb(c.out_dir + "/" + level_label(target) + "_" + file_safe(c.slides[k]) + ".png",
                      shaded);
      level.cells.push_back(std::move(cell));
    }
    level.shadow_ms = median(shadow_ms);
    out.levels.push_back(std::move(level));
  }
  return out;
}

std::string masking_tables(const MaskingResult& r) {
  std::string s;
  auto table = [&](const char* title, auto value) {
    s += std::string(title) + "\n";
    s += fmt::format("  {:<8}", "level");
    for (const std::string& slide : r.slides) s += fmt::format(" {:>22}", slide);
    s += "\n";
    for (const MaskingLevel& L : r.levels) {
      s += fmt::format("  {:<8}", level_label(L.target));
      for (const MaskingCell& cell : L.cells) s += fmt::format(" {:22.4f}", value(cell));
      s += "\n";
    }
  };
  table("SSIM against the full mesh under the same slide (1 = identical)",
        [](const MaskingCell& c) { return c.ssim; });
  table("RMSE of display values [0, 1]", [](const MaskingCell& c) { return c.rmse; });
  table("visible difference, % of pixels (|diff| > 2/255)",
        [](const MaskingCell& c) { return 100.0 * c.visible.plain; });
  table("visible after contrast masking, % of pixels (threshold elevated by local contrast)",
        [](const MaskingCell& c) { return 100.0 * c.visible.masked; });
  s += "level costs\n  level    triangles  camera ms  shadow ms  lod\n";
  for (const MaskingLevel& L : r.levels) {
    s += fmt::format("  {:<8} {:9} {:10.2f} {:10.2f}  {}\n", level_label(L.target), L.triangles,
                     L.camera_ms, L.shadow_ms,
                     L.target == 0 ? "original" : (L.from_cache ? "cached" : "simplified"));
  }
  return s;
}

std::string masking_slide_label(const std::string& s) {
  const size_t a = s.find("amp="), f = s.find("freq=");
  if (a == std::string::npos || f == std::string::npos) return s;
  // Each value runs to the next ',' or the end, whichever key comes first.
  auto value = [&](size_t from) { return s.substr(from, s.find(',', from) - from); };
  return "A" + value(a + 4) + " F" + value(f + 5);
}

void write_masking_csv(const std::string& path, const MaskingResult& r) {
  std::ostringstream f;
  f << "level,triangles,slide,ssim,rmse,visible,visible_masked,camera_ms,shadow_ms\n";
  for (const MaskingLevel& L : r.levels)
    for (size_t k = 0; k < L.cells.size(); ++k) {
      const MaskingCell& c = L.cells[k];
      f << level_label(L.target) << ',' << L.triangles << ",\"" << r.slides[k] << "\"," << c.ssim
        << ',' << c.rmse << ',' << c.visible.plain << ',' << c.visible.masked << ','
        << L.camera_ms << ',' << L.shadow_ms << '\n';
    }
  write_text_file(path, f.str());
}

ImageF masking_contact_sheet(const MaskingResult& r, int max_cell_width) {
  std::vector<std::string> rows, cols;
  std::vector<std::vector<const ImageF*>> cells;
  for (const MaskingLevel& L : r.levels) {
    rows.push_back(L.target == 0 ? "FULL " + std::to_string(L.triangles)
                                 : std::to_string(L.triangles) + " TRIS");
    std::vector<const ImageF*> row;
    for (const MaskingCell& c : L.cells) row.push_back(&c.shaded_luma);
    cells.push_back(row);
  }
  for (const std::string& s : r.slides) cols.push_back(masking_slide_label(s));
  ContactSheetStyle style;
  style.max_cell_width = max_cell_width;
  return contact_sheet(rows, cols, cells, nullptr, style);
}

}  // namespace shadowlab
