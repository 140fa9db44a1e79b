// The exponential filter (esm; docs/techniques/esm.md): its keys struct and its row,
// kExponentialMap (exponential_map.cpp). One line of techniques/filters/all.h: the struct is
// declared once (the guard), the lines after it are read on every pass of that list.
#ifndef SHADOWLAB_FILTERS_ESM_H
#define SHADOWLAB_FILTERS_ESM_H
namespace shadowlab {

// Keys of the exponential filter.
struct EsmKeys {
  double c{};  // exponent on normalised distance (|p - L| / far)
};

}  // namespace shadowlab
#endif
SHADOWLAB_FILTER(Exponential, kExponentialMap)
SHADOWLAB_FILTER_KEYS(EsmKeys, esm)
