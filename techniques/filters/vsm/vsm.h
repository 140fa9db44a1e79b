// The variance filter (vsm; docs/techniques/vsm.md): its keys struct and its row, kVarianceMap
// (variance_map.cpp). One line of techniques/filters/all.h: the struct is declared once (the
// guard), the lines after it are read on every pass of that list.
#ifndef SHADOWLAB_FILTERS_VSM_H
#define SHADOWLAB_FILTERS_VSM_H
namespace shadowlab {

// Keys of the variance filter.
struct VsmKeys {
  double min_variance{};  // variance floor, m²
  double bleed{};         // light-bleeding reduction, p -> linstep(bleed, 1, p)
  double maxdepth_eps{};  // > 0: a receiver deeper than the footprint's max + eps (m) is shadowed
  bool slope_moment{};    // M2 = d² + ¼((∂d/∂x)² + (∂d/∂y)²) per texel
  bool fp32{};            // moments filtered in float (the naive form), not double
};

}  // namespace shadowlab
#endif
SHADOWLAB_FILTER(Variance, kVarianceMap)
SHADOWLAB_FILTER_KEYS(VsmKeys, vsm)
