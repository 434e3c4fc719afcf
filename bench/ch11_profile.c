/* ch11_profile.c: where a ray's instructions go, in chapter 8's kd-tree
 * and in chapter 9's BVH (chapter 10's packets, chapter 11's wide nodes), exact and
 * in float, counted by Valgrind's callgrind.
 *
 *   build/rel/bench/ch11_profile > figures/ch11-profile.csv
 *
 * Run without arguments, the program runs itself under `valgrind
 * --tool=callgrind --dump-instr=yes` once for each tree and distance of
 * RUNS (the kd-tree, the BVH of the default width and the same BVH with
 * its leaves decided in float, the bunny at K = 1 and K = 2.5), with the
 * arguments TREE K: then it reads the mesh, builds the tree and makes the
 * SIDE x SIDE rays of bench/ch08_rays.h (the Embree comparison's), and
 * only then counts, over the closest hits of every ray (callgrind's
 * client requests start and stop the count). Callgrind counts the
 * instructions executed at each address of the program; addr2line names
 * the chain of functions inlined at that address, and an instruction
 * belongs to the group of GROUPS of the innermost function of its chain
 * that GROUPS names: the ray's setup (its constants, the clip of the
 * mesh's box), the walk of the interior nodes, the leaves (the kd-tree's
 * loop over a leaf's triangles; the BVH's filter of four triangles at
 * once in float, or its test in float), the triangles' tests in double,
 * and the rest (the loop over the rays, a few per cent). Since the
 * chain is read through the inlining, the program is measured as the
 * charts build it, with link-time optimization. Instructions, not
 * times: a count does not change when the machine is busy, and a
 * processor runs some instructions faster than others, so that a share
 * of the instructions is near a share of the time, not equal to it.
 *
 * Rows (method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns):
 *   profile,TREE@K,0,SHARE,share_GROUP     (SHARE: of that run's count)
 *   profile,TREE@K,0,N,instructions_per_ray
 * Without Valgrind (or its callgrind.h when built), or without addr2line:
 * profile,absent,0,0,absent. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#if defined(__has_include) && !defined(NO_CALLGRIND) /* -D: as without */
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define HAVE_CALLGRIND 1
#endif
#endif

#include "ch08_rays.h"
#include "timing.h"

enum { SIDE = 256 };

static const struct {
    const char *tree, *name; /* as the command line and the CSV name it */
    double K;
} RUNS[] = {{"kdtree", "kdtree@1.0", 1.0},       {"kdtree", "kdtree@2.5", 2.5},
            {"bvh", "bvh@1.0", 1.0},             {"bvh", "bvh@2.5", 2.5},
            {"bvh-float", "bvh-float@1.0", 1.0}, {"bvh-float", "bvh-float@2.5", 2.5}};
enum { N_RUNS = sizeof RUNS / sizeof RUNS[0] };

static const char *const GROUP_NAMES[] = {"setup", "interior", "leaves",
                                          "double", "other"};
enum { N_GROUPS = 5 };

#ifdef HAVE_CALLGRIND
/* Which group each function belongs to; an instruction whose chain of
 * inlined functions names none of them is "other". */
static const struct {
    const char *function, *group;
} GROUPS[] = {
    {"mesh_ray_of", "setup"},            {"watertight_ray_of", "setup"},
    {"ray_inverse_dir", "setup"},        {"box_clip", "setup"},
    {"bvh_misses_box", "setup"},         {"bvh_ray_of", "setup"},
    {"bvh_wide_ray_of", "setup"},        {"bvh_ray8_of", "setup"},
    {"bvh_ray8_setup", "setup"},         {"bvh_ray8_setup_avx2", "setup"},
    {"bvh_round_origin", "setup"},       {"bvh_walk_rows", "setup"},
    {"packet_ray_of", "setup"},          {"mesh_nearest", "setup"},
    {"mesh_search_bvh", "setup"},        {"search_avx2_exact", "setup"},
    {"search_avx2_float", "setup"},      {"search_plain_exact", "setup"},
    {"search_plain_float", "setup"}, /* the walk's entry and return */
    {"mesh_search_tree", "interior"},    {"nearest_in", "interior"},
    {"search_bvh8", "interior"},         {"search_bvh2", "interior"},
    {"bvh_node8_lanes", "interior"},     {"bvh_node8_lanes_avx2", "interior"},
    {"bvh_node8_test", "interior"},      {"bvh_push8", "interior"},
    {"bvh_push8_avx2", "interior"},      {"bvh_walk_next", "interior"},
    {"bvh_leaf_test", "leaves"},         {"candidates", "leaves"},
    {"kept_in_vectors", "leaves"},       {"kept_alone", "leaves"},
    {"triangle_packets_nearest_in_mesh", "leaves"},
    {"triangle_packets_any_in_mesh", "leaves"},
    {"triangle_packets_nearest_float", "leaves"},
    {"triangle_packets_any_float", "leaves"},
    {"float_hits_in_vectors", "leaves"}, {"float_interval_of", "leaves"},
    {"nearest_of_packets", "leaves"},    {"hit_lane", "leaves"},
    {"triangle_nearest_of_leaf", "leaves"},
    {"hit_in_mesh", "double"},           {"hit_corners", "double"},
    {"hit_sheared", "double"},           {"triangle_hit_prepared", "double"},
    {"triangle_hit_tightened", "double"},
};
/* The group of function name (a compiler's suffix, ".constprop.0", cut),
 * or -1 if GROUPS does not name it. */
static int group_of(const char *name)
{
    size_t n = strcspn(name, ".\n");
    for (size_t k = 0; k < sizeof GROUPS / sizeof GROUPS[0]; k++)
        if (strlen(GROUPS[k].function) == n &&
            strncmp(GROUPS[k].function, name, n) == 0)
            for (int g = 0; g < N_GROUPS; g++)
                if (strcmp(GROUP_NAMES[g], GROUPS[k].group) == 0)
                    return g;
    return -1;
}

/* The counted part: the closest hits of n rays through m. */
static __attribute__((noinline)) double trace_rays(const mesh *m,
                                                   const float_ray *rays,
                                                   long n)
{
    render_stats st = {0};
    double sum = 0;
    CALLGRIND_TOGGLE_COLLECT;
    for (long k = 0; k < n; k++) {
        mesh_ray mr = mesh_ray_of(ray_of(&rays[k]));
        triangle_hit th;
        sum += mesh_nearest(m, &mr, 0, INFINITY, &th, &st);
    }
    CALLGRIND_TOGGLE_COLLECT;
    return sum;
}

/* The child, under callgrind: the rays of K through the bunny's tree. */
static int trace(const char *tree, double K)
{
    mesh m;
    load_float_mesh("meshes/bunny.obj", &m);
    bool bvh = strncmp(tree, "bvh", 3) == 0;
    kdtree_params kp = kdtree_default_params();
    bvh_params bp = {0}; /* zeros: the mesh's defaults, as the renderer's */
    if (!(bvh ? mesh_build_bvh(&m, &bp) : mesh_build_tree(&m, &kp)))
        return 1;
    m.bvh_in_float = strcmp(tree, "bvh-float") == 0; /* the float path */
    float_ray *rays = make_rays(&m, K, SIDE);
    bench_sink += trace_rays(&m, rays, (long)SIDE * SIDE);
    free(rays);
    return 0;
}
#endif

#ifdef HAVE_CALLGRIND
/* An address of the program and the instructions counted there. */
typedef struct {
    unsigned long address;
    double count;
} counted;

/* The program's addresses in callgrind's file at path (--dump-instr=yes,
 * --dump-line=no), into *out (grown with realloc); their number, or -1.
 * Other objects' instructions (the C library's) are added to *elsewhere. */
static long read_counts(const char *path, const char *self, counted **out,
                        double *elsewhere)
{
    FILE *f = fopen(path, "r");
    char line[4096];
    long n = 0, room = 0;
    unsigned long address = 0;
    bool ours = false, call_cost = false;
    char our_id[32] = ""; /* callgrind's number for this program */
    *elsewhere = 0;
    while (f != NULL && fgets(line, sizeof line, f) != NULL) {
        bool ob = strncmp(line, "ob=", 3) == 0;
        if (ob || strncmp(line, "cob=", 4) == 0) {
            char *id = strchr(line, '('), *close = strchr(line, ')');
            if (id == NULL || close == NULL)
                continue;
            *close = '\0'; /* "(N) name" the first time, then "(N)" */
            if (close[1] == ' ' && strncmp(close + 2, self, strlen(self)) == 0)
                snprintf(our_id, sizeof our_id, "%s", id + 1);
            if (ob)
                ours = our_id[0] != '\0' && strcmp(id + 1, our_id) == 0;
            continue;
        }
        if (strncmp(line, "calls=", 6) == 0) {
            call_cost = true; /* the next line is a call's inclusive cost */
            continue;
        }
        char *end;
        if (line[0] == '0' && line[1] == 'x')
            address = strtoul(line, &end, 16);
        else if (line[0] == '+' || line[0] == '-')
            address += (unsigned long)strtol(line, &end, 10);
        else if (line[0] == '*')
            end = line + 1;
        else
            continue;
        double cost = strtod(end, NULL);
        if (call_cost) {
            call_cost = false;
            continue;
        }
        if (!ours) {
            *elsewhere += cost;
            continue;
        }
        if (n == room) {
            room = room ? 2 * room : 4096;
            counted *grown = realloc(*out, (size_t)room * sizeof **out);
            if (grown == NULL)
                return fclose(f), -1;
            *out = grown;
        }
        (*out)[n++] = (counted){address, cost};
    }
    if (f == NULL)
        return -1;
    fclose(f);
    return n;
}

/* Adds each address's count to the group of the innermost function of
 * its chain that GROUPS names, as addr2line reads the chains from self. */
static bool add_groups(const char *self, const counted *c, long n,
                       double share[N_GROUPS])
{
    char list[] = "/tmp/ch11-profile-addresses-XXXXXX", command[4400];
    int fd = mkstemp(list);
    FILE *out = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (out == NULL)
        return false;
    for (long k = 0; k < n; k++)
        fprintf(out, "0x%lx\n", c[k].address);
    fclose(out);
    snprintf(command, sizeof command,
             "addr2line -i -f -a -e '%s' < '%s' 2>/dev/null", self, list);
    FILE *in = popen(command, "r");
    char line[4096];
    long k = -1;
    int group = -1; /* of address k, once its innermost named function */
    bool any = false;
    while (in != NULL && fgets(line, sizeof line, in) != NULL) {
        if (strncmp(line, "0x", 2) == 0) { /* the next address's chain */
            if (k >= 0)
                share[group >= 0 ? group : N_GROUPS - 1] += c[k].count;
            k++, group = -1, any = true;
        } else if (k >= 0 && k < n && group < 0 && line[0] != '/' &&
                   line[0] != '?' && strchr(line, ':') == NULL)
            group = group_of(line); /* a function's line, not a place's */
    }
    if (k >= 0 && k < n)
        share[group >= 0 ? group : N_GROUPS - 1] += c[k].count;
    bool ok = in != NULL && pclose(in) == 0 && any && k == n - 1;
    remove(list);
    return ok;
}

/* Runs run r under callgrind and adds up its groups into share; the
 * instructions a ray, or 0 when it cannot. */
static double profile_run(const char *self, int r, double share[N_GROUPS])
{
    char dir[] = "/tmp/ch11-profile-XXXXXX", command[4400], path[1100];
    if (mkdtemp(dir) == NULL)
        return 0;
    snprintf(path, sizeof path, "%s/callgrind.out", dir);
    snprintf(command, sizeof command,
             "valgrind --tool=callgrind --collect-atstart=no "
             "--dump-instr=yes --dump-line=no --callgrind-out-file='%s' "
             "'%s' %s %.1f >/dev/null 2>&1", path, self, RUNS[r].tree,
             RUNS[r].K);
    counted *c = NULL;
    double elsewhere = 0, total = 0;
    long n = system(command) == 0 ? read_counts(path, self, &c, &elsewhere)
                                  : -1;
    for (int g = 0; g < N_GROUPS; g++)
        share[g] = 0;
    if (n > 0 && add_groups(self, c, n, share)) {
        share[N_GROUPS - 1] += elsewhere;
        for (int g = 0; g < N_GROUPS; g++)
            total += share[g];
        for (int g = 0; g < N_GROUPS && total > 0; g++)
            share[g] /= total;
    }
    free(c);
    snprintf(command, sizeof command, "rm -rf '%s'", dir);
    if (system(command) != 0)
        fprintf(stderr, "ch11_profile: %s left behind\n", dir);
    return total / ((double)SIDE * SIDE);
}
#endif

int main(int argc, char **argv)
{
#ifdef HAVE_CALLGRIND
    if (argc == 3)
        return trace(argv[1], atof(argv[2]));
#endif
    (void)argv;
    if (argc != 1) {
        fprintf(stderr, "usage: ch11_profile > CSV\n");
        return 2;
    }
    bench_print_machine();
    bench_csv_header();
    char self[1024];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    self[n > 0 ? n : 0] = '\0'; /* this program, for valgrind to run */
    for (int r = 0; r < N_RUNS; r++) {
        double share[N_GROUPS], per_ray = 0;
#ifdef HAVE_CALLGRIND
        if (n > 0)
            per_ray = profile_run(self, r, share);
#endif
        if (per_ray <= 0) {
            printf("profile,absent,0,0,absent\n");
            break;
        }
        bench_timing none = {0};
        for (int g = 0; g < N_GROUPS; g++) {
            char kind[32];
            snprintf(kind, sizeof kind, "share_%s", GROUP_NAMES[g]);
            bench_row("profile", RUNS[r].name, &none, "%.4f", share[g], kind);
        }
        bench_row("profile", RUNS[r].name, &none, "%.1f", per_ray,
                  "instructions_per_ray");
    }
    return 0;
}
