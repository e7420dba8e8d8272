/* Loading a model with overrides (geardyn/model_file.h): the YAML document is read,
 * the overrides change it, and the model is read from the changed document, so its
 * validation sees the new values. */
#include <string.h>

#include "geardyn/model_file.h"
#include "model_file/model_file_impl.h"
#include "model_file/overrides_impl.h"

void gd_load_options_init(gd_load_options *opt)
{
    memset(opt, 0, sizeof *opt);
}

/* Takes doc (freed here, whatever happens). */
static gd_status from_doc(gd_ydoc *doc, const char *name, const gd_load_options *opt,
                          gd_model **out, gd_error *err)
{
    gd_status st = gd_ydoc_apply(doc, opt, err);
    if (!st) st = gd_model_from_ydoc(doc, name, out, err);
    gd_ydoc_free(doc);
    return st;
}

gd_status gd_model_load_opts(const char *path, const gd_load_options *opt, gd_model **out,
                             gd_error *err)
{
    *out = NULL;
    gd_ydoc *doc;
    gd_status st = gd_ydoc_load_file(path, &doc, err);
    if (st) return st;
    return from_doc(doc, path, opt, out, err);
}

gd_status gd_model_load_string_opts(const char *yaml, const char *name, const gd_load_options *opt,
                                    gd_model **out, gd_error *err)
{
    *out = NULL;
    gd_ydoc *doc;
    gd_status st = gd_ydoc_load_string(yaml, name, &doc, err);
    if (st) return st;
    return from_doc(doc, name, opt, out, err);
}
