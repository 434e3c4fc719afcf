/* pixel_statement.h: the pixel statement of scene files, and the
 * --pixel option that replaces it (chapter 13). */
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

/* --pixel's settings in place of the scene's, then the worst case of the
 * settings on the image, at the size --size gives or the scene's, checked
 * against PIXEL_RAY_BUDGET, and each primary ray's share of
 * IMAGE_RAY_BUDGET into s->ray_budget; false with err filled, about the
 * option that asks for the most or the pixel statement of the file
 * called name. */
bool pixel_settings_final(scene *s, const char *name, parse_error *err);

#endif
