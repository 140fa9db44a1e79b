// The exponential variance filter (evsm; docs/techniques/evsm.md): its keys struct and its row,
// kExponentialVarianceMap (exponential_variance_map.cpp). One line of techniques/filters/all.h:
// the struct is declared once (the guard), the lines after it are read on every pass of that list.
#ifndef SHADOWLAB_FILTERS_EVSM_H
#define SHADOWLAB_FILTERS_EVSM_H
namespace shadowlab {

// Keys of the exponential variance filter. The exponents warp the normalised distance
// d' = 2d − 1 in [−1, 1].
struct EvsmKeys {
  int moments{};          // 2: the positive warp e^(c_pos·d'); 4: also −e^(−c_neg·d')
  double c_pos{};         // positive exponent
  double c_neg{};         // negative exponent
  double min_variance{};  // variance floor of the distance, m², carried into each warp
  double bleed{};         // light-bleeding reduction, as for vsm
};

}  // namespace shadowlab
#endif
SHADOWLAB_FILTER(ExponentialVariance, kExponentialVarianceMap)
SHADOWLAB_FILTER_KEYS(EvsmKeys, evsm)
