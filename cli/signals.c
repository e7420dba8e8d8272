/* SIGINT, SIGTERM and SIGHUP in the CLI: one process-wide handler, installed by main
 * before any thread exists, so the signal is handled the same whichever thread the
 * kernel picks (OpenMP and OpenBLAS workers block nothing: a mask set in the calling
 * thread alone let a worker take the default action mid-write, issue 38 M3).
 *
 * Outside a commit the handler runs the registered clean-up (the --out stage's files)
 * and ends the process with the signal's default action. During a commit (the --plot
 * file written and renamed, the --out folder put in place) it only notes the signal:
 * gd_cli_commit_end delivers it once the commit is whole, so a reader sees the old
 * file or the new one and no FILE.tmp-PID-XXXXXX is left. A commit is short (a few MB
 * written, a few renames).
 *
 * This and the stage list of outdir.c are the CLI's process-wide state: a signal
 * handler has nothing else to reach. The library installs no handler. */
#include <signal.h>
#include <stdatomic.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

enum { IDLE = 0, COMMITTING = 1, ENDING = 2 };

static atomic_int g_state = IDLE; /* IDLE, COMMITTING or ENDING */
static atomic_int g_pending = 0;  /* a signal that came during a commit */
static void (*volatile g_cleanup)(void) = NULL;
static int g_depth; /* nested commits (the main thread's only) */

/* Clean-up, then the signal's default action (the exit status a shell expects). */
static void end_with(int sig)
{
    void (*fn)(void) = g_cleanup;
    if (fn) fn();
    signal(sig, SIG_DFL);
    sigset_t one;
    sigemptyset(&one);
    sigaddset(&one, sig);
    raise(sig);
    /* from the handler the signal is blocked until it returns: unblock it here, so
     * the process ends now and this thread does not go back to work */
    pthread_sigmask(SIG_UNBLOCK, &one, NULL);
    for (;;)
        pause();
}

static void on_signal(int sig)
{
    int expect = IDLE;
    if (atomic_compare_exchange_strong(&g_state, &expect, ENDING)) end_with(sig);
    if (expect != COMMITTING) return; /* another thread is already ending the process */
    int none = 0;
    atomic_compare_exchange_strong(&g_pending, &none, sig);
    /* the commit may have ended between the two reads: then end here */
    expect = IDLE;
    if (atomic_compare_exchange_strong(&g_state, &expect, ENDING)) end_with(sig);
}

void gd_cli_signals_install(void)
{
    static const int sigs[3] = {SIGINT, SIGTERM, SIGHUP};
    for (int i = 0; i < 3; i++) {
        struct sigaction old;
        /* a signal the caller ignores (nohup) stays ignored */
        if (sigaction(sigs[i], NULL, &old) == 0 && old.sa_handler == SIG_IGN) continue;
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_signal;
        sa.sa_flags = SA_RESTART; /* the commit's writes and renames are not interrupted */
        sigfillset(&sa.sa_mask);
        sigaction(sigs[i], &sa, NULL);
    }
}

void gd_cli_signals_cleanup(void (*fn)(void))
{
    g_cleanup = fn;
}

void gd_cli_commit_begin(void)
{
    if (g_depth++ > 0) return;
    int expect = IDLE;
    if (atomic_compare_exchange_strong(&g_state, &expect, COMMITTING)) return;
    /* a signal is already ending the process: no commit starts */
    for (;;)
        pause();
}

void gd_cli_commit_end(void)
{
    if (--g_depth > 0) return;
    int expect = COMMITTING;
    atomic_compare_exchange_strong(&g_state, &expect, IDLE);
    int sig = atomic_exchange(&g_pending, 0);
    if (!sig) return;
    expect = IDLE;
    if (atomic_compare_exchange_strong(&g_state, &expect, ENDING)) end_with(sig);
    for (;;) /* the handler's thread is ending the process */
        pause();
}
