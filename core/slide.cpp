#include "core/slide.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/image_io.h"
#include "core/parse_number.h"
#include "core/spec.h"
#include "core/texture.h"

namespace shadowlab {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool ends_with(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  for (size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i])
      return false;
  return true;
}

ImageF bake(int res, float amp, float freq) {
  ImageF img(res, res, 3);
  for (int y = 0; y < res; ++y)
    for (int x = 0; x < res; ++x) {
      const vec2 st((float(x) + 0.5f) / float(res), (float(y) + 0.5f) / float(res));
      const float v = spot_profile(st) * grid_modulation(st, amp, freq);
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = v;
    }
  return img;
}

}  // namespace

float spot_profile(vec2 st) {
  const double dx = 2.0 * double(st.x) - 1.0, dy = 2.0 * double(st.y) - 1.0;
  const double r = std::sqrt(dx * dx + dy * dy);
  const double t = std::clamp((r - 0.6) / 0.4, 0.0, 1.0);
  return float(1.0 - t * t * (3.0 - 2.0 * t));
}

float grid_modulation(vec2 st, float amp, float freq) {
  auto m = [&](double x) {
    return 1.0 - double(amp) * 0.5 * (1.0 - std::cos(2.0 * kPi * double(freq) * (x - 0.5)));
  };
  return float(m(st.x) * m(st.y));
}

vec3 sample_slide(const ImageF& rgb, vec2 st) {
  const int w = rgb.width, h = rgb.height;
  // Texel space with centres at integers; clamp to edge.
  const float gx = std::clamp(st.x * float(w) - 0.5f, 0.0f, float(w - 1));
  const float gy = std::clamp(st.y * float(h) - 0.5f, 0.0f, float(h - 1));
  const int x0 = int(gx), y0 = int(gy);
  const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
  const float fx = gx - float(x0), fy = gy - float(y0);
  vec3 out;
  for (int c = 0; c < 3; ++c) {
    const float top = (1.0f - fx) * rgb.at(x0, y0, c) + fx * rgb.at(x1, y0, c);
    const float bot = (1.0f - fx) * rgb.at(x0, y1, c) + fx * rgb.at(x1, y1, c);
    out[c] = (1.0f - fy) * top + fy * bot;
  }
  return out;
}

// Slides are looked up bilinearly at the GBuffer points: beyond 4096² texels (16.8 M, ~200 MB
// as float RGB) a slide only costs memory. A 261 KB black 8192² PNG used to peak at 1.84 GB.
constexpr size_t kMaxSlideTexels = size_t(4096) * 4096;

void check_slide_size(const std::string& path, std::pair<int, int> size) {
  const size_t texels = size_t(size.first) * size_t(size.second);
  if (texels > kMaxSlideTexels)
    throw InputError(path, "slide is " + std::to_string(size.first) + "x" + std::to_string(size.second) +
                               " (" + std::to_string(texels / 1000000) +
                               " M texels, about 12 bytes each as float RGB); the limit is 4096x4096 "
                               "texels: downscale it");
}

Slide make_slide(const std::string& spec, const std::string& flag) {
  Slide slide;
  slide.name = spec;
  if (ends_with(spec, ".png") || ends_with(spec, ".jpg") || ends_with(spec, ".jpeg")) {
    // The size is checked from the header before decoding; the 8-bit texels go straight to
    // linear float RGB (about 20 bytes per texel at the peak, 12 kept).
    check_slide_size(spec, image_file_size(spec));
    const Texture8 tex = load_texture8(spec);
    slide.rgb = ImageF(tex.width, tex.height, 3);
    for (size_t i = 0; i < slide.rgb.pixel_count(); ++i)
      for (int c = 0; c < 3; ++c) slide.rgb.plane(c)[i] = srgb8_to_linear(tex.rgba[4 * i + size_t(c)]);
    return slide;
  }
  if (ends_with(spec, ".exr")) {
    check_slide_size(spec, exr_image_size(spec));
    slide.rgb = read_exr_rgb(spec);
    for (float v : slide.rgb.data)
      if (!std::isfinite(v) || v < 0.0f)
        throw InputError(spec, "slide has a negative or non-finite value");
    return slide;
  }
  // The generic strict "name:key=value,…" parser (core/spec.h): no repeated keys, no
  // trailing comma, no spaces in numbers.
  const Spec parsed = parse_spec(spec, flag);
  const std::string& name = parsed.name;
  if (name != "spot" && name != "grid")
    throw InputError(flag, "unknown slide '" + spec +
                               "' (known: spot, grid:amp=A,freq=F, or a .png/.jpg/.exr file)");
  SpecReader r(parsed, flag);
  const long res = r.get_int("res", 512, 8, 4096);
  double amp = 0.0, freq = 0.0;
  if (name == "grid") {
    if (!parsed.params.count("amp") || !parsed.params.count("freq"))
      throw InputError(flag, "slide 'grid' needs both amp and freq (grid:amp=A,freq=F)");
    amp = r.get_double("amp", 0.0, 0.0, 1.0);
    freq = r.get_double("freq", 0.0, 0.0, 1000.0);
  }
  r.reject_unknown();
  slide.rgb = bake(int(res), float(amp), float(freq));
  return slide;
}

}  // namespace shadowlab
