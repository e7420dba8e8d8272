/* libFuzzer harness over the model reader and the system build (`make fuzz`): every
 * input is a model file; it must load or fail with a located error, and a model that
 * loads must build its system (and, when small, solve its modes) without a crash,
 * undefined behaviour, a leak or exhaustion. Inputs that raise the size limit
 * (`limits:`) are skipped: a model the user asks to be huge is allowed to be. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/modal.h"
#include "geardyn/model.h"
#include "geardyn/model_file.h"
#include "geardyn/system.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    if (strstr(text, "limits")) {
        free(text);
        return 0;
    }
    gd_model *m = NULL;
    gd_error err;
    gd_error_clear(&err);
    if (gd_model_load_string(text, "fuzz.yaml", &m, &err) == GD_OK) {
        gd_system *sys = NULL;
        if (gd_system_build(m, &sys, &err) == GD_OK) {
            if (sys->ndof <= 60) {
                gd_modal_options opt;
                gd_modal_options_init(&opt);
                opt.speed = m->speed;
                gd_modal_result *res = NULL;
                if (gd_modal_solve(sys, &opt, &res, &err) == GD_OK) gd_modal_free(res);
            }
            gd_system_free(sys);
        }
        gd_model_free(m);
    }
    free(text);
    return 0;
}
