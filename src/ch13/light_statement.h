/* light_statement.h: the light statement of a scene file (chapter 3). */
#ifndef LIGHT_STATEMENT_H
#define LIGHT_STATEMENT_H

#include "parse.h"
#include "scene.h"

/* 'light KIND SETTING...': reads the light and adds it to s; false with
 * p's error at the first setting that is wrong. */
bool light_statement_parse(parser *p, scene *s);

#endif
