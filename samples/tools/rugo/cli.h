/* What the rugo tool's files share (private to the tool): exit codes, the command line, shape file
 * input and output, the roughness of a shape file, and the commands main() dispatches to. Functions
 * returning int return 0 or an exit code after printing the reason on stderr ("rugo COMMAND: ..."),
 * except parse_*, which return -1 and leave the message to the caller. */
#ifndef RUGO_TOOLS_CLI_H
#define RUGO_TOOLS_CLI_H

#include "rugo/rugo.h"

#include <stdint.h>
#include <stdio.h>

enum { EXIT_INPUT = 1, EXIT_USAGE = 2 };

/* ---- the command line (args.c) ---- */

/* The command being run, for messages. */
extern const char* g_command;

int usage_error(const char* fmt, const char* arg);
int fail(const char* what, rugo_status st);
/* 0 on success, -1 if s is not exactly the value asked for. */
int parse_real(const char* s, double* out);
int parse_int(const char* s, int lo, int hi, int* out);
int parse_pair(const char* s, rugo_vec2* out);
int parse_seed(const char* s, uint64_t* out);
int parse_pose(const char* s, rugo_transform* out);

/* Options: a flat table of "--name" -> value (NULL for flags). Positional arguments in order. */
typedef struct args {
    const char* positional[4];
    int positional_count;
    const char* names[16];
    const char* values[16];
    int count;
} args;

/* Parses argv against the allowed option names (NULL-terminated lists; either may be NULL). */
int parse_args(int argc, char** argv, const char* const* value_options, const char* const* flag_options,
               args* a);
/* Last value given for an option (NULL if absent); *present for flags. */
const char* opt(const args* a, const char* name, int* present);

/* ---- shapes in and out (shape_io.c) ---- */

int load_shape_any(const char* path, rugo_shape_desc* desc, rugo_shape** baked);
int load_shape(const char* path, rugo_shape_desc* desc);
void report_problem(const char* path, rugo_status st, const rugo_contour_problem* pr,
                    const rugo_shape_desc* desc);
void report_parse_error(const char* file, rugo_status st, const rugo_parse_error* err);
int check_outline(const char* path, const rugo_shape_desc* desc, int flags);
int build_pyramid(const char* path, const rugo_shape_desc* desc, rugo_filter filter, int coarsest,
                  rugo_pyramid** out);
int make_shape(const char* path, const rugo_shape_desc* desc, rugo_shape** out);
int write_desc(const char* path, const rugo_shape_desc* d, const char* extra);
int write_shape(const char* path, const rugo_vec2* points, int count, rugo_filter filter, const char* extra);
/* log2(n) for a power of two, -1 otherwise. */
int log2_exact(int n);

/* ---- roughness (roughness.c) ---- */

rugo_roughness_desc roughness_of(const rugo_shape_desc* d);
int finest_tolerances(const char* path, const rugo_roughness_desc* r, const rugo_vec2* points, int n,
                      int reversed, rugo_real** out);
int carried_roughness(const char* path, const rugo_shape_desc* in, int reversed, const rugo_vec2* points,
                      rugo_roughness_desc* out, rugo_real** tol);

/* ---- the commands: argc and argv after the command's name; 0 or an exit code ---- */

int cmd_info(int argc, char** argv);       /* shape_io.c */
int cmd_decompose(int argc, char** argv);  /* edit.c */
int cmd_refine(int argc, char** argv);     /* edit.c */
int cmd_deform(int argc, char** argv);     /* edit.c */
int cmd_fit(int argc, char** argv);        /* edit.c */
int cmd_import(int argc, char** argv);     /* import.c */
int cmd_roughen(int argc, char** argv);    /* roughness.c */
int cmd_tolerances(int argc, char** argv); /* roughness.c */
int cmd_contacts(int argc, char** argv);   /* contacts.c */
int cmd_render(int argc, char** argv);     /* render.c */
int cmd_bake(int argc, char** argv);       /* bake.c */

#endif
