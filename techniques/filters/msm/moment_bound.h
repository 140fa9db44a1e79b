#pragma once
// The moment shadow map's reconstruction (Peters & Klein 2015, "Moment shadow mapping",
// I3D; docs/design.md §6, MSM): from the filtered power moments m = (E[d], E[d²], E[d³], E[d⁴])
// of the occluders' normalised distances d in [0, 1], the sharpest lower bound on the fraction
// of them strictly in front of a receiver at depth z (the shadow intensity G; visibility 1 − G).
//
//   1. Bias: b = (1 − α)·m + α·(½, ½, ½, ½), which keeps the Hankel matrix
//      B = [[1, b1, b2], [b1, b2, b3], [b2, b3, b4]] positive definite when rounding (fp32 or
//      16-bit storage) or a single depth in the footprint makes it singular.
//   2. Solve B·c = (1, z, z²) by B = L·D·Lᵀ (Cholesky without square roots), carried out
//      scaled by k = d22²·d33 (D's pivots): k·c needs no division, and step 3 only needs c
//      up to scale (docs/performance_history.md: five of the seven divisions gone).
//   3. The roots z2 <= z3 of c1 + c2·x + c3·x² are, with z, the atoms of the distribution with
//      moments b that has an atom at z (its canonical representation).
//   4. Hamburger (support ℝ): G = 0 when z <= z2; the weight of z2 when z2 < z <= z3; one minus
//      the weight of z when z > z3 (each weight by Lagrange interpolation on the three atoms).
//   5. Hausdorff (support [0, 1]): as Hamburger when 0 <= z2 and z3 <= 1; otherwise the
//      representation with atoms 0, z, u, 1, whose free atom u makes E[x(x − 1)(x − z)(x − u)]
//      vanish: G = w0 + (u < z ? w_u : 0).
// A G that is not a number (a singular B: α = 0 over a footprint of one depth) counts as 0, as
// a GPU's saturate() does: the pixel is lit. α = 0 is allowed so that this leak can be measured.
//
// The scalar functions are the oracle; msm_intensity4n and msm_intensity8n
// (techniques/filters/msm/moment_bound_avx2.inl, moment_bound_avx512.inl) compute groups of 4 and 8 lanes
// with the same operations in the same order (selects as compare-and-blend), so they give
// their bits.
#include <cmath>

namespace shadowlab {

// Solution c of B·c = (1, z, z²) for biased moments b[0..3] = (b1, b2, b3, b4), scaled by
// k = d22²·d33 > 0 (B positive definite): c = (c1, c2, c3) / k.
struct HankelSolution {
  double c1, c2, c3, k;
};

inline HankelSolution hankel_solve(const double b[4], double z) {
  // B = L·D·Lᵀ with L = [[1, 0, 0], [b1, 1, 0], [b2, l32, 1]], D = diag(1, d22, d33),
  // l32 = e32 / d22. Every quantity that would be divided by d22 is kept multiplied by it:
  // s33 = d22·d33 = d22·(b4 − b2²) − e32², and y3s = d22·y3 from the forward pass
  // (L·y = (1, z, z²)). Backward (Lᵀ·c = D⁻¹·y) times k = d22·s33:
  // k·c3 = d22·y3s, k·c2 = s33·y2 − e32·y3s, k·c1 = k − b1·(k·c2) − b2·(k·c3).
  const double d22 = b[1] - b[0] * b[0];
  const double e32 = b[2] - b[0] * b[1];
  const double s33 = d22 * (b[3] - b[1] * b[1]) - e32 * e32;
  const double y2 = z - b[0];
  const double y3s = d22 * (z * z - b[1]) - e32 * y2;
  const double k = d22 * s33;
  const double c3 = d22 * y3s;
  const double c2 = s33 * y2 - e32 * y3s;
  const double c1 = (k - b[0] * c2) - b[1] * c3;
  return {c1, c2, c3, k};
}

// The biased moments of step 1.
inline void msm_bias(const double m[4], double alpha, double b[4]) {
  const double keep = 1.0 - alpha, pull = 0.5 * alpha;
  for (int i = 0; i < 4; ++i) b[i] = m[i] * keep + pull;
}

// Shadow intensity G in [0, 1] (visibility is 1 − G) for moments m, receiver depth z.
inline double msm_intensity(const double m[4], double z, double alpha, bool hausdorff) {
  double b[4];
  msm_bias(m, alpha, b);
  const HankelSolution c = hankel_solve(b, z);
  // The quadratic's roots do not depend on its scale: p = c2/c3 and q = c1/c3 from the scaled
  // solution, through one reciprocal.
  const double inv = 1.0 / c.c3;
  const double p = c.c2 * inv, q = c.c1 * inv;
  const double r = std::sqrt(p * p * 0.25 - q);
  const double z2 = -0.5 * p - r, z3 = -0.5 * p + r;
  // Weight of z2 (z between the roots) or one minus the weight of z (z beyond both): one
  // division of the operands that z's branch selects (the vector forms select before dividing,
  // which gives these bits).
  const bool mid = z <= z3;
  const double num =
      mid ? ((z * z3 - b[0] * (z + z3)) + b[1]) : ((z2 * z3 - b[0] * (z2 + z3)) + b[1]);
  const double den = mid ? ((z3 - z2) * (z - z2)) : ((z - z2) * (z - z3));
  const double w = num / den;
  double g = z <= z2 ? 0.0 : (mid ? w : 1.0 - w);
  if (hausdorff && (z2 < 0.0 || z3 > 1.0)) {
    // Atoms 0, z, u, 1: E[x(x − 1)(x − z)(x − u)] = 0 fixes u; w0 and w_u by Lagrange.
    const double zp1 = z + 1.0;
    const double u = ((b[3] - zp1 * b[2]) + z * b[1]) / ((b[2] - zp1 * b[1]) + z * b[0]);
    const double zu = z * u;
    const double w0 = (((b[2] - (zp1 + u) * b[1]) + ((z + u) + zu) * b[0]) - zu) / -zu;
    const double wu = ((b[2] - zp1 * b[1]) + z * b[0]) / ((u * (u - 1.0)) * (u - z));
    g = u < z ? w0 + wu : w0;
  }
  return g > 0.0 ? (g < 1.0 ? g : 1.0) : 0.0;  // NaN -> 0
}

// The optimized 16-bit quantization (Peters & Klein 2015, §4.3): an affine map of the four
// moments of any depth in [0, 1] into [0, 1]⁴ whose rounding to 16 bits hurts the
// reconstruction least; q = m·Θ + (0.035955884801, 0, 0, 0) (m a row vector), and its
// published inverse.
inline constexpr double kMsmTheta[4][4] = {
    {-2.07224649, 13.7948857237, 0.105877704, 9.7924062118},
    {32.23703778, -59.4683975703, -1.9077466311, -33.7652110555},
    {-68.571074599, 82.0359750338, 9.3496555107, 47.9456096605},
    {39.3703274134, -35.364903257, -6.6543490743, -23.9728048165}};
inline constexpr double kMsmInverse[4][4] = {
    {0.2227744146, 0.1549679261, 0.1451988946, 0.163127443},
    {0.0771972861, 0.1394629426, 0.2120202157, 0.2591432266},
    {0.7926986636, 0.7963415838, 0.7258694464, 0.6539092497},
    {0.0319417555, -0.1722823173, -0.2758014811, -0.3376131734}};
inline constexpr double kMsmOffset = 0.035955884801;

inline void msm_encode16(const double m[4], double q[4]) {
  for (int j = 0; j < 4; ++j)
    q[j] = ((m[0] * kMsmTheta[0][j] + m[1] * kMsmTheta[1][j]) + m[2] * kMsmTheta[2][j]) +
           m[3] * kMsmTheta[3][j];
  q[0] += kMsmOffset;
}

inline void msm_decode16(const double q_in[4], double m[4]) {
  const double q[4] = {q_in[0] - kMsmOffset, q_in[1], q_in[2], q_in[3]};
  for (int j = 0; j < 4; ++j)
    m[j] = ((q[0] * kMsmInverse[0][j] + q[1] * kMsmInverse[1][j]) + q[2] * kMsmInverse[2][j]) +
           q[3] * kMsmInverse[3][j];
}

}  // namespace shadowlab
