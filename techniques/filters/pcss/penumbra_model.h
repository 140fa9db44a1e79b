#pragma once
// The penumbra-width model of Datta et al.'s Neural Shadow Mapping supplemental (§4, eqs. 1–8;
// docs/design.md §6): an emitter of radius r_e facing a receiver at depth z_f (depths measured
// from the emitter along its axis), the occluders between depths z_min and z_max modelled as a
// sphere of radius r_s = (z_max − z_min)/2 centred on the axis at z_m = (z_max + z_min)/2:
//   θ_δ = asin(r_s / √(z_m² + r_e²))        the sphere's angular radius seen from the rim point A
//   BQ  = r_e·(z_f − z_m)/z_m               where the line from A through the centre lands
//   θ   = atan((BQ + r_e)/z_f)              that line's angle from the axis
//   x_a = z_f·tan(θ − θ_δ) − r_e,  x_b = z_f·tan(θ + θ_δ) − r_e
// x_a and x_b (lateral, from the axis, on the side opposite A) are where the two rays from A
// tangent to the sphere reach the receiver: the rim point's shadow of the sphere spans
// [x_a, x_b], the opposite rim's [−x_b, −x_a]. The receiver is fully lit beyond x_b and sees no
// emitter point inside −x_a (when x_a < 0: the umbra), so one side's transition from umbra to
// full light, the penumbra width, is w = x_a + x_b. Small angles give the classic PCSS width
// 2·r_e·(z_f − z_m)/z_m (Fernando 2005); for a disk emitter facing the receiver and a sphere
// on its axis the tangent construction is exact in the plane of symmetry (the caps' tangency
// lies in it), so x_a, x_b are the penumbra's exact ends in that case (tests/techniques/
// penumbra_model_test.cpp checks that against 3-D tangent geometry in long double).
//
// The 10–90 % width. The model gives the ends; the profile between them follows from the same
// geometry: the fraction of the emitter disk (radius r_e at depth 0, facing the receiver) that
// a receiver at lateral x sees past the model's sphere, integrated over a fixed grid of the disk
// (160 equal-area rings × 360 angles over the half disk the symmetry leaves). penumbra_transition
// measures the width between the points where that fraction crosses 10 % and 90 % of the way
// from its minimum (0 with an umbra) to 1, the rule measured_transition applies to a measured
// profile (programs/penumbra.cpp).
namespace shadowlab {

struct PenumbraModel {
  double z_m = 0.0, r_s = 0.0;
  double theta = 0.0, theta_delta = 0.0;  // radians
  double x_a = 0.0, x_b = 0.0;            // same units as the inputs
  double width = 0.0;                     // x_a + x_b: one side's umbra-to-lit transition
};

// Eqs. 1–8. Inputs in any one length unit, z_f > z_max >= z_min > 0, r_e >= 0 (a blocker
// behind the receiver, z_max >= z_f, as a receiver-plane bias allows, gives a small or negative
// width, which PCSS clamps to its smallest radius).
PenumbraModel penumbra_model(double r_e, double z_f, double z_min, double z_max);

// The model's lit fraction at lateral x on the receiver (the grid integral above).
double penumbra_lit_fraction(const PenumbraModel& m, double r_e, double z_f, double x);

// The width between the 10 % and 90 % points (of the way from the minimum to 1) of the model's
// profile, and the minimum itself.
struct PenumbraTransition {
  double width = 0.0;
  double x10 = 0.0, x90 = 0.0;
  double minimum = 0.0;
};
// For a thin occluder (z_min = z_max: r_s = 0) the model's sphere has no size and its width
// means an edge: under a disk emitter a straight edge's lit fraction is the share of the disk
// beyond a chord, which crosses 10 % and 90 % at ±disk_edge_1090_ratio() (0.6870) of the half
// width, so the 10–90 % width is that ratio × width.
PenumbraTransition penumbra_transition(const PenumbraModel& m, double r_e, double z_f);
double disk_edge_1090_ratio();

// The same rule on a sampled profile: positions x (increasing) and lit fractions v, crossings by
// linear interpolation between neighbouring samples (the first crossing from the shadowed
// side). width 0 when the profile never reaches the 90 % level.
PenumbraTransition measured_transition(const double* x, const double* v, int n);

}  // namespace shadowlab
