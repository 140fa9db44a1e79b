// Depth compare with PCF (sm; docs/techniques/depth_compare.md): its row is kDepthCompare
// (depth_compare.cpp). Its keys (pcf, pcf_kind, taps, rpdb, seams) are members of MapParams
// itself, since stage 2 (techniques/pipeline/faces_needed.h) and the guard band read them too.
// One line of techniques/filters/all.h, read once per pass of that list (no include guard).
SHADOWLAB_FILTER(Depth, kDepthCompare)
