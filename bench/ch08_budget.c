/* ch08_budget.c: how much model does a picture need? Tessellations of a
 * sphere and of the Utah teapot's patches, against the exact shape (or the
 * finest tessellation), in image error against render time, with the
 * kd-tree and by brute force.
 *
 *   build/rel/bench/ch08_budget [TEAPOT-PATCHES] > figures/ch08-budget.csv
 *   build/rel/bench/ch08_budget --obj LEVEL > meshes/icosphere-LEVEL.obj
 *
 * Every render is the renderer's own (render(), one thread), of a scene
 * made here: a grey floor-less view, one directional light, the shape in
 * the middle. Errors are in 8-bit sRGB codes, over the pixels that the
 * reference shape covers or the tessellation covers: the largest, the RMS,
 * and the share of those pixels off by more than one code.
 *
 * Times (bench/timing.h): one operation is one whole render of a case's
 * scene (the trees built before). The renders of one family (flat
 * icospheres, smooth icospheres, teapots), every level with the tree and by
 * brute force, are timed together, interleaved, in RENDER_ROUNDS rounds of
 * thread CPU time (brute force takes seconds a render); every scene of the
 * family is built first and freed after. The images for the errors are
 * rendered once, before the timing.
 *
 * Rows (method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns), after
 * the "# machine:" line:
 *   sphere-flat|smooth-tree|brute,LEVEL,ns,value,max_code|rms_code|
 *       over_one_code (an icosphere of 20 4^LEVEL triangles against the
 *       analytic sphere, 320 x 240, 200 pixels across)
 *   teapot-tree|brute,N,ns,value,...   (N x N quads a patch, against 64 x 64)
 *   teapot-size,N,0,T,triangles
 *   teapot-needed,0,0,N,quads_per_side  teapot-ratio,8,0,X,brute_over_tree
 *   growth,sphere-smooth-tree,0,X,level7_over_level0
 *   growth,sphere-smooth-brute,0,X,level4_over_level0     (from medians)
 *   needed-curve,D:LEVEL,0,share,over_one_code
 *   needed,D,0,LEVEL,level  needed,D,0,T,triangles  needed,D,0,T/D,
 *       triangles_per_pixel_across  needed,D,0,T/area,triangles_per_pixel
 *       (the coarsest smooth icosphere within one code on 99.9% of the
 *       pixels, for a sphere D pixels across)
 * ns_per_op, ns_q1, ns_q3 and wall_ns are a render's median, quartiles and
 * median wall time divided by its pixels: ns per pixel. Brute force stops
 * at BRUTE_MAX_TRIANGLES. */
#include <string.h>

#include "render.h"
#include "trees.h"
#include "ch08_rays.h"
#include "timing.h"

/* Brute force beyond this many triangles takes minutes a render: not run. */
#define BRUTE_MAX_TRIANGLES 5120

/* ---------------------------------------------------------------- an icosphere */

/* The unit icosphere of 20 4^level triangles (ch08_rays.h); with smooth,
 * the exact sphere's normals at its vertices. */
static mesh icosphere(int level, bool smooth)
{
    mesh m = unit_icosphere(level);
    if (smooth) { /* vertex k's normal is vertex k itself */
        m.normals = malloc((size_t)m.vertex_count * sizeof *m.normals);
        memcpy(m.normals, m.vertices, (size_t)m.vertex_count * sizeof *m.normals);
        m.normal_count = m.vertex_count;
        m.triangle_normals = malloc((size_t)m.triangle_count * sizeof *m.triangle_normals);
        memcpy(m.triangle_normals, m.triangles, (size_t)m.triangle_count * sizeof *m.triangles);
    }
    mesh_compute_bounds(&m);
    return m;
}

/* ---------------------------------------------------------------- the teapot */

static int n_patches, n_points;
static int patches[32][16];
static vec3 points[306];

static void read_patches(const char *path)
{
    FILE *f = fopen(path, "r");
    if (f == NULL || fscanf(f, "%d", &n_patches) != 1 || n_patches != 32) {
        fprintf(stderr, "%s: not Newell's 32 patches\n", path);
        exit(1);
    }
    for (int p = 0; p < 32; p++)
        for (int k = 0; k < 16; k++)
            if (fscanf(f, " %d ,", &patches[p][k]) != 1)
                exit(1);
    if (fscanf(f, "%d", &n_points) != 1 || n_points != 306)
        exit(1);
    for (int k = 0; k < 306; k++) {
        double x, y, z;
        if (fscanf(f, " %lf , %lf , %lf", &x, &y, &z) != 3)
            exit(1);
        points[k] = (vec3){x, z, -y}; /* z-up to y-up */
    }
    fclose(f);
}

static void bernstein(double t, double b[4], double d[4])
{
    double s = 1 - t;
    b[0] = s * s * s, b[1] = 3 * t * s * s, b[2] = 3 * t * t * s, b[3] = t * t * t;
    d[0] = -3 * s * s, d[1] = 3 * s * s - 6 * t * s, d[2] = 6 * t * s - 3 * t * t, d[3] = 3 * t * t;
}

/* Patch p at (u, v): the point, and the normal from its derivatives. */
static vec3 patch_point(int p, double u, double v, vec3 *normal)
{
    double bu[4], du[4], bv[4], dv[4];
    bernstein(u, bu, du), bernstein(v, bv, dv);
    vec3 pt = {0, 0, 0}, tu = {0, 0, 0}, tv = {0, 0, 0};
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            vec3 c = points[patches[p][4 * i + j] - 1];
            pt = vec3_add(pt, vec3_scale(c, bu[i] * bv[j]));
            tu = vec3_add(tu, vec3_scale(c, du[i] * bv[j]));
            tv = vec3_add(tv, vec3_scale(c, bu[i] * dv[j]));
        }
    *normal = vec3_cross(tv, tu); /* zero at a pole: the face's normal then */
    return pt;
}

/* The teapot with n x n quads a patch (two triangles each; the ones that
 * collapse at the poles dropped), with the patches' own normals. */
static mesh teapot(int n)
{
    mesh m = {0};
    int per = (n + 1) * (n + 1);
    m.vertices = malloc(32 * (size_t)per * sizeof *m.vertices);
    m.normals = malloc(32 * (size_t)per * sizeof *m.normals);
    m.triangles = malloc(64 * (size_t)n * n * sizeof *m.triangles);
    for (int p = 0; p < 32; p++) {
        int base = m.vertex_count;
        for (int i = 0; i <= n; i++)
            for (int j = 0; j <= n; j++)
                m.vertices[m.vertex_count++] =
                    patch_point(p, (double)i / n, (double)j / n, &m.normals[base + i * (n + 1) + j]);
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                int a = base + i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
                const int quad[2][3] = {{a, c, d}, {a, d, b}};
                for (int t = 0; t < 2; t++) {
                    vec3 x = m.vertices[quad[t][0]], y = m.vertices[quad[t][1]];
                    vec3 z = m.vertices[quad[t][2]];
                    vec3 cr = vec3_cross(vec3_sub(y, x), vec3_sub(z, x));
                    if (cr.x != 0 || cr.y != 0 || cr.z != 0)
                        m.triangles[m.triangle_count++] =
                            (mesh_triangle){{quad[t][0], quad[t][1], quad[t][2]}};
                }
            }
    }
    m.normal_count = m.vertex_count;
    m.triangle_normals = malloc((size_t)m.triangle_count * sizeof *m.triangle_normals);
    memcpy(m.triangle_normals, m.triangles, (size_t)m.triangle_count * sizeof *m.triangles);
    mesh_compute_bounds(&m);
    return m;
}

/* ---------------------------------------------------------------- scenes and images */

/* A scene of width x height with nothing in it but a light: the shape
 * comes next. */
static void bare_scene(scene *s, int width, int height)
{
    scene_init(s);
    s->cam.width = width, s->cam.height = height, s->cam.fov_deg = 40;
    s->bg = (background){BACKGROUND_SOLID, {0.2, 0.22, 0.25}, {0, 0, 0}};
    s->ambient = (vec3){0.2, 0.2, 0.2};
    light L = {.kind = LIGHT_DIRECTIONAL, .direction = vec3_normalize((vec3){1, -1, 1.5}),
               .intensity = {0.9, 0.9, 0.9}};
    if (!scene_add_light(s, L))
        exit(1);
}

/* Adds the mesh m, moved by `at` and scaled by `scale`, as the scene's one
 * object, with or without a tree. */
static void add_mesh(scene *s, mesh m, double scale, vec3 at, bool tree)
{
    for (int k = 0; k < m.vertex_count; k++)
        m.vertices[k] = vec3_add(vec3_scale(m.vertices[k], scale), at);
    mesh_compute_bounds(&m);
    object o = {.kind = SHAPE_MESH, .color = {0.8, 0.75, 0.7}};
    if ((o.mesh = scene_add_mesh(s, m)) < 0 || !scene_add_object(s, o))
        exit(1);
    s->tree_params.method = tree ? KDTREE_SAH : KDTREE_NONE;
    if (!scene_build_trees(s, NULL))
        exit(1);
}

/* Renders s into img, made here at the scene's size. */
static void render_new(const scene *s, image *img)
{
    render_stats stats = {0};
    if (!image_init(img, s->cam.width, s->cam.height))
        exit(1);
    render(s, img, &stats);
}

typedef struct {
    double max, rms, over_one; /* codes; share of the pixels */
} image_error;

/* The error of img against ref over the pixels where either shows the
 * shape (not the background colour bg). */
static image_error compare(const image *img, const image *ref, vec3 bg)
{
    image_error e = {0, 0, 0};
    long covered = 0, over = 0;
    double sum = 0;
    unsigned char b[3] = {srgb_to_byte(bg.x), srgb_to_byte(bg.y), srgb_to_byte(bg.z)};
    for (long k = 0; k < (long)img->width * img->height; k++) {
        const double x[3] = {img->pixels[k].x, img->pixels[k].y, img->pixels[k].z};
        const double y[3] = {ref->pixels[k].x, ref->pixels[k].y, ref->pixels[k].z};
        bool shape = false;
        int worst = 0;
        for (int c = 0; c < 3; c++) {
            int p = srgb_to_byte(x[c]), q = srgb_to_byte(y[c]);
            shape = shape || p != b[c] || q != b[c];
            int d = abs(p - q);
            worst = d > worst ? d : worst;
            sum += (double)d * d / 3;
        }
        covered += shape;
        over += worst > 1;
        e.max = worst > e.max ? worst : e.max;
    }
    e.rms = sqrt(sum / (covered ? covered : 1));
    e.over_one = (double)over / (covered ? covered : 1);
    return e;
}

/* ---------------------------------------------------------------- timed renders */

/* Every family's images are 320 x 240. */
enum { WIDTH = 320, HEIGHT = 240 };

/* Rounds of a family's timing: its brute-force renders take up to 3 s each,
 * and with 7 rounds the whole benchmark takes about two minutes. */
#define RENDER_ROUNDS 7

/* One render of a family: its scene, its error against the reference and
 * its time per pixel. */
typedef struct {
    scene s;
    char method[32], param[16];
    int level; /* the icosphere's level or the teapot's quads a side */
    image_error e;
    bench_timing t; /* ns per pixel */
} render_case;

static image frame; /* where every timed render draws, one after another */

/* reps renders of the case's scene into frame. */
static void run_render(void *ctx, long reps)
{
    const render_case *c = ctx;
    for (long r = 0; r < reps; r++) {
        render_stats stats = {0};
        render(&c->s, &frame, &stats);
        bench_sink += frame.pixels[(long)WIDTH * HEIGHT / 2].x;
    }
}

/* Renders each of the n cases once for its error against ref, then times
 * the renders of all n together, interleaved; frees their scenes. */
static void measure(render_case *c, int n, const image *ref)
{
    bench_case *cases = malloc((size_t)n * sizeof *cases);
    bench_timing *t = malloc((size_t)n * sizeof *t);
    if (!cases || !t || !image_init(&frame, WIDTH, HEIGHT))
        exit(1);
    for (int k = 0; k < n; k++) {
        render_stats stats = {0};
        render(&c[k].s, &frame, &stats);
        c[k].e = compare(&frame, ref, c[k].s.bg.bottom);
        cases[k] = (bench_case){c[k].method, c[k].param, run_render, &c[k], 1};
    }
    bench_time_cases_rounds(cases, n, RENDER_ROUNDS, t);
    for (int k = 0; k < n; k++) {
        c[k].t = bench_timing_scaled(t[k], 1.0 / ((double)WIDTH * HEIGHT));
        scene_free(&c[k].s);
    }
    image_free(&frame);
    free(cases), free(t);
}

/* Fills in c as the render of mesh m (scaled and moved) with or without a
 * tree. */
static void make_case(render_case *c, const char *method, int level, mesh m, double scale,
                      vec3 at, bool tree)
{
    snprintf(c->method, sizeof c->method, "%s-%s", method, tree ? "tree" : "brute");
    snprintf(c->param, sizeof c->param, "%d", level);
    c->level = level;
    bare_scene(&c->s, WIDTH, HEIGHT);
    add_mesh(&c->s, m, scale, at, tree);
}

static void print_error(const render_case *c)
{
    bench_row(c->method, c->param, &c->t, "%.0f", c->e.max, "max_code");
    bench_row(c->method, c->param, &c->t, "%.4f", c->e.rms, "rms_code");
    bench_row(c->method, c->param, &c->t, "%.6f", c->e.over_one, "over_one_code");
}

/* ---------------------------------------------------------------- the measurements */

/* A sphere D pixels across in a square image of 1.25 D, at distance 6. */
static double radius_for(int pixels_across, int side)
{
    double half_width = tan(20 * M_PI / 180); /* fov 40 */
    return 6 * half_width * pixels_across / side;
}

/* The icospheres of levels 0 to 7, flat or smooth, with the tree and (up
 * to BRUTE_MAX_TRIANGLES) by brute force, against the analytic sphere;
 * their times per pixel in ns[tree][level] when ns is not NULL. */
static void sphere_family(bool smooth, const image *ref, double r, double ns[2][8])
{
    render_case *c = calloc(16, sizeof *c);
    int n = 0;
    const char *name = smooth ? "sphere-smooth" : "sphere-flat";
    if (!c)
        exit(1);
    for (int level = 0; level <= 7; level++)
        for (int tree = 1; tree >= 0; tree--)
            if (tree || (20 << (2 * level)) <= BRUTE_MAX_TRIANGLES)
                make_case(&c[n++], name, level, icosphere(level, smooth), r, (vec3){0, 0, 6},
                          tree);
    measure(c, n, ref);
    for (int k = 0; k < n; k++) {
        print_error(&c[k]);
        if (ns)
            ns[strstr(c[k].method, "-tree") != NULL][c[k].level] = c[k].t.median;
    }
    fflush(stdout);
    free(c);
}

static void spheres(void)
{
    double ns[2][8] = {{0}};
    double r = radius_for(200, WIDTH); /* 200 pixels across */
    scene ref;
    image ref_img;
    bare_scene(&ref, WIDTH, HEIGHT);
    object o = {.kind = SHAPE_SPHERE, .color = {0.8, 0.75, 0.7}, .sphere = {{0, 0, 6}, r}};
    if (!scene_add_object(&ref, o))
        exit(1);
    render_new(&ref, &ref_img);
    sphere_family(false, &ref_img, r, NULL);
    sphere_family(true, &ref_img, r, ns);
    image_free(&ref_img);
    scene_free(&ref);
    printf("growth,sphere-smooth-tree,0,%.2f,level7_over_level0\n", ns[1][7] / ns[1][0]);
    printf("growth,sphere-smooth-brute,0,%.1f,level4_over_level0\n", ns[0][4] / ns[0][0]);
}

static void needed_levels(void)
{
    const int sizes[] = {25, 50, 100, 200, 400};
    for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++) {
        int side = (int)(1.25 * sizes[k]);
        double r = radius_for(sizes[k], side);
        scene ref;
        image ref_img, img;
        bare_scene(&ref, side, side);
        object o = {.kind = SHAPE_SPHERE, .color = {0.8, 0.75, 0.7}, .sphere = {{0, 0, 6}, r}};
        if (!scene_add_object(&ref, o))
            exit(1);
        render_new(&ref, &ref_img);
        int level = 0;
        for (; level <= 8; level++) {
            scene s;
            bare_scene(&s, side, side);
            add_mesh(&s, icosphere(level, true), r, (vec3){0, 0, 6}, true);
            render_new(&s, &img);
            image_error e = compare(&img, &ref_img, s.bg.bottom);
            image_free(&img);
            scene_free(&s);
            printf("needed-curve,%d:%d,0,%.6f,over_one_code\n", sizes[k], level, e.over_one);
            if (e.over_one <= 0.001) /* one code or less on 99.9% of the pixels */
                break;
        }
        int triangles = 20 << (2 * level);
        double area = M_PI / 4 * sizes[k] * sizes[k];
        printf("needed,%d,0,%d,level\n", sizes[k], level);
        printf("needed,%d,0,%d,triangles\n", sizes[k], triangles);
        printf("needed,%d,0,%.2f,triangles_per_pixel_across\n", sizes[k],
               triangles / (double)sizes[k]);
        printf("needed,%d,0,%.3f,triangles_per_pixel\n", sizes[k], triangles / area);
        fflush(stdout);
        image_free(&ref_img);
        scene_free(&ref);
    }
}

/* The quads a side where the share of pixels off by more than one code
 * reaches 1/1000, between the levels that straddle it. */
static void teapot_needed(const int *levels, const double *over, int n)
{
    for (int k = 0; k + 1 < n; k++)
        if (over[k] > 0.001 && over[k + 1] <= 0.001) {
            double f = log(over[k] / 0.001) / log(over[k] / over[k + 1]);
            printf("teapot-needed,0,0,%.1f,quads_per_side\n",
                   levels[k] * pow((double)levels[k + 1] / levels[k], f));
        }
}

/* The teapot 4 units wide, seen from the front at 320 x 240. */
static void teapots(void)
{
    enum { N_LEVELS = 10 };
    const int levels[N_LEVELS] = {2, 3, 4, 6, 8, 12, 16, 24, 32, 48};
    const vec3 at = {-0.1, -0.9, 7};
    double over[N_LEVELS], ns[2] = {0, 0};
    render_case *c = calloc(2 * N_LEVELS, sizeof *c);
    int n = 0, triangles[2 * N_LEVELS];
    scene ref;
    image ref_img;
    if (!c)
        exit(1);
    bare_scene(&ref, WIDTH, HEIGHT);
    add_mesh(&ref, teapot(64), 0.6, at, true);
    render_new(&ref, &ref_img);
    for (int k = 0; k < N_LEVELS; k++)
        for (int tree = 1; tree >= 0; tree--) {
            mesh m = teapot(levels[k]);
            if (!tree && m.triangle_count > BRUTE_MAX_TRIANGLES) {
                mesh_free(&m);
                continue;
            }
            triangles[n] = m.triangle_count;
            make_case(&c[n++], "teapot", levels[k], m, 0.6, at, tree);
        }
    measure(c, n, &ref_img);
    for (int k = 0, level = 0; k < n; k++) {
        level += k > 0 && c[k].level != c[k - 1].level;
        over[level] = c[k].e.over_one;
        print_error(&c[k]);
        printf("teapot-size,%d,0,%d,triangles\n", c[k].level, triangles[k]);
        if (c[k].level == 8)
            ns[strstr(c[k].method, "-tree") != NULL] = c[k].t.median;
    }
    image_free(&ref_img);
    scene_free(&ref);
    free(c);
    teapot_needed(levels, over, N_LEVELS);
    printf("teapot-ratio,8,0,%.1f,brute_over_tree\n", ns[0] / ns[1]);
}

/* The icosphere of the level as OBJ text, vertices and faces only. */
static void write_obj(int level)
{
    mesh m = icosphere(level, false);
    printf("# icosphere: 20 4^%d = %d triangles on the unit sphere, made by\n"
           "# bench/ch08_budget.c --obj %d\n",
           level, m.triangle_count, level);
    for (int k = 0; k < m.vertex_count; k++)
        printf("v %.7g %.7g %.7g\n", m.vertices[k].x, m.vertices[k].y, m.vertices[k].z);
    for (int k = 0; k < m.triangle_count; k++)
        printf("f %d %d %d\n", m.triangles[k].v[0] + 1, m.triangles[k].v[1] + 1,
               m.triangles[k].v[2] + 1);
    mesh_free(&m);
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "--obj") == 0) {
        write_obj(atoi(argv[2]));
        return 0;
    }
    read_patches(argc > 1 ? argv[1] : "meshes/teapot-newell-patches.txt");
    bench_print_machine();
    bench_csv_header();
    if (argc > 2 && strcmp(argv[2], "needed") == 0) {
        needed_levels();
        return 0;
    }
    spheres();
    needed_levels();
    teapots();
    return 0;
}
