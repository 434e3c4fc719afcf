/* obj.h: reading Wavefront OBJ meshes (chapter 4).
 *
 * On bad input the readers fill err (the OBJ file's line and column, or
 * line 0 when the file cannot be read) and return false; the mesh then
 * holds what was read so far, for mesh_free. */
#ifndef OBJ_H
#define OBJ_H

#include "mesh.h"
#include "parse.h"

#define OBJ_MAX_BYTES (512L << 20) /* half a gigabyte of text */

/* What one mesh may take, within the limits of mesh.h. */
typedef struct {
    long triangles;  /* at most MESH_MAX_TRIANGLES */
    long long bytes; /* of its arrays, as allocated: see mesh_bytes */
} mesh_budget;

/* Reads the OBJ file at path into the zeroed mesh m. */
bool mesh_load_obj(mesh *m, const char *path, parse_error *err);

/* The same within budget: crossing it is an error of kind
 * PARSE_OVER_BUDGET, at the line that crossed it. */
bool mesh_load_obj_within(mesh *m, const char *path, mesh_budget budget,
                          parse_error *err);

/* The same for OBJ text already in memory, text[0..length), called name. */
bool mesh_parse_obj(mesh *m, const char *text, size_t length,
                    const char *name, parse_error *err);

#endif
