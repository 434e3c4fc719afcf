/* output.h: the output file, removed when a signal stops the program
 * before it is whole (chapter 1). */
#ifndef OUTPUT_H
#define OUTPUT_H

#include "image.h"

/* From now on the signals that stop the program from outside (SIGINT,
 * SIGTERM, SIGHUP, SIGQUIT, ...) remove the output's temporary file before
 * they stop it (unless they were ignored), and SIGPIPE and SIGXFSZ are
 * ignored: a write to a closed pipe or past the file size limit fails. */
void output_catch_stop_signals(void);

/* png_output_open, with the signal handler told of the temporary file. */
bool output_open(const char *path, png_output *out, char *why,
                 size_t why_size);

/* Removes an unfinished temporary, then tells the handler it is gone. */
void output_close(png_output *out);

#endif
