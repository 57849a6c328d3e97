/* Solves A x = b (A n x n, row-major, overwritten; b overwritten) by LU
 * with partial pivoting: what a SymPy user's C does with KanesMethod's
 * mass matrix and forcing (not symmetric with constraints, so no Cholesky).
 * n is a compile-time constant at every call, so gcc -O3 unrolls it. */
#ifndef CONSTRAINED_LU_H
#define CONSTRAINED_LU_H
#include <math.h>

static inline void lu_solve(int n, double *a, double *b, double *x) {
  for (int k = 0; k < n; ++k) {
    int piv = k;
    for (int i = k + 1; i < n; ++i)
      if (fabs(a[i * n + k]) > fabs(a[piv * n + k])) piv = i;
    if (piv != k) {
      for (int j = 0; j < n; ++j) {
        double t = a[k * n + j]; a[k * n + j] = a[piv * n + j]; a[piv * n + j] = t;
      }
      double t = b[k]; b[k] = b[piv]; b[piv] = t;
    }
    for (int i = k + 1; i < n; ++i) {
      double l = a[i * n + k] / a[k * n + k];
      for (int j = k + 1; j < n; ++j) a[i * n + j] -= l * a[k * n + j];
      b[i] -= l * b[k];
    }
  }
  for (int i = n - 1; i >= 0; --i) {
    double s = b[i];
    for (int j = i + 1; j < n; ++j) s -= a[i * n + j] * x[j];
    x[i] = s / a[i * n + i];
  }
}
#endif
