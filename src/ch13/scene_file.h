/* scene_file.h: reading a scene from text (chapter 1).
 *
 * scene_parse and scene_load apply a scene file on top of what the scene
 * already holds (scene_init's defaults, usually). On bad input they return
 * false and describe the first problem in err; they never print. */
#ifndef SCENE_FILE_H
#define SCENE_FILE_H

#include "parse.h"
#include "scene.h"

typedef parse_error scene_error;

#define SCENE_MAX_BYTES (16L << 20) /* a scene file is text, not data */

/* Reads statements from text[0..length); name is the file name for errors. */
bool scene_parse(scene *s, const char *text, size_t length, const char *name,
                 scene_error *err);

/* Reads the scene file at path (at most SCENE_MAX_BYTES) and parses it. */
bool scene_load(scene *s, const char *path, scene_error *err);

#endif
