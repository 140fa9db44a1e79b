// Percentage-closer soft shadows (pcss; docs/techniques/pcss.md): its keys struct and its row,
// kPcss (pcss.cpp): a blocker search, the penumbra width from the mean blocker distance, then
// rotated Poisson PCF over that width. One line of techniques/filters/all.h: the struct is
// declared once (the guard), the lines after it are read on every pass of that list.
#ifndef SHADOWLAB_FILTERS_PCSS_H
#define SHADOWLAB_FILTERS_PCSS_H
namespace shadowlab {

// Keys of percentage-closer soft shadows.
struct PcssKeys {
  double light_size{};   // light radius, m; < 0: the scene light's radius
  int search{};          // blocker-search taps (rotated Poisson disk)
  int taps{};            // PCF taps (rotated Poisson disk)
  double search_near{};  // nearest blocker searched for, × the receiver's distance
  bool model{};          // the penumbra from penumbra_model.h, not the mean blocker
};

}  // namespace shadowlab
#endif
SHADOWLAB_FILTER(Pcss, kPcss)
SHADOWLAB_FILTER_KEYS(PcssKeys, pcss)
