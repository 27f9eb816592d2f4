// The SH basis of the glossy response (prt_glossy.glsl, which includes this file).
// The real SH basis without its normalisation N_lm (folded into uDiffuse/uGlossy): with
// A_m + i B_m = (x + i y)^m and P̃_l^m = P_l^m / ρ^m (Condon–Shortley phase, ρ = sqrt(x² + y²)),
//   m > 0: P̃_l^m(z) A_m,   m < 0: P̃_l^|m|(z) B_|m|,   m = 0: P_l(z);
// P̃_m^m = (−1)^m (2m−1)!!, P̃_{m+1}^m = (2m+1) z P̃_m^m,
// P̃_l^m = ((2l−1) z P̃_{l−1}^m − (l+m−1) P̃_{l−2}^m) / (l−m).
void shBasis(vec3 d, int bands, out float y[PRT_GLOSSY_COEFFS]) {
  float a = 1.0, b = 0.0;  // A_m, B_m
  float pmm = 1.0;         // P̃_m^m
  for (int m = 0; m < bands; ++m) {
    if (m > 0) {
      float a1 = a * d.x - b * d.y;
      b = a * d.y + b * d.x;
      a = a1;
      pmm *= -float(2 * m - 1);
    }
    float p2 = 0.0, p1 = pmm;  // P̃_{l−1}^m, P̃_l^m walking up l from m
    for (int l = m; l < bands; ++l) {
      if (l == m + 1) {
        p2 = p1;
        p1 = float(2 * m + 1) * d.z * pmm;
      } else if (l > m + 1) {
        float p = (float(2 * l - 1) * d.z * p1 - float(l + m - 1) * p2) / float(l - m);
        p2 = p1;
        p1 = p;
      }
      int c = l * (l + 1);
      if (m == 0) {
        y[c] = p1;
      } else {
        y[c + m] = p1 * a;
        y[c - m] = p1 * b;
      }
    }
  }
}
