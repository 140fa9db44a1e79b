// The vector row of techniques/rt/atrous.h, written once for AVX2 and AVX-512: included inside
// the ISA file's namespace after its lane helpers (V, kL, vset1, vloadu, vmaskload (lanes whose
// x lies in [0, w): other lanes 0, never read), vabs, vmax, vdiv, vexp, vpositive, vselect_nonzero,
// vmaskstore). Per pixel the same float operations in the same order as the scalar row.

void row(const AtrousRow& r) {
  const AtrousGuide& gd = *r.guide;
  const int w = gd.width, h = gd.height, y = r.y, s = r.step;
  const float* hw = atrous_tap_weights();
  const size_t row0 = size_t(y) * size_t(w);
  for (int x0 = 0; x0 < w; x0 += kL) {
    const size_t p = row0 + size_t(x0);
    const V fp = vmaskload(gd.f.data() + p, x0, w);
    const V zp = vmaskload(gd.z.data() + p, x0, w);
    const V gp = vmaskload(gd.g.data() + p, x0, w);
    const V nxp = vmaskload(gd.nx.data() + p, x0, w);
    const V nyp = vmaskload(gd.ny.data() + p, x0, w);
    const V nzp = vmaskload(gd.nz.data() + p, x0, w);
    const V in_p = vmaskload(r.in + p, x0, w);
    const V var_p = vmaskload(r.var_in + p, x0, w);
    const V vden = vadd(vmul(vset1(r.sigma_v), vsqrt(var_p)), vset1(kAtrousValueEps));
    const V vinv = r.sigma_v > 0.0f ? vdiv(vset1(1.0f), vden) : vset1(0.0f);
    V sum = vset1(0.0f), wsum = vset1(0.0f), vsum = vset1(0.0f);
    for (int j = 0; j < 5; ++j) {
      const int qy = y + (j - 2) * s;
      if (qy < 0 || qy >= h) continue;
      for (int i = 0; i < 5; ++i) {
        const int qx0 = x0 + (i - 2) * s;
        const size_t q = size_t(qy) * size_t(w);  // row start; lanes at qx0 + lane
        const V fq = vmaskload_at(gd.f.data() + q, qx0, w);
        const V zq = vmaskload_at(gd.z.data() + q, qx0, w);
        const V dz = vabs(vsub(zp, zq));
        const V dv = vabs(vsub(in_p, vmaskload_at(r.in + q, qx0, w)));
        const V arg = vneg(vadd(vdiv(dz, vadd(vmul(gp, vset1(r.tap_c[j * 5 + i])), vset1(kAtrousDepthEps))),
                                vmul(dv, vinv)));
        const V e = vexp(vmax(arg, vset1(kAtrousMinExponent)));
        const V d = vadd(vadd(vmul(nxp, vmaskload_at(gd.nx.data() + q, qx0, w)),
                              vmul(nyp, vmaskload_at(gd.ny.data() + q, qx0, w))),
                         vmul(nzp, vmaskload_at(gd.nz.data() + q, qx0, w)));
        V wn = vpositive(d);
        for (int k = 0; k < r.normal_power; ++k) wn = vmul(wn, wn);
        const V wt = vmul(vmul(vmul(vset1(hw[j * 5 + i]), e), wn), fq);
        sum = vadd(sum, vmul(wt, vmaskload_at(r.in + q, qx0, w)));
        wsum = vadd(wsum, wt);
        vsum = vadd(vsum, vmul(vmul(wt, wt), vmaskload_at(r.var_in + q, qx0, w)));
      }
    }
    vmaskstore(r.var_out + p, x0, w, vselect_nonzero(fp, vdiv(vsum, vmul(wsum, wsum)), var_p));
    vmaskstore(r.out + p, x0, w, vselect_nonzero(fp, vdiv(sum, wsum), in_p));
  }
}
