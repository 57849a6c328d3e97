/* The machine's double-precision peak per core, measured: the clock (a
 * chain of dependent register-to-register integer adds retires one per
 * cycle on x86-64; adds of an immediate are not used, as Intel's Golden
 * Cove cores fold chains of them before they execute, which made this
 * probe read 22 GHz on a Sapphire Rapids Xeon), and
 * the time per fused multiply-add when twelve independent ones are in
 * flight, 256-bit (four doubles) and 512-bit (eight). FLOP per cycle =
 * FMAs per cycle x doubles x 2. Prints one JSON line; medians of 11 runs.
 *
 *   gcc -O2 -mavx512f -o /tmp/fma_peak bench/peak/fma_peak.c && taskset -c 1 /tmp/fma_peak
 *
 * (An x86-64 with AVX-512; without it, drop the 512-bit loop.) */
#include <stdio.h>
#include <stdint.h>
#include <time.h>
#include <stdlib.h>
/* Twelve independent fused multiply-adds on registers of kind R ("ymm":
   256-bit, "zmm": 512-bit): accumulators 0-11, operands 12 and 13. */
#define FMA(R, N) "vfmadd231pd %%" R "12,%%" R "13,%%" R #N "\n\t"
#define TWELVE_FMAS(R) FMA(R, 0) FMA(R, 1) FMA(R, 2) FMA(R, 3) FMA(R, 4) FMA(R, 5) \
                       FMA(R, 6) FMA(R, 7) FMA(R, 8) FMA(R, 9) FMA(R, 10) FMA(R, 11)
#define CLOBBERS ::: "xmm0", "xmm1", "xmm2", "xmm3", "xmm4", "xmm5", "xmm6", "xmm7", \
                     "xmm8", "xmm9", "xmm10", "xmm11"
static double now(void){struct timespec t;clock_gettime(CLOCK_MONOTONIC,&t);return t.tv_sec+1e-9*t.tv_nsec;}
static int cmp(const void*a,const void*b){double x=*(const double*)a,y=*(const double*)b;return (x>y)-(x<y);}
int main(void){
  enum{R=11}; double ghz[R], fma256[R], fma512[R];
  const long it=20000000;
  for(int r=0;r<R;r++){
    uint64_t x=0, one=1; double t0=now();
#define ADD "add %1,%0\n\t"
    for(long i=0;i<it;i++) __asm__ volatile(ADD ADD ADD ADD ADD ADD ADD ADD ADD ADD:"+r"(x):"r"(one));
    ghz[r]=10.0*it/(now()-t0)/1e9;
    t0=now();
    for(long i=0;i<it;i++) __asm__ volatile(TWELVE_FMAS("ymm") CLOBBERS);
    fma256[r]=(now()-t0)/(12.0*it)*1e9; /* ns per 256-bit FMA */
    t0=now();
    for(long i=0;i<it;i++) __asm__ volatile(TWELVE_FMAS("zmm") CLOBBERS);
    fma512[r]=(now()-t0)/(12.0*it)*1e9;
  }
  qsort(ghz,R,8,cmp);qsort(fma256,R,8,cmp);qsort(fma512,R,8,cmp);
  double g=ghz[R/2];
  printf("{\"ghz_median\": %.3f, \"ghz_max\": %.3f, \"fma256_ns\": %.4f, \"fma512_ns\": %.4f, \"fma256_per_cycle\": %.2f, \"fma512_per_cycle\": %.2f, \"dp_flop_per_cycle_256\": %.1f, \"dp_flop_per_cycle_512\": %.1f, \"dp_gflops_256\": %.1f, \"dp_gflops_512\": %.1f}\n",
    g, ghz[R-1], fma256[R/2], fma512[R/2], 1/(fma256[R/2]*g), 1/(fma512[R/2]*g), 8/(fma256[R/2]*g), 16/(fma512[R/2]*g), 8/fma256[R/2], 16/fma512[R/2]);
}
