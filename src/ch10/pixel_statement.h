/* pixel_statement.h: the pixel statement of scene files, and the
 * --pixel option that replaces it (chapter 10). */
#ifndef PIXEL_STATEMENT_H
#define PIXEL_STATEMENT_H

#include "parse.h"
#include "scene.h"

/* The statement after its keyword: its settings into s->pixels. */
bool pixel_statement_parse(parser *p, scene *s);

/* The settings of a pixel statement in text (the --pixel option, called
 * name in errors) in place of the scene's; false with err filled. */
bool pixel_settings_parse(scene *s, const char *text, const char *name,
                          parse_error *err);

/* Is the worst case of s's settings on s's image within
 * PIXEL_RAY_BUDGET? If not, false with err filled, about line `line` of
 * name (0: name as a whole). */
bool pixel_check_budget(const scene *s, const char *name, int line,
                        parse_error *err);

#endif
