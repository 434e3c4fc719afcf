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

/* <<more OBJ readers>> ch12 */
/* mesh_load_obj_within on threads threads (0: one per core), for files
 * large enough to share: the same mesh, bit for bit, and the same
 * errors; and an error when the file changes while it is read. */
bool mesh_load_obj_on(mesh *m, const char *path, mesh_budget budget,
                      int threads, parse_error *err);

/* mesh_parse_obj within budget, the text cut into parts (1 to
 * OBJ_MAX_PARTS) that threads threads (0: one per core) take in turn:
 * the same mesh and errors. m->parts says how many parts it was read
 * in, or 0 when chapter 4's reader read it after all. */
bool mesh_parse_obj_in_parts(mesh *m, const char *text, size_t length,
                             const char *name, mesh_budget budget,
                             int parts, int threads, parse_error *err);

/* For tests: called, when set, with a file's path once the file is read
 * into memory and before its size is looked at again, where a writer
 * could change it. */
extern void (*obj_test_after_reading)(const char *path);

#define OBJ_MAX_PARTS 1024
/* Parts a thread: its lines cost more where its numbers are longer. */
#define OBJ_PARTS_A_THREAD 8
/* A part is at least this much text: a job costs a thread's waking. */
#define OBJ_MIN_PART_BYTES (1 << 16)
/* parse.c reads a number this long from a copy in memory of its own */
#define OBJ_LONG_NUMBER 64

#endif
