/* Times or dumps a model's SymPy C (rhs.c, written by derive.py) at the
 * states derive.py drew, as ../peers times its peers: 1000 states, batches
 * of 1000 calls, about 0.04 s of batches per model and round.
 * Compile with -DMODEL=<name> -DRHS=<name>_rhs -DEVAL=<name>_eval -DNX=<states>
 * -DNPAR=<parameters> -DNU=<all speeds>.
 *   harness bench DIR   prints two JSON lines (ns per call of every batch):
 *                       method sympy_lu, the whole state derivative (RHS),
 *                       and sympy_eval, M, f and dq/dt without the solve (EVAL)
 *   harness dump DIR    writes DIR/dx_sympy.bin (dx at every state) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define NS 1000
#define STR2(x) #x
#define STR(x) STR2(x)

void RHS(const double *x, const double *p, double *dx);
void EVAL(const double *x, const double *p, double *M, double *f, double *dx);

static double X[NS][NX], DX[NS][NX], PAR[NPAR];
volatile double g_sink;

static double now_ns(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return 1e9 * t.tv_sec + t.tv_nsec;
}

static void read_all(const char *dir, const char *name, double *to, size_t n) {
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "rb");
  if (!f || fread(to, sizeof(double), n, f) != n) { fprintf(stderr, "cannot read %zu doubles from %s\n", n, path); exit(1); }
  fclose(f);
}

static double pass_rhs(void) {
  double acc = 0, dx[NX];
  for (int s = 0; s < NS; ++s) { RHS(X[s], PAR, dx); acc += dx[NX - 1]; }
  return acc;
}

static double pass_eval(void) {
  double acc = 0, dx[NX], M[NU * NU], f[NU];
  for (int s = 0; s < NS; ++s) { EVAL(X[s], PAR, M, f, dx); acc += M[NU * NU - 1] + f[NU - 1]; }
  return acc;
}

static void bench(const char *method, double (*pass)(void)) {
  double acc = pass();
  double t0 = now_ns();
  acc += pass();
  double one = now_ns() - t0;
  int R = (int)(0.04e9 / (one > 1 ? one : 1));
  if (R < 7) R = 7;
  if (R > 601) R = 601;
  printf("{\"kind\": \"%s\", \"tool\": \"sympy\", \"method\": \"%s\", \"calls_per_batch\": %d, \"batches_ns\": [", STR(MODEL), method, NS);
  for (int r = 0; r < R; ++r) {
    t0 = now_ns();
    acc += pass();
    printf("%s%.3f", r ? ", " : "", (now_ns() - t0) / NS);
  }
  printf("]}\n");
  g_sink = acc;
}

int main(int argc, char **argv) {
  if (argc != 3) { fprintf(stderr, "usage: %s bench|dump DIR\n", argv[0]); return 2; }
  read_all(argv[2], "states.bin", &X[0][0], NS * NX);
  read_all(argv[2], "params.bin", PAR, NPAR);
  if (strcmp(argv[1], "dump") == 0) {
    char path[4096];
    snprintf(path, sizeof path, "%s/dx_sympy.bin", argv[2]);
    for (int s = 0; s < NS; ++s) RHS(X[s], PAR, DX[s]);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(DX, sizeof(double), NS * NX, f) != NS * NX) { fprintf(stderr, "cannot write %s\n", path); return 1; }
    fclose(f);
    return 0;
  }
  bench("sympy_lu", pass_rhs);
  bench("sympy_eval", pass_eval);
  return 0;
}
