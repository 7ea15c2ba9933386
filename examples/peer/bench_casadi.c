/* Times CasADi's generated fast_newton rootfinder on the same points and from the same start
   as `stewart bench`. Usage: bench_casadi points.csv home_v.txt
   points.csv: header, then rows `kind,L1..L6,yaw,pitch,roll,x,y,z,v1..v18` (table-v --export). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "stewart_casadi.h"

#define MAX_POINTS 10000

static double now_us(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e6 + t.tv_nsec * 1e-3;
}

static int cmp(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: %s points.csv home_v.txt\n", argv[0]);
        return 2;
    }
    static double legs[MAX_POINTS][6], truth[MAX_POINTS][18];
    int n = 0;
    FILE *f = fopen(argv[1], "r");
    if (!f) { perror(argv[1]); return 2; }
    char line[8192];
    if (!fgets(line, sizeof line, f)) return 2;
    while (n < MAX_POINTS && fgets(line, sizeof line, f)) {
        char *tok = strtok(line, ",");
        double vals[40];
        int k = 0;
        while ((tok = strtok(NULL, ",\n")) && k < 40) vals[k++] = atof(tok);
        if (k < 30) continue;
        for (int j = 0; j < 6; j++) legs[n][j] = vals[j];
        for (int j = 0; j < 18; j++) truth[n][j] = vals[12 + j];
        n++;
    }
    fclose(f);
    double v0[18];
    f = fopen(argv[2], "r");
    if (!f) { perror(argv[2]); return 2; }
    for (int j = 0; j < 18; j++) if (fscanf(f, "%lf", &v0[j]) != 1) return 2;
    fclose(f);

    casadi_int sz_arg, sz_res, sz_iw, sz_w;
    stewart_rf_work(&sz_arg, &sz_res, &sz_iw, &sz_w);
    const casadi_real **arg = malloc(sizeof(casadi_real *) * (sz_arg > 2 ? sz_arg : 2));
    casadi_real **res = malloc(sizeof(casadi_real *) * (sz_res > 1 ? sz_res : 1));
    casadi_int *iw = malloc(sizeof(casadi_int) * (sz_iw + 1));
    casadi_real *w = malloc(sizeof(casadi_real) * (sz_w + 1));
    double v[18];
    static double times[MAX_POINTS * 4000];
    /* Each row's fastest pass: preemption on a shared machine only ever adds time. */
    static double best[MAX_POINTS];
    for (int i = 0; i < MAX_POINTS; i++) best[i] = INFINITY;
    int count = 0, passes = 0, failures = 0, off_truth = 0;
    double err_sum = 0.0;
    double start = now_us();
    while (passes < 3 || now_us() - start < 1e6) {
        for (int i = 0; i < n && count < MAX_POINTS * 4000; i++) {
            arg[0] = v0;
            arg[1] = legs[i];
            res[0] = v;
            double t0 = now_us();
            int flag = stewart_rf(arg, res, iw, w, 0);
            times[count] = now_us() - t0;
            if (times[count] < best[i]) best[i] = times[count];
            count++;
            if (passes == 0) {
                double d = 0, s = 0;
                for (int j = 0; j < 18; j++) { d += (v[j] - truth[i][j]) * (v[j] - truth[i][j]); s += truth[i][j] * truth[i][j]; }
                double rel = sqrt(d / s);
                if (flag != 0 || !isfinite(rel)) failures++;
                else if (rel >= 1e-3) off_truth++;
                else err_sum += rel;
            }
        }
        passes++;
    }
    qsort(times, count, sizeof(double), cmp);
    double mean = 0;
    for (int i = 0; i < count; i++) mean += times[i];
    mean /= count;
    double best_mean = 0;
    for (int i = 0; i < n; i++) best_mean += best[i];
    best_mean /= n;
    qsort(best, n, sizeof(double), cmp);
    printf("{\"method\": \"casadi_fast_newton\", \"points\": %d, \"repetitions\": %d, \"mean_us\": %.4f, \"median_us\": %.4f, \"p99_us\": %.4f, \"best_of_passes_mean_us\": %.4f, \"best_of_passes_median_us\": %.4f, \"failed\": %d, \"off_truth\": %d, \"mean_rel_error_ok\": %.3e}\n",
           n, passes, mean, times[count / 2], times[(int)((count - 1) * 0.99)], best_mean, best[(n - 1) / 2], failures, off_truth, err_sum / (n - failures - off_truth > 0 ? n - failures - off_truth : 1));
    return 0;
}
