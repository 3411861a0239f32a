/* proxima check: the assembly interference check of the proxima command
 * (issue 11 §4; docs/check.md). */
#ifndef PROXIMA_CLI_CHECK_H
#define PROXIMA_CLI_CHECK_H

#include <stdint.h>

typedef struct check_opts {
    const char *file;    /* an assembly file, or a folder of part files */
    double clearance;    /* >= 0, finite */
    int json;            /* 1: the JSON document instead of the table */
    uint32_t pieces;     /* px_pieces: TRIANGLES (exact), PARTS or APPROXIMATE */
    double tolerance;    /* approximate pieces (0: the library's default) */
    unsigned threads;    /* approximate pieces (0: one) */
    double scale;        /* 0: 1 */
    const char **ignore; /* "A,B": pairs of part names never reported */
    int nignore;
} check_opts;

/* Runs the check and prints the report on standard output (messages on
 * standard error). Returns the exit status: 0 clean, 1 something found,
 * 2 an error. */
int check_run(const check_opts *o);

#endif /* PROXIMA_CLI_CHECK_H */
