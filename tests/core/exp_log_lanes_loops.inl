// The scalar functions of core/exp_log.h in loops the compiler vectorizes for the including
// file's set (the ESM filter's loops are of this kind). flatten inlines every call into the
// loop, so that no out-of-line copy of exp_d and the others is compiled for this set (the
// linker could pick it for baseline callers).
[[gnu::flatten]] void exp_loop(const double* x, double* y, int n) {
  for (int i = 0; i < n; ++i) y[i] = exp_d(x[i]);
}
[[gnu::flatten]] void expf_loop(const float* x, float* y, int n) {
  for (int i = 0; i < n; ++i) y[i] = exp_f(x[i]);
}
[[gnu::flatten]] void log_loop(const double* x, double* y, int n) {
  for (int i = 0; i < n; ++i) y[i] = log_d(x[i]);
}
