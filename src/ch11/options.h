/* options.h: the command line's options (chapter 1). */
#ifndef OPTIONS_H
#define OPTIONS_H

#include <stdbool.h>
#include <stdio.h>

/* <<command-line options>> ch01 */
typedef struct {
    const char *scene_path; /* NULL: the built-in scene */
    const char *output;
    int width, height;      /* 0: as the scene says */
    bool stats, help;
    /* <<option members>> ch09 */
    int accelerator; /* 0: the scene's; else a mesh_accelerator */
} options;

/* The help text, on out. */
void options_usage(FILE *out, const char *program);

/* Reads argv into *opt; on a mistake prints the error and a hint on stderr
 * and returns false. */
bool options_parse(int argc, char **argv, options *opt);

#endif
