// The moment filter (msm; docs/techniques/msm.md): its keys struct and its row,
// kMomentShadowMap (moment_shadow_map.cpp; the reconstruction in moment_bound.h). One line of
// techniques/filters/all.h: the struct is declared once (the guard), the lines after it are read
// on every pass of that list.
#ifndef SHADOWLAB_FILTERS_MSM_H
#define SHADOWLAB_FILTERS_MSM_H
namespace shadowlab {

// Keys of the moment filter. The moments are filtered in float and stored as 4 floats per
// texel, or (quantize16) through Peters & Klein's optimized 16-bit quantization, whose coarser
// rounding needs the larger default α.
struct MsmKeys {
  bool hausdorff{};   // variant=hausdorff (support [0, 1]) instead of hamburger (support ℝ)
  bool quantize16{};  // store 4 × 16 bits instead of 4 × fp32
  double alpha{};     // moment bias toward (½, ½, ½, ½)
};

}  // namespace shadowlab
#endif
SHADOWLAB_FILTER(Moment, kMomentShadowMap)
SHADOWLAB_FILTER_KEYS(MsmKeys, msm)
