/* material_statement.h: the material statement of a scene file, and
 * materials found by name (chapter 3). */
#ifndef MATERIAL_STATEMENT_H
#define MATERIAL_STATEMENT_H

#include "parse.h"
#include "scene.h"

/* 'material NAME SETTING...': reads the material and adds it to s (or
 * redefines 'default' once); false with p's error. */
bool material_statement_parse(parser *p, scene *s);

/* The index of the material named by the token just read: 0 for
 * "default", k for the scene's k-th material, -1 if there is none. */
int material_statement_find(const scene *s, const parser *p);

#endif
