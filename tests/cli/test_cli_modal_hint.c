/* The modal warning when the sparse refinement did not converge: it said "--method dense
 * gives them to rounding", untrue (LAPACK has a floor of its own: residuals up to 1.4e-11
 * on the 336-DOF reducer, 1.6e-10 on rig366; and it needs memory growing as n^2). It now
 * names this model's size, the dense solve's memory and time by the cost model, and what
 * this solve reached. The reducer at --tol 1e-14 is such a case (residuals up to 3e-5:
 * the sparse path degrades at that tolerance, reported to the lead). The branch for a
 * model too large for dense memory is not reached by any test model (untested). */
#include "cli_support.h"
#include "harness.h"

TEST(dense_hint_names_the_model_at_hand)
{
    setenv("OPENBLAS_NUM_THREADS", "1", 1);
    scratch sc;
    REQUIRE(scratch_open(&sc));
    run_result r;
    run(&sc, &r,
        "modal examples/reducer_three_stage.yaml --speed 500rpm --modes 14 --tol 1e-14 --json");
    CHECK(r.code == 0);
    CHECK(contains(r.err, "refinement did not converge"));
    CHECK(contains(r.err, "336 DOFs, state space: about 16 MB of memory"));
    CHECK(contains(r.err, "rounding floor of its own"));
    CHECK(!contains(r.err, "gives them to rounding"));
    if (!contains(r.err, "336 DOFs")) show(&r);
    run_free(&r);
    scratch_close(&sc);
}

RUN_TESTS(T(dense_hint_names_the_model_at_hand))
