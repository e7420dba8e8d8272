/* The analyses a study can run, one entry each (analysis_<name>.c). Adding one: write
 * analysis_<name>.c defining `const gd_study_runner gd_study_<name>` (options, outputs,
 * run) and list it here
 * (and its extern in study_impl.h); the study file, the table, MPI and shards need no
 * other change. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study/study_impl.h"

const gd_study_runner *const gd_study_analysis_table[] = {
    &gd_study_modal,     &gd_study_campbell,
    &gd_study_frf,       &gd_study_unbalance,
    &gd_study_transient, &gd_study_mesh_stiffness,
    &gd_study_periodic,  &gd_study_static,
    &gd_study_contact,   NULL};

const char *gd_study_analysis_name(int i)
{
    int n = (int)(sizeof gd_study_analysis_table / sizeof gd_study_analysis_table[0]) - 1;
    return i >= 0 && i < n ? gd_study_analysis_table[i]->name : NULL;
}

const gd_study_runner *gd_study_find_analysis(const char *name)
{
    for (int i = 0; gd_study_analysis_table[i]; i++)
        if (!strcmp(gd_study_analysis_table[i]->name, name)) return gd_study_analysis_table[i];
    return NULL;
}
