/* One continuation driver over a method table (issue 33 item 7; docs/periodic.md,
 * "Structure"). A method is a row of gd_per_methods (method_table.c): its entry, which
 * builds its own context (the problem per value, its unknowns and scales) and runs each
 * direction, and its operations (gd_per_arc_ops), which the shared drivers call on that
 * context: the first point, the pseudo-arclength (driver/arclength.c) and the natural
 * continuation of --sequential (driver/sequential.c). The drivers own the branch: the
 * first point's search, the predictor, the step control (turn of the tangent, the chord's
 * length and direction, corners of a sampled branch), the starts of a fixed-value solve
 * and their order, the requested values crossed on a step, the range and the step count,
 * and the reasons of the values beyond the furthest point reached. A method owns what
 * differs: its problem, corrector, tangent, multipliers, its own start (rest, a
 * transient) and its bifurcation rules (detect: between two arclength steps; between:
 * between two natural-continuation points).
 *
 * Not thread-safe per context (a run is one thread); the table is constant. */
#ifndef GD_PERIODIC_METHOD_H
#define GD_PERIODIC_METHOD_H
#include <stddef.h>

#include "geardyn/periodic.h"

/* One accepted step of the branch, handed to the method's bifurcation rule: the point
 * before y (yb at lb, have_b 0 when there is none at this size), the step's start y (lam,
 * unit tangent t) and end y1 (l1, t1), n unknowns (the arrays hold n + 1, the parameter
 * last), the step length ds in the scaled variables (y / D, lambda / sl). */
typedef struct gd_per_arc_step {
    int n;
    double ds, sl;
    const double *D;
    const double *yb;
    double lb;
    int have_b;
    const double *y, *t;
    double lam;
    const double *y1, *t1;
    double l1;
    int fold_prev; /* the last step found a fold */
} gd_per_arc_step;

/* The operations of one method on its context m. Return codes: 0 ok, 1 failed (the
 * method's reason buffer says why) unless noted. */
typedef struct gd_per_arc_ops {
    int (*size)(void *m);   /* the unknowns now (they may grow: grow) */
    void (*step)(void *m);  /* a step begins: counted, then as begin */
    void (*begin)(void *m); /* NULL, or a point's solve begins: per-point budgets reset */
    int (*prepare)(void *m, double v); /* the problem at v made current */
    /* the fixed-value solve at v (prepared) from the method's own start, no neighbour's
     * (harmonic balance: rest, then a transient; shooting: a transient); *y may be
     * reallocated to size() + 1 */
    int (*cold)(void *m, double **y, double v, int *it, double *res);
    const char *cold_name; /* that start, for the messages ("a transient") */
    /* the converged start y at lam: its scales D (n) given the range sl, the unit tangent
     * t (n + 1) oriented so that lambda moves by sign, its multipliers; 1: no tangent */
    int (*start)(void *m, const double *y, double lam, double sign, double sl, double *D,
                 double *t);
    /* the corrector on the hyperplane normal to t through the predictor yp (n + 1) */
    int (*correct)(void *m, double *y, double *lam, const double *t, const double *yp, int *it,
                   double *res);
    /* the unit tangent at a converged point, oriented along prev (or lambda by sign) */
    int (*tangent)(void *m, const double *y, double lam, const double *prev, double sign,
                   double *t);
    /* NULL, or a direction begins (dir 1 from the first requested value, -1 from the last,
     * v0 to v1): 0 ok, 1 an error */
    int (*direction)(void *m, int dir, double v0, double v1);
    void (*branch_end)(void *m); /* NULL, or after a direction's branch that succeeded */
    /* NULL, or 1 when the point's budget ran out: after a failed arclength step the branch
     * stops, after a failed start of a sequential point no further start is tried */
    int (*give_up)(void *m);
    void (*measure)(void *m, const double *y1, double l1); /* the step end's multipliers */
    /* the fixed-value solve at v from y (Newton; it makes the problem at v current) */
    int (*solve_at)(void *m, double *y, double v, int *it, double *res);
    int (*emit)(void *m, const double *y, double v, int it, double res); /* 1: out of memory */
    int (*fail)(void *m, double v); /* v not solved, the reason recorded; 1: out of memory */
    int (*detect)(void *m, const gd_per_arc_step *s); /* 1 a fold, 0 none, -1 an error */
    /* NULL (none: the row says why), or the bifurcations between two consecutive points of
     * the natural continuation, ya at la and yb at lb, both emitted: 0 ok, 1 an error */
    int (*between)(void *m, const double *ya, double la, const double *yb, double lb);
    void (*rescale)(void *m, const double *y, double *D, double *t); /* D to y's size */
    /* NULL, or after an accepted point at lam: 0 nothing; 1 the unknowns grew (*y, and *t,
     * *D unless NULL, reallocated to size() + 1, y solved again, its iterations in *it;
     * it NULL: padded, not solved again); 2 grown but not solved (the reason recorded: the
     * branch stops); -1 an error */
    int (*grow)(void *m, double **y, double **t, double **D, double lam, int *it);
} gd_per_arc_ops;

/* The branch a method hands to the driver. */
typedef struct gd_per_arc {
    const gd_per_arc_ops *ops;
    void *m;
    char *why; /* the method's reason buffer (the driver's own stops are written there) */
    size_t why_cap;
    int speed;     /* 1: lambda is a speed, the branch ends where it reaches 0 */
    int max_steps; /* opt->max_steps, 0: 50 per requested value + 200 */
    double dsmin;  /* the shortest step (scaled) before the branch stops */
    int corners;   /* a step whose turn does not shrink when halved is a corner, taken */
    void (*on_step)(double lam, void *user); /* opt->on_step: after every accepted step */
    void *user;
} gd_per_arc;

/* Pseudo-arclength (Keller 1977; Seydel 2010 Sec. 4.5) from *y, solved at vals[i0] = lam,
 * to vals[nv - 1]: every requested value crossed solved and emitted, the method's
 * bifurcations between steps, the values beyond the furthest point reached failed with
 * the reason. *y may be reallocated (grow). 0 done, 1 an error (out of memory). */
int gd_per_arclength(const gd_per_arc *a, const double *vals, int nv, int i0, double **y,
                     double lam);

/* The branch of one direction (driver/sequential.c): the first requested value that
 * converges from the method's own start (cold; the ones before it failed with the reason),
 * emitted and grown, then natural continuation to the last (sequential 1) or the
 * pseudo-arclength (gd_per_arclength). 0 done, 1 an error (out of memory). */
int gd_per_branch(const gd_per_arc *a, const double *vals, int nv, int sequential);
/* The branch from the first requested value to the last and, both 1, back from the last
 * (driver/sequential.c): each a direction of gd_per_branch. 0 done, 1 an error. */
int gd_per_directions(const gd_per_arc *a, const double *vals, int nv, int both, int sequential);

/* One row of the method table: the kind and name (the JSON's "method"), the run of the
 * whole branch (both directions) into res, which builds its context and hands it with the
 * row's operations (NULL: the run has its own loop) to gd_per_directions. GD_OK, or the
 * located error. */
typedef gd_status (*gd_per_run_fn)(const gd_per_arc_ops *ops, const gd_system *sys,
                                   const gd_transient_spec *spec, const gd_periodic_param *param,
                                   const double *values, int nvalues,
                                   const gd_periodic_options *opt, const gd_tr_record *records,
                                   int nrecords, gd_periodic_result *res, gd_error *err);
typedef struct gd_per_method_row {
    gd_per_kind kind;
    const char *name;
    gd_per_run_fn run;
    const gd_per_arc_ops *ops;
} gd_per_method_row;

/* The row of kind (NULL: none, GD_PER_AUTO is resolved by the caller). */
const gd_per_method_row *gd_per_method_find(gd_per_kind kind);

/* The rows' runs (hb: hb_method.c, shooting: shooting/shooting_natural.c, multifreq:
 * method_table.c over multifreq/qp_run.c) and operations (continuation.c,
 * shooting/shooting_arclength.c). */
gd_status gd_per_hb_run(const gd_per_arc_ops *ops, const gd_system *sys,
                        const gd_transient_spec *spec, const gd_periodic_param *param,
                        const double *values, int nvalues, const gd_periodic_options *opt,
                        const gd_tr_record *records, int nrecords, gd_periodic_result *res,
                        gd_error *err);
gd_status gd_per_shoot_method(const gd_per_arc_ops *ops, const gd_system *sys,
                              const gd_transient_spec *spec, const gd_periodic_param *param,
                              const double *values, int nvalues, const gd_periodic_options *opt,
                              const gd_tr_record *records, int nrecords, gd_periodic_result *res,
                              gd_error *err);
extern const gd_per_arc_ops gd_per_hb_ops, gd_per_sh_ops;
/* Reduced shooting (rshoot/rshoot.c): its run (natural continuation always: a linear
 * problem) and operations; its refusal (1, msg) of a problem at speed whose laws are not
 * linear in the state at fixed time or whose forces at rest change over the period,
 * naming the law (`--method auto` asks it before taking the row). */
gd_status gd_per_rs_run(const gd_per_arc_ops *ops, const gd_system *sys,
                        const gd_transient_spec *spec, const gd_periodic_param *param,
                        const double *values, int nvalues, const gd_periodic_options *opt,
                        const gd_tr_record *records, int nrecords, gd_periodic_result *res,
                        gd_error *err);
extern const gd_per_arc_ops gd_per_rs_ops;
int gd_per_rs_refusal(const gd_system *sys, const gd_transient_spec *spec, double speed,
                      const gd_periodic_options *opt, char *msg, size_t cap);

#endif
