/* What every reader of test data uses: the line cursor over a file in memory, a new
 * function in the set, and the checks every function passes (an increasing frequency
 * axis, finite values). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testdata/testdata_impl.h"

int gd_td_next_line(gd_td_text *t, const char **s, size_t *n)
{
    if (t->pos >= t->len) return 0;
    const char *b = t->buf + t->pos;
    const char *e = memchr(b, '\n', t->len - t->pos);
    size_t m = e ? (size_t)(e - b) : t->len - t->pos;
    t->pos += m + (e ? 1 : 0);
    t->partial = !e;
    if (m && b[m - 1] == '\r') m--;
    t->line++;
    *s = b;
    *n = m;
    return 1;
}

gd_td_function *gd_td_push(gd_testdata *td, const char *file, int line)
{
    gd_td_function *nf = realloc(td->functions, (size_t)(td->nfunctions + 1) * sizeof *nf);
    if (!nf) return NULL;
    td->functions = nf;
    gd_td_function *f = &nf[td->nfunctions++];
    memset(f, 0, sizeof *f);
    f->line = line;
    f->to_si = 1;
    snprintf(f->file, sizeof f->file, "%s", file);
    return f;
}

gd_status gd_td_check(const gd_td_function *f, const char *field, gd_error *err)
{
    for (int k = 0; k < f->n; k++) {
        if (!isfinite(f->freq_hz[k]) || f->freq_hz[k] < 0)
            return gd_error_set(err, GD_EINPUT, f->file, f->line, 0, field,
                                "frequencies are finite and not negative",
                                "function '%s': frequency %d is %g", f->name, k + 1, f->freq_hz[k]);
        if (k > 0 && !(f->freq_hz[k] > f->freq_hz[k - 1]))
            return gd_error_set(err, GD_EINPUT, f->file, f->line, 0, field,
                                "sort the lines by frequency and remove repeated ones",
                                "function '%s': the frequency axis does not increase at line "
                                "%d (%g Hz after %g Hz)",
                                f->name, k + 1, f->freq_hz[k], f->freq_hz[k - 1]);
        if (!isfinite(f->re[k]) || !isfinite(f->im[k]))
            return gd_error_set(err, GD_EINPUT, f->file, f->line, 0, field,
                                "measured values must be finite numbers",
                                "function '%s': value %d at %g Hz is not finite", f->name, k + 1,
                                f->freq_hz[k]);
    }
    return GD_OK;
}
