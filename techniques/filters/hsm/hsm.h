// A demonstration filter, the hard shadow map (hsm; docs/extending.md): its keys struct and its
// row, kHardMap (hard_map.cpp). One line of techniques/filters/all.h: the struct is declared
// once (the guard), the lines after it are read on every pass of that list.
#ifndef SHADOWLAB_FILTERS_HSM_H
#define SHADOWLAB_FILTERS_HSM_H
namespace shadowlab {

// Keys of the hard shadow map.
struct HsmKeys {
  double shade{};  // visibility of a shadowed receiver
};

}  // namespace shadowlab
#endif
SHADOWLAB_FILTER(Hard, kHardMap)
SHADOWLAB_FILTER_KEYS(HsmKeys, hsm)
