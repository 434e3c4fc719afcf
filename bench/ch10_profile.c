/* ch10_profile.c: where a ray's time goes, in chapter 8's kd-tree and in
 * chapter 9's BVH (chapter 10's wide nodes and packets), exact and in float, by Linux's profiler.
 *
 *   build/rel/bench/ch10_profile > figures/ch10-profile.csv
 *
 * Run without arguments, the program runs itself under `perf record -e
 * cpu-clock` once for each tree and distance of RUNS (the kd-tree, the
 * BVH of the default width and the same BVH with its leaves decided in
 * float, the bunny at K = 1 and K = 2.5), with the
 * arguments TREE K: then it traces the closest hits of the 1024 x 1024
 * rays of bench/ch08_rays.h (the Embree comparison's) PASSES times. `perf
 * report` gives each function's share of the samples, and the functions
 * are added up in the groups of GROUPS: the ray's setup (its constants,
 * the clip of the root box), the walk of the interior nodes, the leaves
 * (the kd-tree's loop over a leaf's triangles; the BVH's filter of four
 * triangles at once in float), the triangles' tests in double, and the
 * rest (the loop, making the rays, reading the mesh and building its
 * tree, a few per cent). `make chart-ch10_profile` builds it without
 * -flto, unlike the other charts: link-time optimization inlines these
 * functions into one another, and a function inlined is counted in its
 * caller. The shares are those of the plain build, each function its
 * own.
 *
 * Rows (method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns):
 *   profile,TREE@K,0,SHARE,share_GROUP     (SHARE: of that run's samples)
 *   profile,TREE@K,0,SAMPLES,samples       (perf's count, to its 3 digits)
 * Without perf, or when it cannot record: profile,absent,0,0,absent. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ch08_rays.h"
#include "timing.h"

enum { SIDE = 1024, PASSES = 60 }; /* the tree's build: a few per cent */

static const struct {
    const char *tree, *name; /* as the command line and the CSV name it */
    double K;
} RUNS[] = {{"kdtree", "kdtree@1.0", 1.0},       {"kdtree", "kdtree@2.5", 2.5},
            {"bvh", "bvh@1.0", 1.0},             {"bvh", "bvh@2.5", 2.5},
            {"bvh-float", "bvh-float@1.0", 1.0}, {"bvh-float", "bvh-float@2.5", 2.5}};
enum { N_RUNS = sizeof RUNS / sizeof RUNS[0] };

/* Which group each function the profile names belongs to; any other is
 * "other". */
static const struct {
    const char *function, *group;
} GROUPS[] = {
    {"mesh_ray_of", "setup"},           {"watertight_ray_of", "setup"},
    {"bvh_ray_of", "setup"},            {"packet_ray_of", "setup"},
    {"box_clip", "setup"},              {"mesh_nearest", "setup"},
    {"mesh_search_tree", "interior"},   {"nearest_in", "interior"},
    {"mesh_search_bvh", "interior"},    {"bvh_walk", "interior"},
    {"search_bvh", "interior"},         {"search_bvh_avx2", "interior"},
    {"search_bvh_plain", "interior"},
    {"kept_in_vectors", "leaves"},      {"nearest_of_packets", "leaves"},
    {"hit_lane", "leaves"},             {"triangle_nearest_of_leaf", "leaves"},
    {"float_hits_in_vectors", "leaves"}, {"triangle_packets_nearest_float", "leaves"},
    {"hit_corners", "double"},          {"hit_sheared", "double"},
    {"triangle_hit_prepared", "double"}, {"triangle_hit_tightened", "double"},
};
static const char *const GROUP_NAMES[] = {"setup", "interior", "leaves",
                                          "double", "other"};
enum { N_GROUPS = 5 };

/* The group of function name (a compiler's suffix, ".constprop.0", cut). */
static int group_of(const char *name)
{
    size_t n = strcspn(name, ".");
    for (size_t k = 0; k < sizeof GROUPS / sizeof GROUPS[0]; k++)
        if (strlen(GROUPS[k].function) == n &&
            strncmp(GROUPS[k].function, name, n) == 0)
            for (int g = 0; g < N_GROUPS; g++)
                if (strcmp(GROUP_NAMES[g], GROUPS[k].group) == 0)
                    return g;
    return N_GROUPS - 1;
}

/* The profiled part: the rays of K through the bunny's tree, PASSES
 * times. */
static int trace(const char *tree, double K)
{
    mesh m;
    load_float_mesh("meshes/bunny.obj", &m);
    bool bvh = strncmp(tree, "bvh", 3) == 0;
    kdtree_params kp = kdtree_default_params();
    bvh_params bp = bvh_default_params();
    if (!(bvh ? mesh_build_bvh(&m, &bp) : mesh_build_tree(&m, &kp)))
        return 1;
    m.bvh_in_float = strcmp(tree, "bvh-float") == 0; /* the float path */
    float_ray *rays = make_rays(&m, K, SIDE);
    render_stats st = {0};
    double sum = 0;
    for (int p = 0; p < PASSES; p++)
        for (long k = 0; k < (long)SIDE * SIDE; k++) {
            mesh_ray mr = mesh_ray_of(ray_of(&rays[k]));
            triangle_hit th;
            sum += mesh_nearest(&m, &mr, 0, INFINITY, &th, &st);
        }
    bench_sink += sum;
    free(rays);
    return 0;
}

/* Records run r under perf into path; false if perf is absent or fails. */
static bool record(const char *self, int r, const char *path)
{
    char command[4096];
    snprintf(command, sizeof command,
             "perf record -q -e cpu-clock -F 4000 -o '%s' -- '%s' %s %.1f "
             ">/dev/null 2>&1", path, self, RUNS[r].tree, RUNS[r].K);
    return system(command) == 0;
}

/* The shares of the groups in the profile at path, into share; the
 * samples, or 0 when it cannot be read. */
static long shares_of(const char *path, double share[N_GROUPS])
{
    char command[1024], line[1024], name[512];
    snprintf(command, sizeof command,
             "perf report -i '%s' --no-children --sort symbol --stdio "
             "2>/dev/null", path);
    FILE *report = popen(command, "r");
    long samples = 0;
    for (int g = 0; g < N_GROUPS; g++)
        share[g] = 0;
    while (report != NULL && fgets(line, sizeof line, report) != NULL) {
        double percent;
        long n;
        char unit = ' ';
        if (sscanf(line, "# Samples: %ld%c", &n, &unit) >= 1)
            samples = n * (unit == 'K' ? 1000 : unit == 'M' ? 1000000 : 1);
        else if (line[0] != '#' &&
                 sscanf(line, " %lf%% [%*[^]]] %511s", &percent, name) == 2)
            share[group_of(name)] += percent / 100;
    }
    if (report != NULL)
        pclose(report);
    return samples;
}

int main(int argc, char **argv)
{
    if (argc == 3)
        return trace(argv[1], atof(argv[2]));
    bench_print_machine();
    bench_csv_header();
    char path[] = "/tmp/ch10-profile-XXXXXX", self[1024];
    int fd = mkstemp(path);
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    self[n > 0 ? n : 0] = '\0'; /* this program, for perf to run */
    for (int r = 0; r < N_RUNS; r++) {
        double share[N_GROUPS];
        long samples = 0;
        if (fd >= 0 && n > 0 && record(self, r, path))
            samples = shares_of(path, share);
        if (samples == 0) {
            printf("profile,absent,0,0,absent\n");
            break;
        }
        bench_timing none = {0};
        for (int g = 0; g < N_GROUPS; g++) {
            char kind[32];
            snprintf(kind, sizeof kind, "share_%s", GROUP_NAMES[g]);
            bench_row("profile", RUNS[r].name, &none, "%.4f", share[g], kind);
        }
        bench_row("profile", RUNS[r].name, &none, "%.0f", (double)samples,
                  "samples");
    }
    if (fd >= 0)
        close(fd), remove(path);
    return 0;
}
