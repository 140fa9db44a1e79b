#include "metric/flip.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/isa.h"
#include "core/error.h"
#include "core/exp_log.h"
#include "core/parallel.h"
#include "metric/flip_kernels.h"

namespace shadowlab {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Linear sRGB primaries → CIE XYZ under D65, and back (the inverse as published with FLIP).
constexpr double kRgbToXyz[3][3] = {
    {10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};
constexpr double kXyzToRgb[3][3] = {{3.241003275, -1.537398934, -0.498615861},
                                    {-0.969224334, 1.875930071, 0.041554224},
                                    {0.055639423, -0.204011202, 1.057148933}};
constexpr double kWhite[3] = {0.950428545, 1.0, 1.088900371};     // D65 XYZ
constexpr double kInvWhite[3] = {1.052156925, 1.0, 0.918357670};  // its reciprocals

// Exponents and the error redistribution (paper §4).
constexpr double kQc = 0.7, kQf = 0.5, kPc = 0.4, kPt = 0.95;
static_assert(kQf == 0.5, "ΔEf's power qf is taken as a square root");
// Peak-to-trough width of the human edge detector, degrees (2 standard deviations).
constexpr double kFeatureWidth = 0.082;

// x^p for x >= 0 through core/exp_log.h (within a few ulp; glibc's pow and cbrt were a third of
// the metric's FLIP time): 0 for x = 0 (and for x below 2^-1000, far under any error FLIP can
// resolve) when p > 0, 1 when p = 0.
double power(double x, double p) {
  if (p == 0.0) return 1.0;
  return x < 0x1p-1000 ? 0.0 : exp_d(p * log_d(x));
}

// power() of n values at once: out[i] = power(x[i], p ? p[i] : p0), the table's vector power
// first (core/exp_log_avx2.h and exp_log_avx512.h give exp_d's and log_d's bits in every lane;
// its selects are power()'s), the tail and the rest by power(): the same bits either way.
void power_n(const FlipKernels& kern, const double* x, const double* p, double p0, size_t n,
             double* out) {
  size_t i = kern.power ? kern.power(x, p, p0, n, out) : 0;
  for (; i < n; ++i) out[i] = power(x[i], p ? p[i] : p0);
}

struct Vec3 {
  double x, y, z;
};

Vec3 mul(const double (&m)[3][3], const Vec3& v) {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
          m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

// YCxCz (Y' = 116·Y/Yn − 16, Cx = 500·(X/Xn − Y/Yn), Cz = 200·(Y/Yn − Z/Zn)) of linear RGB.
Vec3 ycxcz_from_linear(const Vec3& rgb) {
  const Vec3 xyz = mul(kRgbToXyz, rgb);
  const double x = xyz.x * kInvWhite[0], y = xyz.y * kInvWhite[1], z = xyz.z * kInvWhite[2];
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}

Vec3 linear_from_ycxcz(const Vec3& c) {
  const double y = (c.x + 16.0) / 116.0;
  const Vec3 xyz = {(y + c.y / 500.0) * kWhite[0], y * kWhite[1], (y - c.z / 200.0) * kWhite[2]};
  return mul(kXyzToRgb, xyz);
}

// Hunt-adjusted CIELAB (L, a·L/100, b·L/100) of linear RGB.
Vec3 hunt_lab_from_linear(const Vec3& rgb) {
  const Vec3 xyz = mul(kRgbToXyz, rgb);
  const double delta = 6.0 / 29.0;
  auto f = [&](double t) {
    return t > delta * delta * delta ? power(t, 1.0 / 3.0) : t / (3.0 * delta * delta) + 4.0 / 29.0;
  };
  const double fx = f(xyz.x * kInvWhite[0]), fy = f(xyz.y * kInvWhite[1]),
               fz = f(xyz.z * kInvWhite[2]);
  const double L = 116.0 * fy - 16.0;
  return {L, 0.01 * L * 500.0 * (fx - fy), 0.01 * L * 200.0 * (fy - fz)};
}

double hyab(const Vec3& a, const Vec3& b) {
  const double da = a.y - b.y, db = a.z - b.z;
  return std::fabs(a.x - b.x) + std::sqrt(da * da + db * db);
}

// The colour error ΔE^qc mapped to [0, 1]: [0, pc·cmax) linearly onto [0, pt), the rest onto
// [pt, 1].
double redistribute(double e, double cmax) {
  const double knee = kPc * cmax;
  return e < knee ? kPt / knee * e : kPt + (e - knee) / (cmax - knee) * (1.0 - kPt);
}

// The largest colour error: Hunt-adjusted green against blue, to the power qc.
double cmax() {
  return power(hyab(hunt_lab_from_linear({0.0, 1.0, 0.0}), hunt_lab_from_linear({0.0, 0.0, 1.0})),
               kQc);
}

// Contrast sensitivity of one channel: s(x, y) = Σ_k a_k·√(π/b_k)·exp(−π²·d²/b_k), d the
// distance in degrees (paper eq. 2: achromatic, red-green, blue-yellow).
struct Csf {
  double a1, b1, a2, b2;
};
constexpr Csf kCsf[3] = {
    {1.0, 0.0047, 0.0, 1e-5}, {1.0, 0.0053, 0.0, 1e-5}, {34.1, 0.04, 13.5, 0.025}};

// Radius (pixels) of every channel's CSF window: 3 standard deviations of the widest Gaussian
// (b = 0.04, σ = √(b/(2π²)) degrees).
int csf_radius(double ppd) {
  return int(std::ceil(3.0 * std::sqrt(0.04 / (2.0 * kPi * kPi)) * ppd));
}
int feature_radius(double ppd) { return int(std::ceil(3.0 * 0.5 * kFeatureWidth * ppd)); }

// One term c·kx(i)·ky(j) of a separable kernel (taps i, j in [−r, r]).
struct Term {
  double c;
  std::vector<double> kx, ky;
};
using Kernel = std::vector<Term>;

// The CSF of a channel as separable terms, normalized so that the 2D weights sum to 1.
Kernel csf_kernel(const Csf& s, double ppd) {
  const int r = csf_radius(ppd);
  Kernel k;
  double total = 0.0;
  for (const auto& [a, b] : {std::pair{s.a1, s.b1}, std::pair{s.a2, s.b2}}) {
    if (a == 0.0) continue;
    Term t{a * std::sqrt(kPi / b), {}, {}};
    double sum = 0.0;
    for (int i = -r; i <= r; ++i) {
      const double d = double(i) / ppd;
      t.kx.push_back(std::exp(-kPi * kPi * d * d / b));
      sum += t.kx.back();
    }
    t.ky = t.kx;
    total += t.c * sum * sum;
    k.push_back(t);
  }
  for (Term& t : k) t.c /= total;
  return k;
}

// The 1D factor u(x) of a feature detector (edge: −x·g, point: (x²/σ² − 1)·g, g the Gaussian of
// σ = ½·0.082 degrees), before normalization.
std::vector<double> feature_profile(double ppd, bool point, std::vector<double>& gauss) {
  const double sd = 0.5 * kFeatureWidth * ppd;
  const int r = feature_radius(ppd);
  std::vector<double> u;
  gauss.clear();
  for (int i = -r; i <= r; ++i) {
    const double x = double(i), g = std::exp(-x * x / (2.0 * sd * sd));
    gauss.push_back(g);
    u.push_back(point ? (x * x / (sd * sd) - 1.0) * g : -x * g);
  }
  return u;
}

// A feature detector across x as one separable term: the 2D kernel u(x)·g(y) with its positive
// weights scaled to sum 1 and its negative ones to −1. Its positive weights sum to
// (Σ_{u>0} u)·(Σ g), its negative ones likewise, so the scaling is u(x)/Σ_{u>0}u (or the
// negative sum) times g(y)/Σg: still separable.
Term feature_kernel_x(double ppd, bool point) {
  std::vector<double> g;
  std::vector<double> u = feature_profile(ppd, point, g);
  double pos = 0.0, neg = 0.0, gs = 0.0;
  for (double v : u) (v > 0.0 ? pos : neg) += v;
  for (double v : g) gs += v;
  for (double& v : u) v = v > 0.0 ? v / pos : v / -neg;
  for (double& v : g) v /= gs;
  return {1.0, u, g};
}

// A w × h plane of doubles, uninitialized (every value is written before it is read): the
// passes below write whole planes, and zeroing each first was a tenth of FLIP's time.
using Plane = std::unique_ptr<double[]>;
Plane plane(size_t n) { return Plane(new double[n]); }

// The row pass of one separable term, clamp-to-edge: tmp[y][x] = Σ_i kx[i]·in[y][x + i − r].
void row_pass(const double* in, int w, int h, const std::vector<double>& kx, double* tmp) {
  const int r = int(kx.size() / 2);
  const FlipKernels& kern = flip_kernels(process_isa());
  parallel_for_chunks(size_t(h), 16, [&](size_t y0, size_t y1) {
    std::vector<const double*> shifted(kx.size());
    for (size_t y = y0; y < y1; ++y) {
      const double* row = in + y * size_t(w);
      double* o = tmp + y * size_t(w);
      // Taps inside the row need no clamp: there the sums run over contiguous values.
      const int lo = std::min(r, w), hi = std::max(lo, w - r);
      auto clamped = [&](int x) {
        double s = 0.0;
        for (int i = -r; i <= r; ++i) s += kx[size_t(i + r)] * row[std::clamp(x + i, 0, w - 1)];
        o[x] = s;
      };
      for (int x = 0; x < lo; ++x) clamped(x);
      for (int i = -r; i <= r; ++i) shifted[size_t(i + r)] = row + lo + i;
      kern.weighted_rows(shifted.data(), kx.data(), 2 * r + 1, hi - lo, o + lo);
      for (int x = hi; x < w; ++x) clamped(x);
    }
  });
}

// The column pass: c·Σ_j ky[j]·tmp[y + j − r][x] (clamped), stored (first term: onto 0) or
// added to out.
void column_pass(const double* tmp, int w, int h, const std::vector<double>& ky, double c,
                 bool first, double* out) {
  const int r = int(ky.size() / 2);
  const FlipKernels& kern = flip_kernels(process_isa());
  parallel_for_chunks(size_t(h), 16, [&](size_t y0, size_t y1) {
    std::vector<double> acc(static_cast<size_t>(w));
    std::vector<const double*> rows(ky.size());
    for (size_t y = y0; y < y1; ++y) {
      for (int j = -r; j <= r; ++j)
        rows[size_t(j + r)] = tmp + size_t(std::clamp(int(y) + j, 0, h - 1)) * size_t(w);
      kern.weighted_rows(rows.data(), ky.data(), 2 * r + 1, w, acc.data());
      double* o = out + y * size_t(w);
      if (first)
        for (int x = 0; x < w; ++x) o[x] = 0.0 + c * acc[size_t(x)];
      else
        kern.axpy(c, acc.data(), w, o);
    }
  });
}

// Correlation of a w × h plane with a separable kernel: per term a row pass with kx and a
// column pass with ky, the terms added in order.
void correlate(const double* in, int w, int h, const Kernel& k, double* out) {
  const Plane tmp = plane(size_t(w) * size_t(h));
  for (size_t term = 0; term < k.size(); ++term) {
    row_pass(in, w, h, k[term].kx, tmp.get());
    column_pass(tmp.get(), w, h, k[term].ky, k[term].c, term == 0, out);
  }
}

void check_image(const ImageF& im) {
  if (im.empty()) throw InputError("flip", "empty image");
  if (im.channels != 1 && im.channels != 3)
    throw InputError("flip",
                     "an image has " + std::to_string(im.channels) + " channels (1 or 3 expected)");
  for (float v : im.data)
    if (std::isnan(v)) throw InputError("flip", "an image holds NaN");
}

void check_ppd(double ppd) {
  // Below 1 pixel per degree the edge detector's taps at ±1 underflow to 0 (σ = 0.041 ppd
  // pixels) and its normalization would divide 0 by 0.
  if (!(ppd >= 1.0 && ppd <= 1000.0))
    throw InputError("flip", "pixels per degree must be in [1, 1000]");
}

// The pair's sizes (each image and the observer are checked by flip_prepare, before any work).
void check_sizes(const ImageF& test, const ImageF& ref) {
  if (test.empty() || ref.empty()) throw InputError("flip", "empty image");
  if (test.width != ref.width || test.height != ref.height)
    throw InputError("flip", "images differ in size: " + std::to_string(test.width) + "x" +
                                 std::to_string(test.height) + " against " +
                                 std::to_string(ref.width) + "x" + std::to_string(ref.height));
}

// Calls f(i) for every pixel index i < n, rows of w pixels in parallel (each i writes only its
// own outputs, so the result does not depend on the thread count).
template <class F>
void for_pixels(size_t n, int w, const F& f) {
  const size_t rows = (n + size_t(w) - 1) / size_t(w);
  parallel_for_chunks(rows, 8, [&](size_t y0, size_t y1) {
    for (size_t i = y0 * size_t(w); i < std::min(n, y1 * size_t(w)); ++i) f(i);
  });
}

}  // namespace

// Calls f(begin, end) over [0, n) in runs of whole rows of w pixels, in parallel (each index
// writes only its own outputs).
template <class F>
void for_runs(size_t n, int w, const F& f) {
  const size_t rows = (n + size_t(w) - 1) / size_t(w);
  parallel_for_chunks(
      rows, 8, [&](size_t y0, size_t y1) { f(y0 * size_t(w), std::min(n, y1 * size_t(w))); });
}

// Hunt-adjusted CIELAB of pixels [b, e) of three linear RGB planes (clamped to [0, 1]): the
// cube roots as one power_n call per channel; hunt_lab_from_linear's operations otherwise.
void hunt_lab_run(const FlipKernels& kern, const Plane* rgb, size_t b, size_t e,
                  std::vector<double>* lab) {
  const size_t k = e - b;
  std::vector<double> t[3], f[3];
  for (int c = 0; c < 3; ++c) {
    t[c].resize(k);
    f[c].resize(k);
  }
  for (size_t i = 0; i < k; ++i) {
    const Vec3 v = {std::clamp(rgb[0][b + i], 0.0, 1.0), std::clamp(rgb[1][b + i], 0.0, 1.0),
                    std::clamp(rgb[2][b + i], 0.0, 1.0)};
    const Vec3 xyz = mul(kRgbToXyz, v);
    t[0][i] = xyz.x * kInvWhite[0];
    t[1][i] = xyz.y * kInvWhite[1];
    t[2][i] = xyz.z * kInvWhite[2];
  }
  for (int c = 0; c < 3; ++c) power_n(kern, t[c].data(), nullptr, 1.0 / 3.0, k, f[c].data());
  const double delta = 6.0 / 29.0;
  for (int c = 0; c < 3; ++c)
    for (size_t i = 0; i < k; ++i)
      if (!(t[c][i] > delta * delta * delta))
        f[c][i] = t[c][i] / (3.0 * delta * delta) + 4.0 / 29.0;
  for (size_t i = 0; i < k; ++i) {
    const double L = 116.0 * f[1][i] - 16.0;
    lab[0][b + i] = L;
    lab[1][b + i] = 0.01 * L * 500.0 * (f[0][i] - f[1][i]);
    lab[2][b + i] = 0.01 * L * 200.0 * (f[1][i] - f[2][i]);
  }
}

// CIELAB of a grey image's pixels [b, e) from its filtered Y' plane: L from the cube root of
// the clamped luminance, a = b = 0.
void grey_lab_run(const FlipKernels& kern, const double* ycc_y, size_t b, size_t e,
                  std::vector<double>* lab) {
  const size_t k = e - b;
  std::vector<double> t(k), f(k);
  for (size_t i = 0; i < k; ++i) t[i] = std::clamp((ycc_y[b + i] + 16.0) / 116.0, 0.0, 1.0);
  power_n(kern, t.data(), nullptr, 1.0 / 3.0, k, f.data());
  const double delta = 6.0 / 29.0;
  for (size_t i = 0; i < k; ++i) {
    const double fy =
        t[i] > delta * delta * delta ? f[i] : t[i] / (3.0 * delta * delta) + 4.0 / 29.0;
    lab[0][b + i] = 116.0 * fy - 16.0;
    lab[1][b + i] = 0.0;
    lab[2][b + i] = 0.0;
  }
}

FlipPrepared flip_prepare(const ImageF& img, double ppd) {
  check_image(img);
  check_ppd(ppd);
  const int w = img.width, h = img.height;
  const size_t n = img.pixel_count();
  // A 1-channel image is grey: achromatic throughout, Cx = Cz = 0 and a* = b* = 0 exactly (the
  // published matrices leave a residue of ~2e-7·Y in a grey's chroma, which x^0.7 would lift to
  // ~1e-6 of FLIP where nothing differs), so its chroma planes are neither made nor filtered.
  const bool grey = img.channels == 1;
  const int planes = grey ? 1 : 3;
  Plane ycc[3], filtered[3];
  for (int c = 0; c < planes; ++c) {
    ycc[c] = plane(n);
    filtered[c] = plane(n);
  }
  for_pixels(n, w, [&](size_t i) {
    auto v = [&](int c) {
      const float f = img.data[size_t(grey ? 0 : c) * n + i];
      return std::clamp(double(f), 0.0, 1.0);
    };
    const Vec3 c = ycxcz_from_linear({v(0), v(1), v(2)});
    ycc[0][i] = c.x;
    if (!grey) {
      ycc[1][i] = c.y;
      ycc[2][i] = c.z;
    }
  });
  FlipPrepared p;
  p.width = w;
  p.height = h;
  p.pixels_per_degree = ppd;
  for (int c = 0; c < planes; ++c)
    correlate(ycc[c].get(), w, h, csf_kernel(kCsf[c], ppd), filtered[c].get());
  for (auto& l : p.lab) l.resize(n);
  const FlipKernels& kern = flip_kernels(process_isa());
  if (grey) {
    // A grey stays grey: its filtered luminance Y = (Y' + 16)/116, clamped to [0, 1] as the
    // RGB box clamps it, has L* = 116·f(Y) − 16 and a* = b* = 0.
    for_runs(n, w,
             [&](size_t b, size_t e) { grey_lab_run(kern, filtered[0].get(), b, e, p.lab); });
  } else {
    // Back to linear RGB, then Lab.
    Plane rgb[3];
    for (auto& c : rgb) c = plane(n);
    for_pixels(n, w, [&](size_t i) {
      const Vec3 v = linear_from_ycxcz({filtered[0][i], filtered[1][i], filtered[2][i]});
      rgb[0][i] = v.x;
      rgb[1][i] = v.y;
      rgb[2][i] = v.z;
    });
    for_runs(n, w, [&](size_t b, size_t e) { hunt_lab_run(kern, rgb, b, e, p.lab); });
  }
  // Features on the normalized luminance of the unfiltered image.
  // Each detector across x is u(x)·g(y), across y g(x)·u(y), with the same normalized g for
  // edges and points: the row pass with g serves both detectors' y derivatives.
  const Plane lum = plane(n), rows_g = plane(n), rows_u = plane(n), fx = plane(n), fy = plane(n);
  for_pixels(n, w, [&](size_t i) { lum[i] = (ycc[0][i] + 16.0) / 116.0; });
  const Term edge_x = feature_kernel_x(ppd, false);  // its ky is the normalized g
  row_pass(lum.get(), w, h, edge_x.ky, rows_g.get());
  for (const bool point : {false, true}) {
    const Term kx = feature_kernel_x(ppd, point);
    row_pass(lum.get(), w, h, kx.kx, rows_u.get());
    column_pass(rows_u.get(), w, h, kx.ky, 1.0, true, fx.get());
    column_pass(rows_g.get(), w, h, kx.kx, 1.0, true, fy.get());
    std::vector<double>& mag = point ? p.point : p.edge;
    mag.resize(n);
    for_pixels(n, w, [&](size_t i) { mag[i] = std::sqrt(fx[i] * fx[i] + fy[i] * fy[i]); });
  }
  return p;
}

ImageF flip_error_map(const ImageF& test, const ImageF& ref, double ppd) {
  check_sizes(test, ref);
  check_image(ref);  // both checked before the test image's work starts
  return flip_error_map(flip_prepare(test, ppd), flip_prepare(ref, ppd));
}

ImageF flip_error_map(const FlipPrepared& t, const FlipPrepared& r) {
  if (t.width != r.width || t.height != r.height || t.pixels_per_degree != r.pixels_per_degree)
    throw InputError("flip", "prepared images differ in size or observer");
  const double c_max = cmax();
  ImageF out(t.width, t.height, 1);
  const size_t n = out.pixel_count();
  const FlipKernels& kern = flip_kernels(process_isa());
  for_runs(n, t.width, [&](size_t b, size_t e) {
    const size_t k = e - b;
    std::vector<double> de(k), dc(k), ex(k), v(k);
    for (size_t i = 0; i < k; ++i)
      de[i] = hyab({r.lab[0][b + i], r.lab[1][b + i], r.lab[2][b + i]},
                   {t.lab[0][b + i], t.lab[1][b + i], t.lab[2][b + i]});
    power_n(kern, de.data(), nullptr, kQc, k, dc.data());
    for (size_t i = 0; i < k; ++i) {
      dc[i] = redistribute(dc[i], c_max);
      const double df_raw = std::max(std::fabs(r.edge[b + i] - t.edge[b + i]),
                                     std::fabs(r.point[b + i] - t.point[b + i]));
      ex[i] = 1.0 - std::sqrt(df_raw / std::sqrt(2.0));  // 1 − ΔEf, the power qf = 0.5
    }
    power_n(kern, dc.data(), ex.data(), 0.0, k, v.data());
    for (size_t i = 0; i < k; ++i) out.data[b + i] = float(v[i]);
  });
  return out;
}

double srgb_to_linear(double v) {
  return v > 0.04045 ? std::pow((v + 0.055) / 1.055, 2.4) : v / 12.92;
}

double flip_mean(const ImageF& error_map) {
  double total = 0.0;
  for (int y = 0; y < error_map.height; ++y) {
    double row = 0.0;
    for (int x = 0; x < error_map.width; ++x) row += double(error_map.at(x, y));
    total += row;
  }
  return error_map.pixel_count() ? total / double(error_map.pixel_count()) : 0.0;
}

}  // namespace shadowlab
