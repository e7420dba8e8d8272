/* Internals of shooting shared by shooting.c (the problem per value, the period map,
 * Newton, the points), shooting_arclength.c (the entry, its operations for the shared drivers) and
 * shooting_natural.c (the bifurcation rule between sequential points). */
#ifndef GD_PERIODIC_SHOOTING_SHOOTING_IMPL_H
#define GD_PERIODIC_SHOOTING_SHOOTING_IMPL_H
#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"
#include "periodic/periodic_impl.h"

/* The problem at one value (speed or parameter): two are kept, so that the bordered
 * corrector, which needs the value and the value plus a difference step at every
 * iteration, rebuilds nothing while the value stays (shooting.c, gd_per_sh_problem). */
typedef struct shoot_prob {
    gd_tr_load *loads;       /* load_frequency: the loads at it (owned) */
    gd_transient_spec fspec; /* load_frequency: the caller's spec with them */
    double key;
    int have;
    gd_model *m;
    gd_system *s;
    gd_transient_model *tm;
    const gd_system *sys;
    const gd_transient_spec *spec;
    gd_transient *tr;
    int H, Nr;
    double w, T;
    double rhs_s; /* one right-hand side in seconds of counted work (0: not yet) */
} shoot_prob;

typedef struct shoot {
    const gd_system *sys0;
    const gd_transient_spec *spec0;
    const gd_periodic_param *param;
    const gd_periodic_options *opt;
    const gd_tr_record *rec;
    int nrec;
    gd_periodic_result *res;
    int cap_points, cap_bif;
    int dir, ndir;
    int steps; /* continuation steps taken (natural: one per value) */
    double v0, v1;
    shoot_prob slot[2];
    shoot_prob *p; /* the problem at the current value: one of slot */
    int N, nf, ndof;
    int *free_dof; /* nf: the system DOF of each free DOF */
    double rtol, atol_q, atol_v, tol;
    /* work: N each, phi and A N x N */
    double *mem; /* the allocation of phi .. mim (phi and A trade places) */
    double *phi, *A, *yT, *r, *dy, *yt, *q0, *qv0, *mre, *mim, *racc, *ytmp;
    int *ipiv;
    size_t capN;
    int capdof;
    char why[256];
    /* budget of a point (opt->shoot_budget), in seconds of counted work (work.c: the
     * integrator's right-hand sides times their counted flops, never a clock): spent on this
     * point, one plain period and one monodromy (0: not counted yet) */
    double work, t_period, t_mono;
    double last_work;   /* the last integration's */
    double warm_change; /* the last warm-start period's scaled change (NAN: none) */
    int warm_periods;
    int budget_hit;   /* the point stopped at its budget */
    int not_periodic; /* the periodicity probe's verdict (shooting.c): no orbit attracts */
    int dense;        /* the dense monodromy (else Newton-Krylov on monodromy-vector products) */
} shoot;

/* Matrix-free monodromy in scaled variables z = y / d (shooting.c, phi_vec): Phi z by a
 * forward difference of the period map about y (py = P(y)), or a central one (central),
 * work yt and pt (N each). The operator is Phi - shift I on n = N unknowns, or with a
 * border f (N) and row (N + 1) the bordered [Phi - shift I, f; row^T] on n = N + 1 (the
 * arclength's corrector). */
typedef struct kry {
    const double *y, *py, *d;
    double *yt, *pt;
    int n;
    double shift;
    const double *f, *row;
    int central;
} kry;

int gd_per_sh_gmres(shoot *sh, kry *k, const double *b, double *x, double tol, double stop2,
                    int cycles);
int gd_per_sh_problem(shoot *sh, double key);
void gd_per_sh_tolerances(shoot *sh, const double *y);
double gd_per_sh_norm(const shoot *sh, const double *y, const double *f);
void gd_per_sh_scales(const shoot *sh, const double *y, double *d);
int gd_per_sh_period(shoot *sh, const double *y, double *yT);
int gd_per_sh_monodromy(shoot *sh, const double *y, double *phi, double *yT);
int gd_per_sh_warm(shoot *sh, double *y);
/* 1 when the next job (predicted counted cost next) would take the point past its budget
 * (opt->shoot_budget): sh->why says so with what the warm start saw. */
int gd_per_sh_over_budget(shoot *sh, double next, const char *what);
/* The periodicity probe of an unsettled transient (shooting.c) from y (the state after
 * sh->warm_periods periods of a transient from `from`, named in the message): 1 no orbit
 * attracts it at T (sh->why gives the evidence, y the probe's last state), 0 no such
 * verdict (y unchanged: Newton goes on from it), -1 an integration failed (sh->why). */
int gd_per_sh_probe(shoot *sh, double *y, const char *from);
double gd_per_sh_noise(shoot *sh, const double *y);
int gd_per_sh_newton(shoot *sh, double *y, int *iters, double *resid);
int gd_per_sh_emit(shoot *sh, double key, const double *y, int iters, double resid);
int gd_per_sh_fail(shoot *sh, double key);
int gd_per_sh_add_bif(shoot *sh, gd_bifurcation_type type, double key, double mre, double mim);
void gd_per_sh_kinds(const double *re, const double *im, int n, double g[3], int at[3]);
/* Largest Krylov dimension (GMRES restart length, Arnoldi steps for the multipliers). */
#define KRYLOV_M 40
int gd_per_sh_multipliers(shoot *sh, const double *y, double *mre, double *mim);
/* The multipliers at y for the point's stability verdict in *stable (1 stable, 0 unstable,
 * -1 not determined): dense, all of them; matrix-free, Ritz values, the verdict only where
 * converged ones decide it (gd_ritz_verdict), Arnoldi run again to every state (N at most
 * KRYLOV_FULL) where the first KRYLOV_M leave it open. The note (cap bytes, "" when dense)
 * says which and, when not determined, why. Their count, -1 on failure (sh->why). */
int gd_per_sh_verdict(shoot *sh, const double *y, double *mre, double *mim, int *stable, char *note,
                      size_t cap);
/* Natural continuation's bifurcation rule (shooting_natural.c; method.h, between). */
int gd_per_sh_between(shoot *sh, const double *ya, double la, const double *yb, double lb);
void gd_per_sh_free(shoot *sh); /* everything sh owns (not sh) */

#endif
