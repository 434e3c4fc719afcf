/* ch11_instructions.c: the instructions a ray costs, counted by Valgrind's
 * callgrind, in the BVH of chapters 9 to 11 (exact, and decided in float)
 * and in Intel Embree 3, for each kind of ray.
 *
 *   build/rel/bench/ch11_instructions > figures/ch11-instructions.csv
 *
 * Run without arguments, the program runs itself under `valgrind
 * --tool=callgrind --collect-atstart=no`: with the argument "count", it
 * reads the bunny, builds the trees, makes the 256 x 256 rays of
 * bench/ch08_rays.h at K = 1 and sorts them by kind, and only then
 * counts: each method's trace of each kind of ray is collected alone and
 * written to a file of its own (callgrind's client requests), so the
 * reading of the mesh and the builds are never counted. Instructions
 * are a measure that a shared machine does not disturb, where times are
 * not: a run gives the same counts as the next.
 *
 * The kinds: rays that miss the mesh's box (miss-box), rays that enter
 * it and hit nothing (enter-miss), rays that hit (hit), and all of them
 * (all). The methods: the BVH of the default width, exact (bvh) and in
 * float (fast), and Embree's rtcIntersect1 (HIGH, one thread), each
 * given the ray as the Embree comparison gives it (ch11_embree.c: the
 * program makes its mesh_ray, Embree its RTCRayHit). The cost of the
 * loop itself (a pass over the rays that traces none) is taken off.
 *
 * Rows (method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns):
 *   instructions,METHOD@KIND,0,N,instructions_per_ray
 *   rays,KIND,0,COUNT,rays
 *   ratio,METHOD@KIND,0,R,instructions_over_embree
 *   vector,WIDTH_NAME,0,0,bvh_vector_width  (the node test's instructions)
 *   visits,bvh@KIND,0,N,nodes_per_ray       (and triangles_per_ray: what
 *   the exact walk visits, a ray of each kind, from the program's own
 *   counters; bvh@hit-answer-known: a hit ray bounded by its own t)
 * Without Valgrind (or its callgrind.h when built), or without Embree:
 * instructions,absent,0,0,absent and, for Embree alone, no Embree rows. */
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

#ifdef HAVE_EMBREE
#include "embree_scene.h"
#endif
#include "ch08_rays.h"
#include "timing.h"

enum { SIDE = 256 };

/* The row that names the node test's instructions. */
static void print_vector(bool avx2, bool avx512)
{
    printf("vector,%s,0,0,bvh_vector_width\n",
           avx512 ? "AVX-512VL chosen at run time"
           : avx2 ? "AVX2 chosen at run time"
                  : "the build's own instructions");
}

/* The kinds of ray: index 0 all of them, then 1 to 3. */
static const char *const KINDS[] = {"all", "miss-box", "enter-miss", "hit"};

/* The kind of ray f through m's exact BVH (an index of KINDS, not 0);
 * the walk's counters added to *stats, a hit's answer in *th. */
static int kind_through(const mesh *m, const float_ray *f,
                        render_stats *stats, triangle_hit *th)
{
    mesh_ray mr = mesh_ray_of(ray_of(f));
    double near = 0, far = INFINITY;
    if (!box_clip(&m->bounds, mr.r.origin, mr.inv_dir, &near, &far))
        return 1;
    return mesh_nearest(m, &mr, 0, INFINITY, th, stats) >= 0 ? 3 : 2;
}

#ifdef HAVE_CALLGRIND
static const char *const METHODS[] = {"loop", "bvh", "fast", "embree"};
enum { N_KINDS = 4, N_METHODS = 4 };

/* What a count traces: the bunny, its BVH both ways, Embree's scene. */
typedef struct {
    mesh m, m_float; /* the same tree, decided exactly and in float */
#ifdef HAVE_EMBREE
    RTCScene scene;
#endif
} subject;

/* Ray f by method (an index of METHODS): 1 for a hit, else 0. The
 * program's counters in *stats, kept from one ray to the next as the
 * renderer keeps them. Never inlined: its code, and so the counts, stay
 * the same when the rest of this file changes. */
static __attribute__((noinline)) int one_ray(const subject *s, int method, const float_ray *f,
                   render_stats *stats)
{
    if (method == 0)
        return f->d[0] > 2; /* the loop alone: never */
#ifdef HAVE_EMBREE
    if (method == 3) {
        struct RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        struct RTCRayHit rh;
        rh.ray.org_x = f->o[0], rh.ray.org_y = f->o[1], rh.ray.org_z = f->o[2];
        rh.ray.dir_x = f->d[0], rh.ray.dir_y = f->d[1], rh.ray.dir_z = f->d[2];
        rh.ray.tnear = 0, rh.ray.tfar = INFINITY;
        rh.ray.mask = 0xffffffffu, rh.ray.flags = 0, rh.ray.time = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(s->scene, &context, &rh);
        return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
#endif
    triangle_hit th;
    mesh_ray mr = mesh_ray_of(ray_of(f));
    const mesh *m = method == 2 ? &s->m_float : &s->m;
    return mesh_nearest(m, &mr, 0, INFINITY, &th, stats) >= 0;
}

/* The kind of ray f (an index of KINDS, not 0). */
static int kind_of(const subject *s, const float_ray *f)
{
    render_stats stats = {0};
    triangle_hit th;
    return kind_through(&s->m, f, &stats, &th);
}

/* The rays of kind k (0: all) moved to the front of rays; how many. */
static long keep_kind(const subject *s, float_ray *rays, long n, int k)
{
    long kept = 0;
    for (long j = 0; j < n; j++)
        if (k == 0 || kind_of(s, &rays[j]) == k) {
            float_ray f = rays[j];
            rays[j] = rays[kept], rays[kept++] = f;
        }
    return kept;
}

/* The counted part: n rays by method, callgrind collecting. */
static __attribute__((noinline)) long trace(const subject *s, int method,
                                            const float_ray *rays, long n)
{
    long hits = 0;
    render_stats stats = {0};
    CALLGRIND_TOGGLE_COLLECT;
    for (long k = 0; k < n; k++)
        hits += one_ray(s, method, &rays[k], &stats);
    CALLGRIND_TOGGLE_COLLECT;
    return hits;
}

/* The child, under callgrind: every method's trace of every kind, each
 * dumped apart as "METHOD KIND"; prints "KIND COUNT" for each kind, after
 * "avx2 0|1" and "avx512 0|1" for its walk's instructions. */
static int count(void)
{
    subject s;
    load_float_mesh("meshes/bunny.obj", &s.m);
    bvh_params bp = {0}; /* zeros: the mesh's defaults, as the renderer's */
    if (!mesh_build_bvh(&s.m, &bp))
        return 1;
    s.m_float = s.m, s.m_float.bvh_in_float = true; /* shares the tree */
    int methods = 3;
#ifdef HAVE_EMBREE
    RTCDevice device = rtcNewDevice("threads=1");
    s.scene = embree_scene(device, &s.m, RTC_BUILD_QUALITY_HIGH);
    rtcCommitScene(s.scene);
    methods = 4;
#endif
    long n = (long)SIDE * SIDE;
    /* what the walk takes under callgrind, which may hide AVX-512 */
    printf("avx2 %d\navx512 %d\n", s.m.bvh.avx2, s.m.bvh.avx512);
    for (int k = 0; k < N_KINDS; k++) {
        float_ray *rays = make_rays(&s.m, 1.0, SIDE);
        long kept = keep_kind(&s, rays, n, k);
        printf("%s %ld\n", KINDS[k], kept);
        for (int j = 0; j < methods; j++) {
            char name[64];
            bench_sink += (double)trace(&s, j, rays, kept);
            snprintf(name, sizeof name, "%s %s", METHODS[j], KINDS[k]);
            CALLGRIND_DUMP_STATS_AT(name);
        }
        free(rays);
    }
    return 0;
}

/* The instructions of the dump "METHOD KIND" among files prefix.N; -1 if
 * absent. */
static double counted(const char *prefix, const char *name)
{
    char path[4200], line[512], want[128];
    snprintf(want, sizeof want, "desc: Trigger: Client Request: %s\n", name);
    for (int d = 1; d < 64; d++) {
        snprintf(path, sizeof path, "%s.%d", prefix, d);
        FILE *f = fopen(path, "r");
        if (f == NULL)
            continue;
        bool ours = false;
        double total = -1;
        while (fgets(line, sizeof line, f) != NULL) {
            ours = ours || strcmp(line, want) == 0;
            if (strncmp(line, "totals: ", 8) == 0)
                total = atof(line + 8);
        }
        fclose(f);
        if (ours)
            return total;
    }
    return -1;
}

/* Runs this program under callgrind into files prefix.N; reads the rays
 * of each kind into rays, and the walk's instructions into isa[2] (AVX2,
 * AVX-512VL); false if it cannot. */
static bool run_counts(const char *self, const char *prefix,
                       long rays[N_KINDS], long isa[2])
{
    char command[8400], kind[32];
    snprintf(command, sizeof command,
             "valgrind --tool=callgrind --collect-atstart=no "
             "--callgrind-out-file='%s' '%s' count 2>/dev/null",
             prefix, self);
    FILE *child = popen(command, "r");
    long n;
    int got = 0;
    while (child != NULL && fscanf(child, "%31s %ld", kind, &n) == 2) {
        if (strcmp(kind, "avx2") == 0 || strcmp(kind, "avx512") == 0)
            isa[kind[3] == '5'] = n;
        for (int k = 0; k < N_KINDS; k++)
            if (strcmp(kind, KINDS[k]) == 0)
                rays[k] = n, got++;
    }
    return child != NULL && pclose(child) == 0 && got == N_KINDS;
}

static void print_counts(const char *prefix, const long rays[N_KINDS])
{
    bench_timing none = {0};
    for (int k = 0; k < N_KINDS; k++) {
        bench_row("rays", KINDS[k], &none, "%.0f", (double)rays[k], "rays");
        char name[64], param[64];
        snprintf(name, sizeof name, "loop %s", KINDS[k]);
        double loop = counted(prefix, name), per[N_METHODS] = {0};
        for (int j = 1; j < N_METHODS && rays[k] > 0; j++) {
            snprintf(name, sizeof name, "%s %s", METHODS[j], KINDS[k]);
            double total = counted(prefix, name);
            if (total < 0 || loop < 0)
                continue;
            per[j] = (total - loop) / (double)rays[k];
            snprintf(param, sizeof param, "%s@%s", METHODS[j], KINDS[k]);
            bench_row("instructions", param, &none, "%.1f", per[j],
                      "instructions_per_ray");
        }
        for (int j = 1; j < 3 && per[3] > 0; j++) {
            snprintf(param, sizeof param, "%s@%s", METHODS[j], KINDS[k]);
            bench_row("ratio", param, &none, "%.4f", per[j] / per[3],
                      "instructions_over_embree");
        }
    }
}

/* Counts every method's instructions under callgrind and prints their
 * rows; false if it cannot. */
static bool count_all(void)
{
    char dir[] = "/tmp/ch11-instructions-XXXXXX", self[1024];
    char prefix[2048];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    self[n > 0 ? n : 0] = '\0'; /* this program, for valgrind to run */
    long rays[N_KINDS] = {0}, isa[2] = {0};
    if (n <= 0 || mkdtemp(dir) == NULL)
        return false;
    snprintf(prefix, sizeof prefix, "%s/callgrind.out", dir);
    bool ran = run_counts(self, prefix, rays, isa);
    if (ran) {
        print_vector(isa[0], isa[1]);
        print_counts(prefix, rays);
    }
    char command[2200];
    snprintf(command, sizeof command, "rm -rf '%s'", dir);
    if (system(command) != 0)
        fprintf(stderr, "ch11_instructions: %s left behind\n", dir);
    return ran;
}
#endif

/* What the exact walk visits, a ray of each kind (1 miss-box, 2
 * enter-miss, 3 hit): the nodes whose children it tests and the
 * triangles of the leaves it tests, from the program's own counters; and
 * for the rays that hit, the nodes it would test with its answer known
 * before it set out (the bound just past its own t). Counted natively:
 * the counters are the same under callgrind and without it. */
static void print_visits(void)
{
    mesh m;
    load_float_mesh("meshes/bunny.obj", &m);
    bvh_params bp = {0}; /* zeros: the mesh's defaults, as the renderer's */
    if (!mesh_build_bvh(&m, &bp))
        exit(1);
    long n = (long)SIDE * SIDE, rays[4] = {0};
    render_stats by_kind[4] = {{0}}, known = {0};
    float_ray *all = make_rays(&m, 1.0, SIDE);
    for (long j = 0; j < n; j++) {
        triangle_hit th;
        render_stats one = {0};
        int k = kind_through(&m, &all[j], &one, &th);
        mesh_ray mr = mesh_ray_of(ray_of(&all[j]));
        if (k == 3) /* again, bounded by its own answer */
            mesh_nearest(&m, &mr, 0, nextafter(th.t, INFINITY), &th,
                         &known);
        rays[k]++, by_kind[k].bvh_nodes += one.bvh_nodes;
        by_kind[k].triangle_tests += one.triangle_tests;
    }
    bench_timing none = {0};
    for (int k = 1; k < 4; k++) {
        char param[64];
        double count = rays[k] > 0 ? (double)rays[k] : 1;
        snprintf(param, sizeof param, "bvh@%s", KINDS[k]);
        bench_row("visits", param, &none, "%.2f",
                  (double)by_kind[k].bvh_nodes / count, "nodes_per_ray");
        bench_row("visits", param, &none, "%.2f",
                  (double)by_kind[k].triangle_tests / count,
                  "triangles_per_ray");
    }
    bench_row("visits", "bvh@hit-answer-known", &none, "%.2f",
              (double)known.bvh_nodes / (rays[3] > 0 ? (double)rays[3] : 1),
              "nodes_per_ray");
    free(all);
    mesh_free(&m);
}

int main(int argc, char **argv)
{
#ifdef HAVE_CALLGRIND
    if (argc == 2 && strcmp(argv[1], "count") == 0)
        return count();
#endif
    (void)argv;
    if (argc != 1) {
        fprintf(stderr, "usage: ch11_instructions > CSV\n");
        return 2;
    }
    bench_print_machine();
    bench_csv_header();
    print_visits();
#ifdef HAVE_CALLGRIND
    if (count_all())
        return 0;
#endif
    print_vector(bvh_walks_with_avx2(), bvh_walks_with_avx512());
    printf("instructions,absent,0,0,absent\n");
    return 0;
}
