/* The planetary set element ([LinParker1999]): their example system's natural frequencies
 * (Table 1 data, Table 2 frequencies) for N = 3, 4 and 5 planets, the mode multiplicities
 * (rotational 1, translational 2, planet N - 3), the same eigenvalues from an independent
 * assembly in their own coordinates (zeta, eta, u = r theta), the planet-mode frequencies
 * from the planet's 3 x 3 problem with the central members held (their Sec. 4.3), and the
 * mesh and bearing deformations of a rigid rotation of a consistent set. */
#include <lapacke.h>

#include "elements/elements_impl.h"
#include "geardyn/builder.h"
#include "geardyn/modal.h"
#include "geardyn/static.h"
#include "geardyn/model.h"
#include "geardyn/model_file.h"
#include "geardyn/system.h"
#include "harness.h"

#define PI 3.14159265358979323846
#define NMAX 5

/* [LinParker1999] Table 1: masses, I/r^2 (kg), radii (diameters 77.4, 275, 176.8, 100.3 mm
 * for sun, ring, carrier, planet), stiffnesses, alpha = 24.6 deg. */
static const double MS = 0.4, MR = 2.35, MC = 5.43, MP = 0.66;
static const double JS = 0.39, JR = 3.00, JC = 6.29, JP = 0.61;
static const double RS = 0.0387, RR = 0.1375, RC = 0.0884, RP = 0.05015;
static const double KSP = 5e8, KB = 1e8, KRU = 1e9, ALPHA = 24.6 * PI / 180;

/* [LinParker1999] Table 2 (Hz): rotational (6, one rigid), translational (6 pairs), planet (3,
 * each N - 3 times). */
static const double ROT[3][6] = {{0, 1475.7, 1930.3, 2658.3, 7462.8, 11775.3},
                                 {0, 1536.6, 1970.6, 2625.7, 7773.6, 13071.1},
                                 {0, 1567.4, 2006.1, 2614.8, 8065.4, 14253.1}};
static const double TRA[3][6] = {{743.2, 1102.4, 1896.0, 2276.4, 6986.3, 9647.9},
                                 {727.0, 1091.0, 1892.8, 2342.5, 7189.9, 10437.6},
                                 {710.0, 1072.0, 1888.1, 2425.3, 7382.4, 11172.3}};
static const double PLA[3] = {1808.2, 5963.8, 6981.7};

/* The Lin & Parker system with N planets as a model file (examples/planetary_lin_parker.yaml
 * with count N): inertia = (I/r^2) r^2, k_torsion = k_ru r_r^2. */
static gd_model *lp_model_ex(int N, double ksup, double kru, const char *planet_extra,
                             const char *set_extra)
{
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "dofs: [x, y, rz]\n"
             "shafts:\n"
             "  - {name: a, nodes: [{name: sun}]}\n"
             "  - {name: b, nodes: [{name: ring}]}\n"
             "  - {name: c, nodes: [{name: carrier}]}\n"
             "planetary_sets:\n"
             "  - name: lp\n"
             "    held: ring\n"
             "    sun: {node: sun, mass: %.17g, inertia: %.17g, k_support: %.17g}\n"
             "    ring: {node: ring, mass: %.17g, inertia: %.17g, k_support: %.17g, "
             "k_torsion: %.17g}\n"
             "    carrier: {node: carrier, mass: %.17g, inertia: %.17g, k_support: %.17g}\n"
             "    planets: {count: %d, mass: %.17g, inertia: %.17g, bearing_stiffness: %.17g%s}\n"
             "    base_radius: {sun: %.17g, ring: %.17g, planet: %.17g}\n"
             "    carrier_radius: %.17g\n"
             "    pressure_angle: %.17g\n"
             "    mesh_stiffness: %.17g\n%s",
             MS, JS * RS * RS, ksup, MR, JR * RR * RR, ksup, kru * RR * RR, MC, JC * RC * RC, ksup,
             N, MP, JP * RP * RP, KB, planet_extra, RS, RR, RP, RC, ALPHA, KSP, set_extra);
    gd_model *m = NULL;
    gd_error err;
    if (gd_model_load_string(yaml, "lp.yaml", &m, &err)) {
        fprintf(stderr, "  %s\n", err.message);
        return NULL;
    }
    return m;
}

static gd_model *lp_model(int N)
{
    return lp_model_ex(N, KB, KRU, "", "");
}

/* The system of m and its modes at speed W (undamped, or damped with its gyroscopic terms);
 * 0 on failure (both freed). */
static int solve_modes(const gd_model *m, double W, gd_modal_kind kind, gd_system **sys,
                       gd_modal_result **r)
{
    gd_modal_options opt;
    gd_modal_options_init(&opt);
    opt.speed = W;
    opt.kind = kind;
    *sys = NULL;
    *r = NULL;
    if (gd_system_build(m, sys, NULL) || gd_modal_solve(*sys, &opt, r, NULL)) {
        gd_system_free(*sys);
        *sys = NULL;
        return 0;
    }
    return 1;
}

/* The model's undamped natural frequencies (Hz), ascending; returns their count. */
static int model_frequencies(const gd_model *m, double *f)
{
    gd_system *sys;
    gd_modal_result *r;
    if (!solve_modes(m, 0, GD_MODAL_UNDAMPED, &sys, &r)) return 0;
    int n = r->nmodes;
    for (int i = 0; i < n; i++)
        f[i] = r->modes[i].frequency_hz;
    gd_modal_free(r);
    gd_system_free(sys);
    return n;
}

/* K += k v v^T (n x n, column-major) */
static void add_outer(double *K, int n, double k, const double *v)
{
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            K[i + j * n] += k * v[i] * v[j];
}

/* A set in [LinParker1999]'s terms: masses and I/r^2 of carrier, ring, sun, planet; supports
 * k (x, y) and k_u (u = r theta) of carrier, ring, sun; k_sp, k_rp, k_p; alpha (both meshes). */
typedef struct paper_set {
    double m[4], j[4], k[3], ku[3], ksp, krp, kp, alpha;
} paper_set;

static const paper_set LP_SET = {
    {MC, MR, MS, MP}, {JC, JR, JS, JP}, {KB, KB, KB}, {0, KRU, 0}, KSP, KSP, KB, ALPHA};

/* [LinParker1999] Eqs. 1-6 assembled in their coordinates (c, r, s, then planets; x, y, u
 * and zeta, eta, u) from the deformations; with [CooleyParker2012] Eq. 1's G (2 m [0 -1; 1 0]
 * on every body's translations) and K_Omega (diag(m, m, 0)). n x n column-major, n = 9 + 3N;
 * G and KO may be NULL. */
static void paper_matrices(const paper_set *p, int N, double *M, double *K, double *G, double *KO)
{
    int n = 9 + 3 * N;
    size_t bytes = (size_t)(n * n) * sizeof(double);
    memset(M, 0, bytes);
    memset(K, 0, bytes);
    if (G) memset(G, 0, bytes);
    if (KO) memset(KO, 0, bytes);
    double *v = calloc((size_t)n, sizeof *v);
    for (int b = 0; b < 3 + N; b++) {
        int z = 3 * b, t = b < 3 ? b : 3;
        M[z * (n + 1)] = M[(z + 1) * (n + 1)] = p->m[t];
        M[(z + 2) * (n + 1)] = p->j[t];
        if (b < 3) {
            K[z * (n + 1)] += p->k[b];
            K[(z + 1) * (n + 1)] += p->k[b];
            K[(z + 2) * (n + 1)] += p->ku[b];
        }
        if (G) G[z + (z + 1) * n] = -2 * p->m[t], G[z + 1 + z * n] = 2 * p->m[t];
        if (KO) KO[z * (n + 1)] = KO[(z + 1) * (n + 1)] = p->m[t];
    }
    double al = p->alpha;
    for (int q = 0; q < N; q++) {
        double psi = 2 * PI * q / N, ps = psi - al, pr = psi + al;
        int z = 9 + 3 * q;
        memset(v, 0, (size_t)n * sizeof *v); /* sun mesh, Eq. 2 */
        v[6] = -sin(ps), v[7] = cos(ps), v[8] = 1, v[z] = -sin(al), v[z + 1] = -cos(al);
        v[z + 2] = 1;
        add_outer(K, n, p->ksp, v);
        memset(v, 0, (size_t)n * sizeof *v); /* ring mesh, Eq. 3 */
        v[3] = -sin(pr), v[4] = cos(pr), v[5] = 1, v[z] = sin(al), v[z + 1] = -cos(al);
        v[z + 2] = -1;
        add_outer(K, n, p->krp, v);
        memset(v, 0, (size_t)n * sizeof *v); /* bearing, radial */
        v[0] = -cos(psi), v[1] = -sin(psi), v[z] = 1;
        add_outer(K, n, p->kp, v);
        memset(v, 0, (size_t)n * sizeof *v); /* bearing, tangential */
        v[0] = sin(psi), v[1] = -cos(psi), v[2] = -1, v[z + 1] = 1;
        add_outer(K, n, p->kp, v);
    }
    free(v);
}

/* The paper's assembly at rest solved by LAPACK's dsygv: frequencies (Hz), ascending. */
static int paper_frequencies(int N, double *f)
{
    int n = 9 + 3 * N;
    double *M = malloc((size_t)(n * n) * sizeof *M), *K = malloc((size_t)(n * n) * sizeof *K);
    double *w = calloc((size_t)n, sizeof *w);
    paper_matrices(&LP_SET, N, M, K, NULL, NULL);
    int info = LAPACKE_dsygv(LAPACK_COL_MAJOR, 1, 'N', 'U', n, K, n, M, n, w);
    for (int i = 0; i < n; i++)
        f[i] = sqrt(fmax(w[i], 0)) / (2 * PI);
    free(M);
    free(K);
    free(w);
    return info == 0 ? n : 0;
}

/* The model matches the paper's own assembly to rounding, and Table 2 to 0.1 % (the table
 * prints 5 digits: 0.1 % is its rounding plus the Table 1 data's, e.g. 727.27 vs 727.0). */
TEST(lin_parker_table2_and_independent_assembly)
{
    for (int N = 3; N <= NMAX; N++) {
        gd_model *m = lp_model(N);
        REQUIRE(m);
        double f[9 + 3 * NMAX], g[9 + 3 * NMAX], want[9 + 3 * NMAX];
        int n = model_frequencies(m, f);
        gd_model_free(m);
        CHECK(n == 9 + 3 * N);
        CHECK(paper_frequencies(N, g) == n);
        for (int i = 0; i < n; i++)
            CHECK_ABS(f[i], g[i], 1e-8 * g[n - 1]);
        int k = 0;
        for (int i = 0; i < 6; i++) {
            want[k++] = ROT[N - 3][i];
            want[k++] = TRA[N - 3][i];
            want[k++] = TRA[N - 3][i];
        }
        for (int j = 0; j < N - 3; j++)
            for (int i = 0; i < 3; i++)
                want[k++] = PLA[i];
        for (int i = 0; i < k; i++) /* sort the table */
            for (int j = i + 1; j < k; j++)
                if (want[j] < want[i]) {
                    double t = want[i];
                    want[i] = want[j];
                    want[j] = t;
                }
        CHECK(k == n);
        CHECK_ABS(f[0], 0, 1e-3); /* the one rigid-body mode: sun and carrier free */
        for (int i = 1; i < n && i < k; i++)
            CHECK_REL(f[i], want[i], 1e-3);
    }
}

/* Multiplicities ([LinParker1999] Sec. 4): distinct frequencies counted; the translational
 * pairs are equal to 1e-9, different classes more than 1e-6 apart. */
TEST(lin_parker_multiplicities)
{
    for (int N = 3; N <= NMAX; N++) {
        gd_model *m = lp_model(N);
        REQUIRE(m);
        double f[9 + 3 * NMAX];
        int n = model_frequencies(m, f);
        gd_model_free(m);
        int mult[4] = {0, 0, 0, 0}; /* frequencies seen once, twice, three times, more */
        for (int i = 0; i < n;) {
            int j = i + 1;
            while (j < n && fabs(f[j] - f[i]) <= 1e-9 * f[n - 1])
                j++;
            mult[(j - i) > 4 ? 3 : j - i - 1]++;
            i = j;
        }
        /* N = 3: 6 single rotational, 6 pairs; N = 4: + 3 single planet modes; N = 5: the
           planet modes are pairs (N - 3 = 2) */
        CHECK(mult[0] == (N == 4 ? 9 : 6));
        CHECK(mult[1] == (N == 5 ? 9 : 6));
        CHECK(mult[2] == 0 && mult[3] == 0);
    }
}

/* Planet modes: the central members still, the planet's own 3 x 3 problem in (zeta, eta,
 * u) ([LinParker1999] Sec. 4.3): k_sp a_s a_s^T + k_rp a_r a_r^T + k_p diag(1, 1, 0). */
TEST(planet_modes_from_the_planet_alone)
{
    double K[9] = {0}, M[9] = {MP, 0, 0, 0, MP, 0, 0, 0, JP}, w[3];
    const double as[3] = {-sin(ALPHA), -cos(ALPHA), 1}, ar[3] = {sin(ALPHA), -cos(ALPHA), -1};
    add_outer(K, 3, KSP, as);
    add_outer(K, 3, KSP, ar);
    K[0] += KB;
    K[4] += KB;
    REQUIRE(LAPACKE_dsygv(LAPACK_COL_MAJOR, 1, 'N', 'U', 3, K, 3, M, 3, w) == 0);
    gd_model *m = lp_model(5);
    REQUIRE(m);
    double f[24];
    int n = model_frequencies(m, f);
    gd_model_free(m);
    for (int i = 0; i < 3; i++) {
        double fp = sqrt(w[i]) / (2 * PI), best = 1e30;
        for (int j = 0; j < n; j++)
            best = fmin(best, fabs(f[j] - fp));
        CHECK(best <= 1e-8 * fp);
        CHECK_REL(fp, PLA[i], 1e-3); /* Table 2's planet modes */
    }
}

/* A consistent set (r_c cos alpha_s = r_s + r_p, r_c cos alpha_r = r_r - r_p) turned rigidly
 * by theta: the planets' centres move r_c theta tangentially, every gear turns theta, and
 * no mesh or bearing deforms. A common translation deforms nothing either. */
TEST(rigid_motion_deforms_nothing)
{
    gd_planetary g;
    memset(&g, 0, sizeof g);
    double angles[3] = {0.3, 2.1, 4.4};
    g.nplanets = 3;
    g.planet_angle = angles;
    g.pressure_angle[0] = 22 * PI / 180;
    g.pressure_angle[1] = 19 * PI / 180;
    g.carrier_radius = 0.1;
    g.base_radius[2] = 0.03;
    g.base_radius[0] = g.carrier_radius * cos(g.pressure_angle[0]) - g.base_radius[2];
    g.base_radius[1] = g.carrier_radius * cos(g.pressure_angle[1]) + g.base_radius[2];
    for (int n = 0; n < 3; n++) {
        double th = 1e-3, q[12] = {0}, t[12] = {0}, a[12], r[12], tg[12];
        /* member (sun, ring or carrier) at rest position, rotating */
        q[GD_RZ] = th;
        q[6 + GD_X] = -sin(angles[n]) * g.carrier_radius * th;
        q[6 + GD_Y] = cos(angles[n]) * g.carrier_radius * th;
        q[6 + GD_RZ] = th;
        t[GD_X] = t[6 + GD_X] = 0.7e-3;
        t[GD_Y] = t[6 + GD_Y] = -0.2e-3;
        for (int ring = 0; ring < 2; ring++) {
            gd_planetary_mesh_vector(&g, ring, n, a);
            double d = 0, e = 0;
            for (int i = 0; i < 12; i++)
                d += a[i] * q[i], e += a[i] * t[i];
            CHECK_ABS(d, 0, 1e-18);
            CHECK_ABS(e, 0, 1e-18);
        }
        gd_planetary_bearing_vectors(&g, n, r, tg);
        double dr = 0, dt = 0, er = 0, et = 0;
        for (int i = 0; i < 12; i++)
            dr += r[i] * q[i], dt += tg[i] * q[i], er += r[i] * t[i], et += tg[i] * t[i];
        CHECK_ABS(dr, 0, 1e-18);
        CHECK_ABS(dt, 0, 1e-18);
        CHECK_ABS(er, 0, 1e-18);
        CHECK_ABS(et, 0, 1e-18);
    }
}

/* The registry's view of the N = 4 set: 3 + 4N instances; planet 1's bearing (psi = 0) by
 * hand: radial along x, tangential along y with the pin moved r_c th_c, so
 * K[carrier.y][carrier.rz] = k_p r_c and K[planet.y][carrier.rz] = -k_p r_c. */
TEST(bearing_matrix_by_hand)
{
    gd_model *m = lp_model(4);
    REQUIRE(m);
    const gd_element_type *t = gd_element_type_find("planetary");
    REQUIRE(t == &gd_element_planetary);
    CHECK(t->count(m) == 3 + 4 * 4 + 4); /* then the bearings' preloads: the carrier turns */
    int node[2], bearing = 3 + 3 * 4;    /* bodies, planets, sun meshes, ring meshes */
    CHECK(t->nodes(m, bearing, node) == 2);
    CHECK(node[0] == gd_model_find_node(m, "carrier") && node[1] == gd_model_find_node(m, "lp.p1"));
    CHECK(t->terms(m, bearing) == GD_TERM_K);
    double K[144];
    t->matrices(m, bearing, 0, NULL, K, NULL, NULL);
    CHECK_ABS(K[GD_X * 12 + GD_X], KB, 1e-6);
    CHECK_ABS(K[GD_X * 12 + 6 + GD_X], -KB, 1e-6);
    CHECK_ABS(K[GD_Y * 12 + GD_RZ], KB * RC, 1e-6);
    CHECK_ABS(K[(6 + GD_Y) * 12 + GD_RZ], -KB * RC, 1e-6);
    CHECK_ABS(K[GD_RZ * 12 + GD_RZ], KB * RC * RC, 1e-6);
    CHECK_ABS(K[(6 + GD_RZ) * 12 + 6 + GD_RZ], 0, 1e-12);
    gd_model_free(m);
}

/* Every mode has its class ([LinParker1999] Sec. 4): 6 rotational (the rigid mode among
 * them), 6 translational pairs, 3 (N - 3) planet modes; none mixed. */
TEST(mode_classes_and_their_counts)
{
    for (int N = 3; N <= NMAX; N++) {
        gd_model *m = lp_model(N);
        REQUIRE(m);
        gd_system *sys;
        gd_modal_result *r;
        REQUIRE(solve_modes(m, 0, GD_MODAL_UNDAMPED, &sys, &r));
        int count[GD_PCLASS_COUNT] = {0};
        for (int j = 0; j < r->nmodes; j++)
            count[gd_modal_planetary_class(sys, r, j, 0)]++;
        CHECK(count[GD_PCLASS_ROTATIONAL] == 6);
        CHECK(count[GD_PCLASS_TRANSLATIONAL] == 12);
        CHECK(count[GD_PCLASS_PLANET] == 3 * (N - 3));
        CHECK(count[GD_PCLASS_MIXED] == 0 && count[GD_PCLASS_NONE] == 0);
        CHECK(gd_modal_planetary_class(sys, r, 0, 0) == GD_PCLASS_ROTATIONAL); /* rigid */
        gd_modal_free(r);
        gd_system_free(sys);
        gd_model_free(m);
    }
}

/* [CooleyParker2012] Table 1 (examples/planetary_cooley_parker.yaml, N = 4, the carrier the
 * reference shaft). */
static const paper_set CP_SET = {{12.0, 7.64, 3.0, 1.86},
                                 {6.80, 8.09, 1.75, 1.25},
                                 {50e6, 100e6, 20e6},
                                 {100e6, 100e6, 20e6},
                                 100e6,
                                 100e6,
                                 10e6,
                                 20 * PI / 180};
#define CP_FILE "examples/planetary_cooley_parker.yaml"

/* At rest: [CooleyParker2012] Table 2, omega / sqrt(k_p / m_p), 4 digits (so 0.1 %). */
TEST(cooley_parker_at_rest)
{
    static const double want[21] = {0.7199, 0.7199, 0.9077, 0.9617, 1.001, 1.001, 1.046,
                                    1.317,  1.317,  1.317,  1.481,  1.481, 2.013, 4.320,
                                    5.153,  5.153,  5.672,  5.809,  6.488, 6.488, 8.383};
    gd_model *m = NULL;
    REQUIRE(!gd_model_load(CP_FILE, &m, NULL));
    double f[21];
    REQUIRE(model_frequencies(m, f) == 21);
    for (int i = 0; i < 21; i++)
        CHECK_REL(f[i] / (sqrt(10e6 / 1.86) / (2 * PI)), want[i], 1e-3);
    gd_model_free(m);
}

/* The rotating carrier at Omega = 5000 rpm: the library's gyroscopic modes (state space in
 * the model's node coordinates) against [CooleyParker2012] Eq. 1 assembled here in the
 * paper's coordinates and solved another way: for M q'' + Omega G q' + (K - Omega^2 K_O) q = 0
 * with K_eff = K - Omega^2 K_O > 0, H(w) = K_eff - w^2 M + i w Omega G is Hermitian, singular
 * at each natural frequency, and its count of negative eigenvalues is the number of natural
 * frequencies below w (each eigencurve of H crosses zero once). LAPACK's zheev gives both. */
TEST(rotating_carrier_against_the_hermitian_count)
{
    /* Eq. 1 has no geometric stiffness of the planets' centrifugal load: left out here */
    static const char *const off[] = {"planetary_sets.cp.centrifugal_stiffness=false"};
    gd_load_options lo;
    gd_load_options_init(&lo);
    lo.nset = 1;
    lo.set = off;
    gd_model *m = NULL;
    REQUIRE(!gd_model_load_opts(CP_FILE, &lo, &m, NULL));
    double W = 5000 * PI / 30;
    gd_system *sys;
    gd_modal_result *r;
    REQUIRE(solve_modes(m, W, GD_MODAL_DAMPED, &sys, &r));
    double w[42];
    int nw = 0;
    for (int j = 0; j < r->nmodes && nw < 42; j++)
        if (r->modes[j].lambda_im > 0) w[nw++] = r->modes[j].lambda_im;
    CHECK(nw == 21);
    for (int i = 0; i < nw; i++) /* ascending */
        for (int j = i + 1; j < nw; j++)
            if (w[j] < w[i]) {
                double t = w[i];
                w[i] = w[j];
                w[j] = t;
            }
    /* the gyroscopic splitting of the lowest translational pair (265.68 Hz at rest) */
    CHECK(w[1] / w[0] > 1.2 && w[0] / (2 * PI) < 265 && w[1] / (2 * PI) > 266);
    int n = 21;
    double M[441], K[441], G[441], KO[441], ev[21];
    lapack_complex_double H[441];
    paper_matrices(&CP_SET, 4, M, K, G, KO);
    double kmax = 0;
    for (int i = 0; i < n * n; i++)
        kmax = fmax(kmax, fabs(K[i]));
    for (int i = 0; i < nw; i++)
        for (int pass = 0; pass < 2; pass++) {
            /* at w_i: singular; between w_i and w_{i+1}: i + 1 negative eigenvalues */
            double x = pass == 0 ? w[i] : (i + 1 < nw ? 0.5 * (w[i] + w[i + 1]) : 1.1 * w[i]);
            for (int c = 0; c < n; c++)
                for (int rr = 0; rr < n; rr++) {
                    int k = rr + c * n;
                    H[k] = lapack_make_complex_double(K[k] - W * W * KO[k] - x * x * M[k],
                                                      x * W * G[k]);
                }
            REQUIRE(LAPACKE_zheev(LAPACK_COL_MAJOR, 'N', 'U', n, H, n, ev) == 0);
            if (pass == 0) {
                double small = 1e300;
                for (int k = 0; k < n; k++)
                    small = fmin(small, fabs(ev[k]));
                CHECK(small <= 1e-8 * kmax);
            } else {
                int neg = 0;
                for (int k = 0; k < n; k++)
                    neg += ev[k] < 0;
                CHECK(neg == i + 1);
            }
        }
    gd_modal_free(r);
    gd_system_free(sys);
    gd_model_free(m);
}

/* The carrier-frame terms: every body of a set on lumped nodes (the default there), the
 * planets only with `carrier_frame: planets`; G = 2 m ratio [0 -1; 1 0] and K at speed W
 * softened by m (ratio W)^2 (the carrier is the reference shaft: ratio 1). */
TEST(carrier_frame_terms)
{
    char *text = NULL;
    FILE *f = fopen(CP_FILE, "rb");
    REQUIRE(f);
    text = calloc(1, 1 << 14);
    size_t n = fread(text, 1, (1 << 14) - 64, f);
    fclose(f);
    REQUIRE(n > 0);
    for (int variant = 0; variant < 2; variant++) {
        if (variant) strcat(text, "    carrier_frame: planets\n");
        gd_model *m = NULL;
        REQUIRE(!gd_model_load_string(text, "cp.yaml", &m, NULL));
        const gd_element_type *t = &gd_element_planetary;
        double M[36], K[36], G[36], W = 300;
        /* instance 0: the sun body (3 kg, k_support 20e6); 3: planet 1 (1.86 kg) */
        CHECK(!!(t->terms(m, 0) & GD_TERM_G) == !variant);
        CHECK(t->terms(m, 3) & GD_TERM_G);
        CHECK(t->terms(m, 3) & GD_TERM_SPEED);
        t->matrices(m, 0, W, M, K, NULL, G);
        CHECK_ABS(G[GD_X * 6 + GD_Y], variant ? 0 : -6.0, 1e-12);
        CHECK_REL(K[GD_X * 6 + GD_X], 20e6 - (variant ? 0 : 3.0 * W * W), 1e-12);
        t->matrices(m, 3, W, M, K, NULL, G);
        CHECK_ABS(G[GD_Y * 6 + GD_X], 2 * 1.86, 1e-12);
        CHECK_REL(K[GD_Y * 6 + GD_Y], -1.86 * W * W, 1e-12);
        CHECK_ABS(M[GD_RZ * 6 + GD_RZ], 2.278125e-4, 1e-15);
        gd_model_free(m);
    }
    free(text);
}

/* Static sun-planet forces at torque T on the sun, the carrier's torsion held. */
static int sharing(gd_model *m, double T, gd_static_planetary_loads *pl)
{
    gd_system *sys = NULL;
    gd_static_result *res = NULL;
    gd_static_options opt;
    gd_static_options_init(&opt);
    opt.input_torque = T;
    opt.input_node = gd_model_find_node(m, "sun");
    opt.hold_node = gd_model_find_node(m, "carrier");
    int ok = !gd_system_build(m, &sys, NULL) && !gd_static_run(sys, &opt, &res, NULL) &&
             !gd_static_planetary(sys, res, 0, pl, NULL);
    gd_static_free(res);
    gd_system_free(sys);
    return ok;
}

/* A perfect set shares equally: F_n = T / (N r_s) for N = 3, 4, 5, K_gamma = 1. */
TEST(equal_load_sharing)
{
    for (int N = 3; N <= NMAX; N++) {
        gd_model *m = lp_model(N);
        REQUIRE(m);
        gd_static_planetary_loads pl;
        REQUIRE(sharing(m, 100, &pl));
        for (int n = 0; n < N; n++)
            CHECK_REL(pl.sun_force[n], 100 / (N * RS), 1e-9);
        CHECK_REL(pl.load_sharing, 1, 1e-9);
        gd_model_free(m);
    }
}

/* A pin error e_1 on planet 1 (docs/planetary.md, "Load sharing"): with the central members'
 * translations rigid (supports 1e14 N/m: 5e-6 of the meshes' stiffness), each planet solves
 * K_p x = -k_sp u_s a_s + k_p e_n t with K_p = k_sp a_s a_s^T + k_rp a_r a_r^T + k_p diag(1,
 * 1, 0), so F_n = c1 u_s + c2 e_n, c2 = k_sp k_p a_s^T K_p^-1 t; the torque balance gives
 * F_n = T / (N r_s) + c2 (e_n - mean e). Here K_p^-1 by LAPACK's dposv on the 3 x 3. */
TEST(pin_error_load_sharing_against_the_closed_form)
{
    const int N = 4;
    const double e1 = 5e-6, T = 100;
    gd_model *m = lp_model_ex(N, 1e14, 1e14, ", pin_errors: [5 um, 0, 0, 0]", "");
    REQUIRE(m);
    gd_static_planetary_loads pl;
    REQUIRE(sharing(m, T, &pl));
    gd_model_free(m);
    double K[9] = {0}, x[3] = {0, 1, 0};
    const double as[3] = {-sin(ALPHA), -cos(ALPHA), 1}, ar[3] = {sin(ALPHA), -cos(ALPHA), -1};
    add_outer(K, 3, KSP, as);
    add_outer(K, 3, KSP, ar);
    K[0] += KB;
    K[4] += KB;
    REQUIRE(LAPACKE_dposv(LAPACK_COL_MAJOR, 'U', 3, 1, K, 3, x, 3) == 0);
    double c2 = KSP * KB * (as[0] * x[0] + as[1] * x[1] + as[2] * x[2]), mean = e1 / N;
    double want[4], sum = 0, mx = 0;
    for (int n = 0; n < N; n++) {
        want[n] = T / (N * RS) + c2 * ((n == 0 ? e1 : 0) - mean);
        CHECK_REL(pl.sun_force[n], want[n], 1e-4);
        sum += want[n];
        mx = fmax(mx, want[n]);
    }
    CHECK(fabs(pl.sun_force[0] - pl.sun_force[1]) > 0.1 * T / (N * RS)); /* the error matters */
    CHECK_REL(pl.load_sharing, N * mx / sum, 1e-4);
}

/* A radial pin error rho_1 on planet 1, with a tangential one e_2 on planet 2 (docs/planetary.md,
 * "Static load sharing"): the planet's equilibrium gets k_p rho_n r, r = (1, 0, 0) in its
 * (zeta, eta, u), so F_n = T / (N r_s) + c2 (e_n - mean e) + c3 (rho_n - mean rho) with
 * c3 = k_sp k_p a_s^T K_p^-1 r. With one pressure angle for both meshes c3 = 0: the planet
 * moved out by rho turns by u = rho sin(alpha), which leaves both meshes undeformed
 * (a_s . (rho, 0, rho sin alpha) = a_r . (...) = 0), so the set carries the radial error
 * without any load: the forces are those of the tangential error alone, the bearings' too. */
TEST(radial_pin_error_load_sharing_against_the_closed_form)
{
    const int N = 4;
    const double e2 = -3e-6, T = 100;
    gd_model *m = lp_model_ex(
        N, 1e14, 1e14, ", pin_errors: [0, -3 um, 0, 0], pin_errors_radial: [8 um, 0, 0, 0]", "");
    gd_model *m0 = lp_model_ex(N, 1e14, 1e14, ", pin_errors: [0, -3 um, 0, 0]", "");
    REQUIRE(m && m0);
    gd_static_planetary_loads pl, p0;
    REQUIRE(sharing(m, T, &pl) && sharing(m0, T, &p0));
    gd_model_free(m);
    gd_model_free(m0);
    double K[9] = {0}, x[6] = {0, 1, 0, 1, 0, 0}; /* K_p^-1 t and K_p^-1 r */
    const double as[3] = {-sin(ALPHA), -cos(ALPHA), 1}, ar[3] = {sin(ALPHA), -cos(ALPHA), -1};
    add_outer(K, 3, KSP, as);
    add_outer(K, 3, KSP, ar);
    K[0] += KB;
    K[4] += KB;
    REQUIRE(LAPACKE_dposv(LAPACK_COL_MAJOR, 'U', 3, 2, K, 3, x, 3) == 0);
    double c2 = KSP * KB * (as[0] * x[0] + as[1] * x[1] + as[2] * x[2]);
    double c3 = KSP * KB * (as[0] * x[3] + as[1] * x[4] + as[2] * x[5]);
    CHECK(fabs(c3) < 1e-9 * fabs(c2));
    double want[4], sum = 0, mx = 0;
    for (int n = 0; n < N; n++) {
        want[n] = T / (N * RS) + c2 * ((n == 1 ? e2 : 0) - e2 / N);
        CHECK_REL(pl.sun_force[n], want[n], 1e-4);
        CHECK_REL(pl.sun_force[n], p0.sun_force[n], 1e-9);
        CHECK_REL(pl.ring_force[n], p0.ring_force[n], 1e-9);
        CHECK_REL(pl.bearing_force[n], p0.bearing_force[n], 1e-9);
        sum += want[n];
        mx = fmax(mx, want[n]);
    }
    CHECK(fabs(pl.sun_force[1] - pl.sun_force[0]) > 0.05 * T / (N * RS)); /* e_2 matters */
    CHECK_REL(pl.load_sharing, N * mx / sum, 1e-4);
}

/* Planet phasing ([Parker2000]) on a modal FRF: Lin & Parker's N = 4 set with Z_s = 21
 * (Z_r = 79, Z_p = 29: (21 + 79) / 4 whole). Mesh harmonic l's phased sun-mesh load F
 * (gd_planetary_mesh_excitation) drives mode k with the modal force p_k = phi_k^T F /
 * sqrt(phi_k^T M phi_k), its response q_k(w) = p_k / (w_k^2 - w^2). l Z_s mod 4 = 0: only
 * rotational modes respond; 1 or 3: only translational; 2: only planet modes. The other
 * classes' responses stay below 1e-9 of the excited class's, at every w of a sweep. */
TEST(planet_phasing_selects_the_mode_class)
{
    gd_model *m = lp_model_ex(4, KB, KRU, "", "    teeth: {sun: 21, ring: 79, planet: 29}\n");
    REQUIRE(m);
    gd_system *sys;
    gd_modal_result *r;
    REQUIRE(solve_modes(m, 0, GD_MODAL_UNDAMPED, &sys, &r));
    int n = sys->ndof;
    double *M = malloc((size_t)(n * n) * sizeof *M), fr[64], fi[64];
    REQUIRE(M && n <= 64);
    gd_system_dense(sys, 0, M, NULL, NULL);
    for (int l = 1; l <= 8; l++) {
        REQUIRE(!gd_planetary_mesh_excitation(sys, 0, l, 0, fr, fi, NULL));
        int res = (l * 21) % 4;
        gd_planetary_class want = res == 0   ? GD_PCLASS_ROTATIONAL
                                  : res == 2 ? GD_PCLASS_PLANET
                                             : GD_PCLASS_TRANSLATIONAL;
        for (int s = 0; s < 5; s++) {
            double w = 2 * PI * (500 + 2000.0 * s), on = 0, off = 0;
            for (int k = 0; k < r->nmodes; k++) {
                const double *phi = r->shape_re + (size_t)k * n;
                double pr = 0, pi = 0, mk = 0;
                for (int i = 0; i < n; i++) {
                    pr += phi[i] * fr[i];
                    pi += phi[i] * fi[i];
                    for (int j = 0; j < n; j++)
                        mk += phi[i] * M[i + (size_t)j * n] * phi[j];
                }
                double wk = r->modes[k].omega_n;
                double q = hypot(pr, pi) / sqrt(mk) / fabs(wk * wk - w * w);
                if (gd_modal_planetary_class(sys, r, k, 0) == want)
                    on = fmax(on, q);
                else
                    off = fmax(off, q);
            }
            CHECK(on > 0);
            CHECK(off <= 1e-9 * on);
        }
    }
    free(M);
    gd_modal_free(r);
    gd_system_free(sys);
    gd_model_free(m);
}

/* Unequally spaced planets ([LinParker2000]): the planet modes survive any spacing, central
 * members still, at the equally spaced set's planet frequencies, N - 3 times each (the
 * planets' weights c_n need only sum c_n = 0 and sum c_n exp(i psi_n) = 0); the other modes
 * are no longer purely rotational or translational. */
TEST(unequal_spacing_keeps_the_planet_modes)
{
    const char *angles[2] = {", angles: [0, 80 deg, 170 deg, 265 deg]",
                             ", angles: [0, 60 deg, 150 deg, 220 deg, 290 deg]"};
    for (int v = 0; v < 2; v++) {
        int N = 4 + v;
        char extra[128];
        snprintf(extra, sizeof extra, "%s", angles[v]);
        /* the angles next to `count: N` (they must agree) */
        gd_model *m = lp_model_ex(N, KB, KRU, extra, "");
        REQUIRE(m);
        CHECK(!m->planetary[0].equally_spaced);
        gd_system *sys;
        gd_modal_result *r;
        REQUIRE(solve_modes(m, 0, GD_MODAL_UNDAMPED, &sys, &r));
        int planet = 0, pure = 0;
        for (int k = 0; k < r->nmodes; k++) {
            gd_planetary_class c = gd_modal_planetary_class(sys, r, k, 0);
            if (c == GD_PCLASS_PLANET) {
                planet++;
                double best = 1e30;
                for (int i = 0; i < 3; i++)
                    best = fmin(best, fabs(r->modes[k].frequency_hz / PLA[i] - 1));
                CHECK(best < 1e-3); /* Table 2's planet modes, to its rounding */
            }
            pure += c == GD_PCLASS_TRANSLATIONAL;
        }
        CHECK(planet == 3 * (N - 3));
        CHECK(pure < 12); /* the translational pairs are gone */
        gd_modal_free(r);
        gd_system_free(sys);
        gd_model_free(m);
    }
}

/* The builder in C: the set of the CLI tests with unequal angles, its planets' nodes and
 * shafts, and an error located at the spec's field. */
TEST(builder_api)
{
    gd_model *m = NULL;
    REQUIRE(!gd_model_new("set.c", &m, NULL));
    const char *names[3] = {"sun", "ring", "carrier"};
    for (int j = 0; j < 3; j++) {
        gd_station_spec st;
        gd_station_spec_init(&st);
        st.name = names[j];
        gd_shaft_spec sh;
        gd_shaft_spec_init(&sh);
        sh.nstations = 1;
        sh.stations = &st;
        REQUIRE(!gd_model_add_shaft(m, &sh, NULL, NULL));
    }
    gd_planetary_spec p;
    gd_planetary_spec_init(&p);
    CHECK(p.held == -1 && fabs(p.pressure_angle[1] - 20 * PI / 180) < 1e-15);
    p.name = "ps";
    for (int j = 0; j < 3; j++)
        p.member[j].node = names[j], p.member[j].mass = 1, p.member[j].inertia = 1e-3;
    p.member[GD_PLANETARY_RING].k_torsion = 1e8;
    p.held = GD_PLANETARY_RING;
    const double ang[3] = {0, 120 * PI / 180, 248 * PI / 180}; /* 90 x 248 / 360 = 62 */
    p.nplanets = 3;
    p.planet_angles = ang;
    p.planet_mass = 0.4, p.planet_inertia = 1.5e-4, p.bearing_stiffness = 1e8;
    p.teeth[0] = 20, p.teeth[1] = 70, p.teeth[2] = 25;
    p.base_radius[0] = 0.0187939, p.base_radius[1] = 0.0657785, p.base_radius[2] = 0.0234923;
    p.carrier_radius = 0.045;
    p.mesh_stiffness[0] = p.mesh_stiffness[1] = 4e8;
    int idx = -1;
    REQUIRE(!gd_model_add_planetary(m, &p, &idx, NULL));
    CHECK(idx == 0);
    gd_planetary_spec bad = p;
    const double near[3] = {0, 60 * PI / 180, 180 * PI / 180};
    bad.name = "bad";
    bad.planet_angles = near;
    gd_error err;
    CHECK(gd_model_add_planetary(m, &bad, NULL, &err) == GD_EINPUT);
    CHECK_STR(err.field, "planetary_sets[1].planets.angles");
    CHECK(m->nplanetary == 1);
    REQUIRE(!gd_model_finish(m, NULL));
    CHECK(m->nshafts == 6 && gd_model_find_node(m, "ps.p3") == m->planetary[0].first_planet + 2);
    CHECK(m->planetary[0].member[GD_PLANETARY_CARRIER].node == gd_model_find_node(m, "carrier"));
    CHECK_REL(m->shafts[2].speed_ratio, 20.0 / 90, 1e-12); /* the carrier's, from the sun's */
    gd_model_free(m);
}

RUN_TESTS(T(unequal_spacing_keeps_the_planet_modes), T(builder_api),
          T(planet_phasing_selects_the_mode_class), T(equal_load_sharing),
          T(pin_error_load_sharing_against_the_closed_form),
          T(radial_pin_error_load_sharing_against_the_closed_form), T(carrier_frame_terms),
          T(cooley_parker_at_rest), T(rotating_carrier_against_the_hermitian_count),
          T(mode_classes_and_their_counts), T(bearing_matrix_by_hand),
          T(lin_parker_table2_and_independent_assembly), T(lin_parker_multiplicities),
          T(planet_modes_from_the_planet_alone), T(rigid_motion_deforms_nothing))
