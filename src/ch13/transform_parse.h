/* transform_parse.h: reading the steps of a transform setting
 * (chapter 5). */
#ifndef TRANSFORM_PARSE_H
#define TRANSFORM_PARSE_H

#include "parse.h"

/* <<transform limits>> ch05 */
/* A transform may stretch or shrink no direction by more than this: the
 * infinity norms of its 3x3 part and of its inverse's are at most 1e12. */
#define TRANSFORM_MAX_STRETCH 1e12

/* Reads one or more steps (translate, scale, rotate, shear, matrix), each
 * composed onto *t in the order written, and stops before the first word
 * that is not a step; false with p's error at the step that made the
 * transform unusable. */
bool transform_parse_steps(parser *p, transform *t);

#endif
