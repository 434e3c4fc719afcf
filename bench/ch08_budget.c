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
 * and the share of those pixels off by more than one code. Times are
 * processor time of the render alone (the trees are built before).
 *
 * Rows (method,param,ns_per_op,error,error_kind):
 *   sphere-flat|smooth-tree|brute,LEVEL,ns,value,max_code|rms_code|
 *       over_one_code (an icosphere of 20 4^LEVEL triangles against the
 *       analytic sphere, 320 x 240, 200 pixels across)
 *   teapot-tree|brute,N,ns,value,...   (N x N quads a patch, against 64 x 64)
 *   teapot-size,N,0,T,triangles
 *   needed,D,0,LEVEL,level  needed,D,0,T,triangles  needed,D,0,T/D,
 *       triangles_per_pixel_across  needed,D,0,T/area,triangles_per_pixel
 *       (the coarsest smooth icosphere within one code on 99.9% of the
 *       pixels, for a sphere D pixels across)
 * ns_per_op is the render's time per pixel. Brute force stops at
 * BRUTE_MAX_TRIANGLES. */
#include <string.h>

#include "render.h"
#include "ch08_rays.h"

/* Brute force beyond this many triangles takes minutes a render: not run. */
#define BRUTE_MAX_TRIANGLES 5120

/* ---------------------------------------------------------------- an icosphere */

typedef struct {
    int a, b, mid;
} edge_entry;

/* The vertex halfway along the edge (a, b), pushed out to the unit sphere,
 * made once for both triangles that share the edge (a hash of edges). */
static int midpoint(mesh *m, edge_entry *table, int size, int a, int b)
{
    int lo = a < b ? a : b, hi = a < b ? b : a;
    unsigned h = ((unsigned)lo * 2654435761u ^ (unsigned)hi * 40503u) % (unsigned)size;
    while (table[h].mid >= 0 && !(table[h].a == lo && table[h].b == hi))
        h = (h + 1) % (unsigned)size;
    if (table[h].mid < 0) {
        vec3 p = vec3_normalize(vec3_add(m->vertices[lo], m->vertices[hi]));
        m->vertices[m->vertex_count] = p;
        table[h] = (edge_entry){lo, hi, m->vertex_count++};
    }
    return table[h].mid;
}

static void subdivide(mesh *m)
{
    int n = m->triangle_count, size = 6 * n + 1;
    edge_entry *table = malloc((size_t)size * sizeof *table);
    mesh_triangle *next = malloc(4 * (size_t)n * sizeof *next);
    for (int k = 0; k < size; k++)
        table[k].mid = -1;
    for (int f = 0; f < n; f++) {
        int a = m->triangles[f].v[0], b = m->triangles[f].v[1], c = m->triangles[f].v[2];
        int ab = midpoint(m, table, size, a, b), bc = midpoint(m, table, size, b, c);
        int ca = midpoint(m, table, size, c, a);
        next[4 * f] = (mesh_triangle){{a, ab, ca}};
        next[4 * f + 1] = (mesh_triangle){{ab, b, bc}};
        next[4 * f + 2] = (mesh_triangle){{ca, bc, c}};
        next[4 * f + 3] = (mesh_triangle){{ab, bc, ca}};
    }
    free(m->triangles);
    m->triangles = next;
    m->triangle_count = m->triangle_capacity = 4 * n;
    free(table);
}

/* The unit icosphere of 20 4^level triangles, its vertices shared; with
 * smooth, the exact sphere's normals at its vertices. */
static mesh icosphere(int level, bool smooth)
{
    mesh m = {0};
    int faces = 20 << (2 * level), vertices = faces / 2 + 2;
    m.vertices = malloc((size_t)vertices * sizeof *m.vertices);
    m.triangles = malloc(20 * sizeof *m.triangles);
    double g = (1 + sqrt(5.0)) / 2;
    const double c[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                             {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    const int ico[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int k = 0; k < 12; k++)
        m.vertices[k] = vec3_normalize((vec3){c[k][0], c[k][1], c[k][2]});
    for (int f = 0; f < 20; f++)
        m.triangles[f] = (mesh_triangle){{ico[f][0], ico[f][1], ico[f][2]}};
    m.vertex_count = 12, m.triangle_count = 20;
    for (int l = 0; l < level; l++)
        subdivide(&m);
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
    if (!scene_build_trees(s))
        exit(1);
}

/* Renders s into img; the processor seconds it took. */
static double render_seconds(const scene *s, image *img)
{
    render_stats stats = {0};
    if (!image_init(img, s->cam.width, s->cam.height))
        exit(1);
    double start = cpu_seconds();
    render(s, img, &stats);
    return cpu_seconds() - start;
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

static void print_error(const char *method, int param, double ns, image_error e)
{
    printf("%s,%d,%.2f,%.0f,max_code\n", method, param, ns, e.max);
    printf("%s,%d,%.2f,%.4f,rms_code\n", method, param, ns, e.rms);
    printf("%s,%d,%.2f,%.6f,over_one_code\n", method, param, ns, e.over_one);
    fflush(stdout);
}

/* ---------------------------------------------------------------- the measurements */

/* A sphere D pixels across in a square image of 1.25 D, at distance 6. */
static double radius_for(int pixels_across, int side)
{
    double half_width = tan(20 * M_PI / 180); /* fov 40 */
    return 6 * half_width * pixels_across / side;
}

static void spheres(void)
{
    const int width = 320, height = 240, across = 200;
    double ns[2][8] = {{0}};
    double r = radius_for(across, width);
    scene ref;
    image ref_img, img;
    bare_scene(&ref, width, height);
    object o = {.kind = SHAPE_SPHERE, .color = {0.8, 0.75, 0.7}, .sphere = {{0, 0, 6}, r}};
    if (!scene_add_object(&ref, o))
        exit(1);
    render_seconds(&ref, &ref_img);
    for (int smooth = 0; smooth < 2; smooth++)
        for (int level = 0; level <= 7; level++)
            for (int tree = 1; tree >= 0; tree--) {
                char name[64];
                snprintf(name, sizeof name, "sphere-%s-%s", smooth ? "smooth" : "flat",
                         tree ? "tree" : "brute");
                scene s;
                bare_scene(&s, width, height);
                add_mesh(&s, icosphere(level, smooth), r, (vec3){0, 0, 6}, tree);
                bool run = tree || (20 << (2 * level)) <= BRUTE_MAX_TRIANGLES;
                double seconds = run ? render_seconds(&s, &img) : -1;
                if (run) {
                    if (smooth)
                        ns[tree][level] = 1e9 * seconds / (width * height);
                    print_error(name, level, 1e9 * seconds / (width * height),
                                compare(&img, &ref_img, s.bg.bottom));
                    image_free(&img);
                }
                scene_free(&s);
            }
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
        render_seconds(&ref, &ref_img);
        int level = 0;
        for (; level <= 8; level++) {
            scene s;
            bare_scene(&s, side, side);
            add_mesh(&s, icosphere(level, true), r, (vec3){0, 0, 6}, true);
            render_seconds(&s, &img);
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
        printf("needed,%d,0,%.2f,triangles_per_pixel_across\n", sizes[k], triangles / (double)sizes[k]);
        printf("needed,%d,0,%.3f,triangles_per_pixel\n", sizes[k], triangles / area);
        fflush(stdout);
        image_free(&ref_img);
        scene_free(&ref);
    }
}

/* The teapot 4 units wide, seen from the front at 320 x 240. */
static void teapots(void)
{
    const int levels[] = {2, 3, 4, 6, 8, 12, 16, 24, 32, 48};
    double over[10], ns[2][10] = {{0}};
    scene ref;
    image ref_img, img;
    bare_scene(&ref, 320, 240);
    add_mesh(&ref, teapot(64), 0.6, (vec3){-0.1, -0.9, 7}, true);
    render_seconds(&ref, &ref_img);
    for (size_t k = 0; k < sizeof levels / sizeof *levels; k++)
        for (int tree = 1; tree >= 0; tree--) {
            scene s;
            bare_scene(&s, 320, 240);
            mesh m = teapot(levels[k]);
            int triangles = m.triangle_count;
            add_mesh(&s, m, 0.6, (vec3){-0.1, -0.9, 7}, tree);
            if (tree || triangles <= BRUTE_MAX_TRIANGLES) {
                double seconds = render_seconds(&s, &img);
                image_error e = compare(&img, &ref_img, s.bg.bottom);
                ns[tree][k] = 1e9 * seconds / (320 * 240);
                over[k] = e.over_one;
                print_error(tree ? "teapot-tree" : "teapot-brute", levels[k], ns[tree][k], e);
                printf("teapot-size,%d,0,%d,triangles\n", levels[k], triangles);
                image_free(&img);
            }
            scene_free(&s);
        }
    image_free(&ref_img);
    scene_free(&ref);
    for (int k = 0; k + 1 < 10; k++) /* the quads a side where the share */
        if (over[k] > 0.001 && over[k + 1] <= 0.001) { /* reaches 1/1000 */
            double f = log(over[k] / 0.001) / log(over[k] / over[k + 1]);
            printf("teapot-needed,0,0,%.1f,quads_per_side\n",
                   levels[k] * pow((double)levels[k + 1] / levels[k], f));
        }
    printf("teapot-ratio,8,0,%.1f,brute_over_tree\n", ns[0][4] / ns[1][4]);
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
    printf("method,param,ns_per_op,error,error_kind\n");
    if (argc > 2 && strcmp(argv[2], "needed") == 0) {
        needed_levels();
        return 0;
    }
    spheres();
    needed_levels();
    teapots();
    return 0;
}
