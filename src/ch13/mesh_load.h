/* mesh_load.h: the meshes a scene file names, read from their OBJ files,
 * placed and added to the scene within its budget (chapter 4). */
#ifndef MESH_LOAD_H
#define MESH_LOAD_H

#include "parse.h"
#include "scene.h"

/* Reads the OBJ file of source, places its mesh and adds it to s: its
 * index in s, or -1 with p's error filled. The error is at the OBJ file's
 * line and column when its text is wrong, else at the token at, on the
 * scene line that named the file. */
int mesh_load_into(parser *p, scene *s, const char *at,
                   const mesh_source *source);

#endif
