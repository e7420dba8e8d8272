/* Thread-safe FFTW planning for the whole library (fft_planner.c). */
#ifndef GD_FFT_PLANNER_IMPL_H
#define GD_FFT_PLANNER_IMPL_H

/* Call before creating FFTW plans in code that may run on several threads. Thread-safe;
 * idempotent. */
void gd_fft_planner_init(void);

#endif
