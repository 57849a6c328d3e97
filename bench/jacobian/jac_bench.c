/* Times CasADi-generated Jacobians (casadi_jacobian.py), in the format of the
 * other peers' harnesses (../shared/bench/casadi/cas_bench.c) and of
 * autosim_jacobian_bench (src/main.rs), so that rounds interleave and pool.
 *
 * Every model is one CasADi function NAME(arg = {x[NX], w[NW]},
 * res = {A, B, C, D}) writing the matrices dense and row-major
 * (A: NLIN x NLIN, B: NLIN x NW, C: NY x NLIN, D: NY x NW); models without
 * inputs or outputs have fewer results (jac_models.inc says how many).
 *
 * Build: see run.sh (gcc -O3 -march=native, no LTO: every call goes through
 * CasADi's generated entry point as a user's would).
 *
 *   jac_bench bench ROUNDS STATES_DIR   one JSON line per model:
 *       {"model", "method": "casadi", "calls_per_batch": 1000, "batches_ns": [...]}
 *       every batch = one call at each of the 1000 states in
 *       STATES_DIR/<model>.txt; batches per round calibrated to about 0.04 s
 *       (7..601), as the other harnesses.
 *   jac_bench dump MODEL STATES_FILE     A, B, C, D at every state, one line each
 *   jac_bench list                       model nx nw nlin ny (one line each)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef long long int casadi_int_t;
typedef int (*cas_fn)(const double **arg, double **res, casadi_int_t *iw, double *w, int mem);
typedef int (*cas_work_fn)(casadi_int_t *sz_arg, casadi_int_t *sz_res, casadi_int_t *sz_iw,
                           casadi_int_t *sz_w);
typedef struct {
  const char *name;
  int nx, nw, nlin, ny;
  cas_fn f;
  cas_work_fn work;
} model_t;

#include "jac_models.inc" /* declarations + static const model_t MODELS[]; NMODELS */

#define NS 1000
#define MAXW (1 << 22)

static double now_ns(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return 1e9 * t.tv_sec + t.tv_nsec;
}

static casadi_int_t g_iw[MAXW];
static double g_w[MAXW];
static const double *g_arg[64];
static double *g_res[64];
volatile double g_sink;

static void check_work(const model_t *m) {
  casadi_int_t a = 0, r = 0, iw = 0, w = 0;
  m->work(&a, &r, &iw, &w);
  if (a > 64 || r > 64 || iw > MAXW || w > MAXW) {
    fprintf(stderr, "work arrays too small for %s\n", m->name);
    exit(2);
  }
}

/* The matrices' sizes, in result order A, B, C, D (empty ones skipped). */
static int sizes(const model_t *m, int *len) {
  int k = 0;
  int all[4] = {m->nlin * m->nlin, m->nlin * m->nw, m->ny * m->nlin, m->ny * m->nw};
  for (int i = 0; i < 4; ++i)
    if (all[i] > 0) len[k++] = all[i];
  return k;
}

typedef struct {
  const model_t *m;
  double *X, *W, *out;
  int nres, len[4];
  int R, nb;
  double *batches;
} case_t;

static void setup(case_t *c, const model_t *m) {
  c->m = m;
  c->nres = sizes(m, c->len);
  int total = 0;
  for (int i = 0; i < c->nres; ++i) total += c->len[i];
  c->out = calloc(total, sizeof(double));
  c->W = calloc(m->nw > 0 ? m->nw : 1, sizeof(double)); /* inputs at zero */
}

static inline void call(case_t *c, const double *x) {
  g_arg[0] = x;
  g_arg[1] = c->W;
  double *o = c->out;
  for (int i = 0; i < c->nres; ++i) {
    g_res[i] = o;
    o += c->len[i];
  }
  c->m->f(g_arg, g_res, g_iw, g_w, 0);
}

/* Reads up to max rows of nx numbers; returns how many. */
static int read_states(const char *path, int nx, double *X, int max) {
  FILE *f = fopen(path, "r");
  if (!f) { fprintf(stderr, "cannot read %s\n", path); exit(2); }
  int s = 0;
  while (s < max) {
    int i = 0;
    for (; i < nx; ++i)
      if (fscanf(f, "%lf", &X[(size_t)s * nx + i]) != 1) break;
    if (i < nx) break;
    ++s;
  }
  fclose(f);
  return s;
}

static const model_t *find(const char *name) {
  for (int k = 0; k < NMODELS; ++k)
    if (!strcmp(MODELS[k].name, name)) return &MODELS[k];
  fprintf(stderr, "no model %s\n", name);
  exit(2);
}

static double run_batch(case_t *c) {
  double acc = 0;
  for (int s = 0; s < NS; ++s) {
    call(c, c->X + (size_t)s * c->m->nx);
    acc += c->out[0];
  }
  return acc;
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s bench ROUNDS STATES_DIR | dump MODEL STATES_FILE | list\n", argv[0]);
    return 2;
  }
  for (int k = 0; k < NMODELS; ++k) check_work(&MODELS[k]);
  if (!strcmp(argv[1], "list")) {
    for (int k = 0; k < NMODELS; ++k)
      printf("%s %d %d %d %d\n", MODELS[k].name, MODELS[k].nx, MODELS[k].nw, MODELS[k].nlin,
             MODELS[k].ny);
    return 0;
  }
  if (!strcmp(argv[1], "dump") && argc == 4) {
    case_t c = {0};
    setup(&c, find(argv[2]));
    c.X = malloc(sizeof(double) * NS * c.m->nx);
    int ns = read_states(argv[3], c.m->nx, c.X, NS);
    for (int s = 0; s < ns; ++s) {
      call(&c, c.X + (size_t)s * c.m->nx);
      int total = 0;
      for (int i = 0; i < c.nres; ++i) total += c.len[i];
      for (int i = 0; i < total; ++i) printf("%s%.17g", i ? " " : "", c.out[i]);
      printf("\n");
    }
    return 0;
  }
  if (strcmp(argv[1], "bench") || argc != 4) { fprintf(stderr, "bad arguments\n"); return 2; }
  const int ROUNDS = atoi(argv[2]);
  case_t *cases = calloc(NMODELS, sizeof(case_t));
  for (int k = 0; k < NMODELS; ++k) {
    case_t *c = &cases[k];
    setup(c, &MODELS[k]);
    c->X = malloc(sizeof(double) * NS * c->m->nx);
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.txt", argv[3], c->m->name);
    if (read_states(path, c->m->nx, c->X, NS) != NS) {
      fprintf(stderr, "%s: fewer than %d states\n", path, NS);
      return 2;
    }
    double acc = run_batch(c); /* warm-up */
    double t0 = now_ns();
    acc += run_batch(c);
    double one = now_ns() - t0;
    g_sink = acc;
    int R = (int)(0.04e9 / (one > 1 ? one : 1));
    c->R = R < 7 ? 7 : R > 601 ? 601 : R;
    c->batches = malloc(sizeof(double) * c->R * ROUNDS);
  }
  for (int round = 0; round < ROUNDS; ++round)
    for (int k = 0; k < NMODELS; ++k) {
      case_t *c = &cases[k];
      double acc = run_batch(c); /* warm-up */
      for (int r = 0; r < c->R; ++r) {
        double t0 = now_ns();
        acc += run_batch(c);
        c->batches[c->nb++] = (now_ns() - t0) / NS;
      }
      g_sink = acc;
    }
  for (int k = 0; k < NMODELS; ++k) {
    case_t *c = &cases[k];
    printf("{\"model\": \"%s\", \"method\": \"casadi\", \"calls_per_batch\": %d, \"batches_ns\": [",
           c->m->name, NS);
    for (int r = 0; r < c->nb; ++r) printf("%s%.3f", r ? ", " : "", c->batches[r]);
    printf("]}\n");
  }
  return 0;
}
