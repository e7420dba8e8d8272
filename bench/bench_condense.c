/* Cost of the condensation onto the meshes' coordinates (docs/condense.md) against the
 * direct sparse solve it replaces: building it once, then H_c at N frequencies, against
 * KLU factor + solve at the same N frequencies (gd_condense_direct, one thread), and the
 * largest difference between the two. Prints figures; asserts nothing.
 * usage: bench_condense MODEL.yaml [NFREQ [NMODES [dense|sparse]]]   (NMODES 0: all) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "geardyn/condense.h"
#include "geardyn/model_file.h"

static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s MODEL.yaml [NFREQ [NMODES]]\n", argv[0]);
        return 2;
    }
    int nf = argc > 2 ? atoi(argv[2]) : 200, nmodes = argc > 3 ? atoi(argv[3]) : 0;
    gd_error err;
    gd_model *m;
    gd_system *s;
    if (gd_model_load(argv[1], &m, &err) || gd_system_build(m, &s, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 2;
    }
    gd_condense_coords cc;
    gd_condense_coords_init(&cc);
    if (gd_condense_coords_meshes(&cc, s, &err)) return 2;
    int nc = cc.n;
    double *w = malloc((size_t)nf * sizeof *w);
    for (int k = 0; k < nf; k++) /* 10 Hz .. 10 kHz, log-spaced */
        w[k] = 2 * 3.14159265358979 * 10 * pow(1000.0, k / (nf - 1.0));
    double *Hd = malloc((size_t)2 * nc * nc * nf * sizeof *Hd),
           *H = malloc((size_t)2 * nc * nc * sizeof *H);
    printf("model %s: %d DOFs, %d coordinates, %d frequencies\n", argv[1], s->ndof, nc, nf);
    double t0 = cpu_now();
    if (gd_condense_direct(s, &cc, 0.0, nf, w, Hd, &err)) {
        fprintf(stderr, "direct: %s\n", err.message);
        return 1;
    }
    double t_direct = cpu_now() - t0;
    printf("direct (KLU per frequency): %.4f s, %.3g ms per frequency\n", t_direct,
           1e3 * t_direct / nf);
    gd_condense_options o;
    gd_condense_options_init(&o);
    o.nmodes = nmodes;
    if (argc > 4) o.method = argv[4][0] == 's' ? GD_CONDENSE_SPARSE : GD_CONDENSE_DENSE;
    gd_condensation *c;
    t0 = cpu_now();
    if (gd_condense_build(s, &cc, &o, &c, &err)) {
        printf("condensation: not built (%s)\n", err.message);
        return 0;
    }
    double t_build = cpu_now() - t0;
    t0 = cpu_now();
    gd_condense_info info;
    gd_condense_info_get(c, &info);
    double worst = 0, worst_est = 0, worst_hi = 0, worst_est_hi = 0; /* below / above w_d/2 */
    for (int k = 0; k < nf; k++) {
        double est;
        gd_condense_receptance(c, w[k], H, &est);
        double d = 0, mx = 0;
        for (int i = 0; i < nc * nc; i++) {
            const double *r = Hd + (size_t)2 * nc * nc * k + 2 * i;
            d = fmax(d, hypot(H[2 * i] - r[0], H[2 * i + 1] - r[1]));
            mx = fmax(mx, hypot(r[0], r[1]));
        }
        if (w[k] <= 0.5 * info.first_discarded) {
            worst = fmax(worst, d / mx);
            worst_est = fmax(worst_est, est / mx);
        } else {
            worst_hi = fmax(worst_hi, d / mx);
            worst_est_hi = fmax(worst_est_hi, est / mx);
        }
    }
    double t_eval = cpu_now() - t0;
    printf("condensation: %d modes kept, %d discarded (first at %.1f Hz), %d rigid\n", info.nkept,
           info.ndiscarded, info.first_discarded / (2 * 3.14159265358979), info.nrigid);
    printf("  build %.4f s; H_c at %d frequencies %.3g ms (%.3g us each)\n", t_build, nf,
           1e3 * t_eval, 1e6 * t_eval / nf);
    printf("  largest difference to direct, relative per frequency: %.2e (estimate %.2e) up to "
           "half the first discarded mode, %.2e (estimate %.2e) above\n",
           worst, worst_est, worst_hi, worst_est_hi);
    printf("  ratio direct / evaluation: %.0f; direct / (build + evaluation): %.2f\n",
           t_direct / t_eval, t_direct / (t_build + t_eval));
    printf("  break-even: the build pays off after %.0f frequencies\n",
           t_build / (t_direct / nf - t_eval / nf));
    gd_condense_destroy(c);
    gd_condense_coords_release(&cc);
    free(w);
    free(H);
    free(Hd);
    gd_system_free(s);
    gd_model_free(m);
    return 0;
}
