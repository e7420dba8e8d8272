/* Internals of the continuation shared by run.c, stage.c, corrector.c, points.c,
 * bifurcation.c and continuation.c: the problem per value (stage), the run's context and
 * the functions each file offers the others. */
#ifndef GD_PERIODIC_CONTINUATION_IMPL_H
#define GD_PERIODIC_CONTINUATION_IMPL_H
#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"
#include "periodic/periodic_impl.h"

#ifndef TWO_PI
#define TWO_PI 6.28318530717958647692
#endif

typedef struct stage {
    int valid;
    long id; /* distinct for every problem made (factorisation reuse) */
    double key;
    gd_model *m;
    gd_system *s;
    gd_transient_model *tm;
    gd_transient *tr;
    gd_tr_load *loads;       /* load_frequency: the loads at this value (owned) */
    gd_transient_spec fspec; /* load_frequency: the caller's spec with them */
    const gd_system *sys;    /* the problem of this stage (either kind) */
    const gd_transient_spec *spec;
    double w; /* HB frequency */
    int bad;  /* the problem could not be made: reason in msg */
    char msg[320];
} stage;

typedef struct ctx {
    const gd_system *sys;
    const gd_transient_spec *spec;
    const gd_periodic_param *param;
    const gd_periodic_options *opt;
    stage st[2];
    int next;
    int nf;
    hb h;
    int H;
    double sx, sl; /* scales of X and of the parameter */
    double rate0;  /* w / lambda of the branch (speed continuation), or w (parameter) */
    int ratio_mode;
    char reason[320];
    char floquet_msg[200]; /* why the last Floquet multipliers were not computed */
    int floquet_n;         /* multipliers the last gd_per_floquet delivered (the rest 0) */
    int floquet_krylov;    /* 1: they are the largest by Krylov (floquet_krylov.c) */
    int floquet_basis;     /* > 0: the reduced basis's size (floquet_reduced.c) */
    int floquet_steps;     /* the Magnus steps per period of the last multipliers */
    gd_periodic_result *res;
    int cap_points, cap_bif;
    const gd_tr_record *rec;
    int nrec;
    int dir;
    int steps;
    int near_fold; /* a fold on this step or the last: a real multiplier at +1 is it */
    long serial;   /* stages made */
    hb hr;         /* the refined workspace (2 H) of the truncation estimate */
    int Hr;        /* its H (0: none) */
    int Hcap;      /* largest H allowed (memory or max_harmonics) */
    int want_H;    /* adaptive H: the branch's H to follow */
    double v0, v1; /* the requested range of this direction (progress) */
    int ndir;
    int min_samples; /* AFT samples at least (backlash: 128, non-smooth laws: 1024) */
    double climbed;  /* the highest tooth of the last turn climbed (gd_per_climb_teeth) */
    int climb_dir;   /* its direction (0: none) and H */
    int climb_H;
    int shoot_stab;         /* the multipliers from the orbit corrected by shooting */
    int floquet_shooting;   /* 1: the last multipliers came from it (floquet_shooting.c) */
    double floquet_change;  /* its correction of the orbit (scaled), or NAN */
    char floquet_note[200]; /* why the correction failed (the Magnus multipliers stand) */
    int corners;            /* a non-smooth law: a step whose turn does not shrink when halved is
                               a corner of the sampled branch, taken (continuation.c) */
    long chb_solves;        /* fixed-value solves by the condensed harmonic balance */
    long chb_tried;         /* and those it was tried on (the rest: the full Newton) */
    int chb_nc;             /* its coordinate count */
    int chb_streak;         /* its failures in a row: from 3 on, not tried again (default) */
} ctx;

typedef struct pstate {
    double *X; /* n + 1 (parameter last unused) */
    double lam;
    int iters;
    double resid;
    int stable;
    double mu_max;
    double *mre, *mim;
} pstate;

void gd_per_stage_clear(stage *s);
int gd_per_make_stage(ctx *c, stage *s, double key);
stage *gd_per_get_stage(ctx *c, double key);
double gd_per_norm2(const double *x, int n);
int gd_per_newton(ctx *c, double *X, double *lam, const double *tan, const double *yp, int *iters,
                  double *resid);
int gd_per_tangent(ctx *c, const double *X, double lam, const double *prev, double sign, double *t);
int gd_per_hb_setup(ctx *c, int H);
/* The reduced-basis multipliers of X at stage s (points.c: the cut-off from the highest
 * excitation frequency); steps > 0 fixed, 0 chosen by gd_hb_floquet_reduced up to
 * steps_cap; the return codes of gd_hb_floquet_reduced, its reason in c->floquet_msg. */
int gd_per_floquet_reduced(ctx *c, stage *s, const double *X, double lam, int steps, int steps_cap,
                           int *steps_used, const gd_tr_record *bl, int nbl, double *mre,
                           double *mim, int *nmu, int *nbasis);
void gd_per_floquet(ctx *c, const double *X, double lam, double *mre, double *mim, int *stable,
                    double *mu_max);
int gd_per_fail_point(ctx *c, double lam, const char *why);
int gd_per_emit_point(ctx *c, const double *X, double lam, int iters, double resid);
void gd_per_categorise(const ctx *c, const double *mre, const double *mim, int out[3],
                       double rho[3]);
int gd_per_add_bif(ctx *c, gd_bifurcation_type type, double lam, double mre, double mim);
double gd_per_ranked(const ctx *c, const double *mre, const double *mim, int m, int *at);
int gd_per_locate(ctx *c, int m, const double *Xa, double la, double ga, const double *Xb,
                  double lb, double gb, const double *tan, const double *mre_b,
                  const double *mim_b);
int gd_per_locate_turn(ctx *c, const double *Xp, double lp, const double *X, double l,
                       const double *X1, double l1, double *lf, double *Yb, double *ub);
int gd_per_climb_teeth(ctx *c, const double *Y0, const double *u0, double h, double sg,
                       double *best);
void gd_per_merge_zigzags(ctx *c, int nb0);
double gd_per_inf_norm(const double *x, int n);
int gd_per_solve_warm(ctx *c, double *X, double lam, int *it, double *res);
int gd_per_solve_fixed(ctx *c, double **X, double **t, double lam, int *it, double *res, int rest);
int gd_per_follow_H(ctx *c, double **X, double **t);
/* Harmonic balance's context for the shared drivers (method.h; continuation.c): the run's,
 * the multipliers of the step's start (mre, mim, their categories out) and end (mre1,
 * mim1). */
typedef struct hb_arc {
    ctx *c;
    double *mre, *mim, *mre1, *mim1;
    int have_mu, stable1, out[3], out1[3];
    int H0;  /* the run's first H (each direction starts there) */
    int nb0; /* the bifurcations before this direction's branch */
} hb_arc;

struct gd_per_arc_ops;
struct gd_per_arc_step;
int gd_per_run_branch(ctx *c, const struct gd_per_arc_ops *ops, const double *vals, int nv, int H0);
/* Harmonic balance's bifurcation rule between two arclength steps (bifurcation.c; m an
 * hb_arc): 1 a fold, 0 none, -1 an error. */
int gd_per_hb_detect(void *m, const struct gd_per_arc_step *s);

#endif
