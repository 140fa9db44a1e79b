#pragma once
// The shadow quality metric of Kluczek ("Quality Metric for Shadow Rendering") as pinned down in
// docs/design.md §5: every submetric, the four groups, the weighted total, and SSIM/RMSE/PSNR
// and FLIP.
#include "core/image.h"
#include "metric/box_blur.h"
#include "metric/contour.h"
#include "metric/detail.h"
#include "metric/flip.h"
#include "metric/performance.h"

namespace shadowlab {

// Group weights of the total (each ≥ 0, finite) and the frame rate that sets T_ref.
struct MetricWeights {
  double fidelity = 1.0;
  double aesthetics = 1.0;
  double detail = 1.0;
  double performance = 1.0;  // ignored when no timings are given
  double target_fps = 30.0;  // T_ref = 1000/target_fps ms
};

// Every submetric in [0, 1] (1 = perfect), the group scores and the extras.
struct MetricReport {
  double c10 = 0, c50 = 0, c90 = 0;  // contour match at blurred levels 0.1, 0.5, 0.9
  double dark = 0, lit = 0;          // dark / lit area coverage
  double acne = 0, noise = 0;        // Roberts-cross roughness in the lit / dark region
  double detail = 1;                 // 1/S_ratio; 1 without a texel image
  bool has_performance = false;      // timings were given
  double performance = 1;            // RP; 1 (and left out of the total) without timings
  double fidelity = 0;               // mean(c10, c50, c90, dark, lit)
  double aesthetics = 0;             // mean(acne, noise)
  double total = 0;                  // weighted mean of the groups
  double ssim = 0;                   // mean SSIM of the unblurred masks
  double rmse = 0;                   // RMSE of the unblurred masks (data range 1)
  double psnr = 0;                   // dB, capped at kPsnrCapDb (identical masks give the cap)
  double flip_mean = 0;              // mean LDR-FLIP of the masks as grey images (0 = same)
  int blur_size = 0;                 // box-blur side k used for B_T and B_R
};

// Buffers compute_metric can reuse from call to call (about 24 MB at 1024×768). Pass the same
// object to every call of a sweep: a fresh buffer costs a page fault per 4 KiB on first touch,
// which can cost as much as the metric itself. One scratch per concurrent caller.
struct MetricScratch {
  ImageD blurred_test, blurred_ref;  // B_T and B_R
  ContourScratch contour;
  DetailScratch detail;
  // The reference's half of FLIP (metric/flip.h) and the reference it was made from, reused by
  // the next call whose reference equals it value for value (a sweep's or a tune's every row).
  FlipPrepared flip_ref;
  ImageF flip_ref_image;
};

// Scores test mask T against reference mask R (1-channel, same size, values in [0, 1]).
// `texels` (optional) is T's texel-index image, same size; `timings` (optional) gives the
// performance score. The result is bit-identical for any thread count. Throws
// InputError("metric", …) for empty, multi-channel or differently sized images, a value outside
// [0, 1] (NaN, inf), a badly sized texel image, bad timings, or bad weights (negative, non-finite,
// or all used weights zero). `scratch` (optional) only saves allocations; results are the same.
MetricReport compute_metric(const ImageF& test, const ImageF& ref, const ImageU32* texels,
                            const Timings* timings, const MetricWeights& weights = {},
                            MetricScratch* scratch = nullptr);

}  // namespace shadowlab
