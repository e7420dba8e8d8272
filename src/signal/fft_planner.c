/* FFTW's planner (fftw_plan_*) is not thread-safe, and the library plans inside calls
 * that may run on several threads at once: a study runs its periodic cases in parallel
 * (OpenMP), each planning its transforms. fftw_make_planner_thread_safe (FFTW >= 3.3.5,
 * libfftw3_threads) serialises the planner; pthread_once makes that happen exactly once
 * before the first plan, whoever calls first. */
#include <fftw3.h>
#include <pthread.h>

#include "signal/fft_planner_impl.h"

static pthread_once_t planner_once = PTHREAD_ONCE_INIT;

static void make_safe(void)
{
    fftw_make_planner_thread_safe();
}

void gd_fft_planner_init(void)
{
    pthread_once(&planner_once, make_safe);
}
