/* pixel_statement.c: the pixel statement (chapter 13). */
#include "pixel_statement.h"

#include <math.h>
#include <string.h>

/* <<the pixel statement's words>> ch13 */
/* Where each setting was given in the statement; NULL: it was not. */
typedef struct {
    const char *samples, *pattern, *filter, *threshold, *depth, *min_depth,
        *corners, *heatmap;
} pixel_words;

/* The token just read names a setting seen already? Else remember it. */
static bool once(parser *p, const char **seen)
{
    if (*seen != NULL)
        return parse_fail_at(p, p->token, "'%.*s' is given twice",
                             p->token_length, p->token);
    *seen = p->token;
    return true;
}

/* The next token as one of the n names; its index into *out. */
static bool read_name(parser *p, const char *const *names, int n,
                      const char *expected, int *out)
{
    if (parse_next_token(p))
        for (int k = 0; k < n; k++)
            if (parse_token_is(p, names[k]))
                return *out = k, true;
    return parse_expected(p, "expected %s", expected);
}

/* <<reading the pixel settings>> ch13 */
static bool read_samples(parser *p, int *side)
{
    long n;
    if (!parse_int_in(p, "a number of samples", 1,
                      PIXEL_MAX_SIDE * PIXEL_MAX_SIDE, &n))
        return false;
    long root = lround(sqrt((double)n));
    if (root * root != n)
        return parse_expected(p, "expected a square number of samples "
                                 "(1, 4, 9, ... 256: n x n rays)");
    *side = (int)root;
    return true;
}

static bool read_int_setting(parser *p, const char *what, long lo,
                             long hi, int *out)
{
    long n;
    if (!parse_int_in(p, what, lo, hi, &n))
        return false;
    *out = (int)n;
    return true;
}

/* The setting whose name was just read, and its value. */
static bool read_pixel_setting(parser *p, pixel_sampling *ps,
                               pixel_words *w)
{
    static const char *const patterns[] = {"center", "grid", "jittered",
                                           "adaptive"};
    static const char *const filters[] = {"box", "tent"};
    static const char *const corners[] = {"grid", "jittered"};
    int k = 0; /* read_name sets it before use; the compiler cannot see so */
    if (parse_token_is(p, "samples"))
        return once(p, &w->samples) && read_samples(p, &ps->side);
    if (parse_token_is(p, "pattern"))
        return once(p, &w->pattern) &&
               read_name(p, patterns, 4, "a pattern (center, grid, "
                                         "jittered, adaptive)", &k) &&
               (ps->pattern = (pixel_pattern)k, true);
    if (parse_token_is(p, "filter"))
        return once(p, &w->filter) &&
               read_name(p, filters, 2, "a filter (box, tent)", &k) &&
               (ps->filter = (pixel_filter)k, true);
    if (parse_token_is(p, "threshold"))
        return once(p, &w->threshold) &&
               parse_number_in(p, "a threshold", 0, 1, &ps->threshold);
    if (parse_token_is(p, "depth"))
        return once(p, &w->depth) &&
               read_int_setting(p, "a depth", 1, PIXEL_MAX_DEPTH,
                                &ps->depth);
    if (parse_token_is(p, "min_depth"))
        return once(p, &w->min_depth) &&
               read_int_setting(p, "a minimum depth", 0, PIXEL_MAX_DEPTH,
                                &ps->min_depth);
    if (parse_token_is(p, "corners"))
        return once(p, &w->corners) &&
               read_name(p, corners, 2, "corners (grid, jittered)", &k) &&
               (ps->jittered_corners = k == 1, true);
    if (parse_token_is(p, "heatmap"))
        return once(p, &w->heatmap) &&
               read_int_setting(p, "a number of rays", 1, PIXEL_MAX_RAYS,
                                &ps->heatmap);
    return parse_expected(p, "expected a pixel setting (samples, pattern, "
                             "filter, threshold, depth, min_depth, "
                             "corners, heatmap)");
}

/* <<checking the pixel settings>> ch13 */
static bool check_pixel_settings(parser *p, const pixel_sampling *ps,
                                 const pixel_words *w)
{
    bool sampled = ps->pattern == PIXEL_GRID ||
                   ps->pattern == PIXEL_JITTERED;
    bool adaptive = ps->pattern == PIXEL_ADAPTIVE;
    const char *only_adaptive = w->threshold ? w->threshold
                                : w->depth   ? w->depth
                                : w->corners ? w->corners
                                             : w->min_depth;
    if (w->samples && !sampled)
        return parse_fail_at(p, w->samples, "samples are for the grid and "
                                            "jittered patterns");
    if (w->filter && !sampled)
        return parse_fail_at(p, w->filter, "a filter is for the grid and "
                                           "jittered patterns");
    if (only_adaptive && !adaptive)
        return parse_fail_at(p, only_adaptive, "threshold, depth, "
                                               "min_depth and corners are "
                                               "for the adaptive pattern");
    if (ps->min_depth > ps->depth)
        return parse_fail_at(p, w->min_depth, "expected a minimum depth "
                                              "no deeper than the depth, "
                                              "%d", ps->depth);
    return true;
}

/* Every setting to the end of the line, then the checks. */
static bool read_pixel_settings(parser *p, pixel_sampling *ps)
{
    pixel_words w = {0};
    while (parse_next_token(p))
        if (!read_pixel_setting(p, ps, &w))
            return false;
    return check_pixel_settings(p, ps, &w);
}

/* <<the pixel statement>> ch13 */
bool pixel_statement_parse(parser *p, scene *s)
{
    if (s->pixel_line > 0)
        return parse_fail_at(p, p->token, "a second pixel statement (the "
                                          "first is on line %d)",
                             s->pixel_line);
    s->pixel_line = p->line_number;
    return read_pixel_settings(p, &s->pixels);
}

static bool pixel_option_line(parser *p, void *target)
{
    scene *s = target;
    s->pixels = PIXEL_DEFAULTS;
    return read_pixel_settings(p, &s->pixels);
}

bool pixel_settings_parse(scene *s, const char *text, const char *name,
                          parse_error *err)
{
    if (strchr(text, '\n') != NULL) /* one statement: one line */
        return parse_fail_on_line(err, name, 0, PARSE_BAD_INPUT,
                                  "expected the settings on one line");
    s->pixels = PIXEL_DEFAULTS;
    return parse_lines(text, strlen(text), name, err, pixel_option_line, s);
}

/* What asked for the rays that pass a budget, and its line (0 for an
 * option): the command line before the file, as it replaces the file's
 * settings; the pixel settings where they ask for more than a ray a
 * pixel, the size otherwise. */
static const char *who_asked(const scene *s, const char *name,
                             bool many_rays, int *line)
{
    *line = 0;
    if (many_rays && s->pixel_option != NULL)
        return "--pixel";
    if (s->width_option > 0)
        return "--size";
    *line = many_rays && s->pixel_line > 0 ? s->pixel_line : s->image_line;
    return name;
}

bool pixel_settings_final(scene *s, const char *name, parse_error *err)
{
    if (s->pixel_option != NULL &&
        !pixel_settings_parse(s, s->pixel_option, "--pixel", err))
        return false;
    bool sized = s->width_option > 0;
    int width = sized ? s->width_option : s->cam.width;
    int height = sized ? s->height_option : s->cam.height;
    long long worst = pixel_worst_rays(&s->pixels, width, height);
    long long pixels = (long long)width * height;
    long shadows = scene_shadow_rays(s);
    if (worst <= PIXEL_RAY_BUDGET) /* the rays besides each primary ray */
        s->ray_budget = IMAGE_RAY_BUDGET / worst - 1;
    if (worst <= PIXEL_RAY_BUDGET && s->ray_budget >= shadows)
        return true;
    int line;
    const char *who = who_asked(s, name, worst > pixels, &line);
    long long each = (worst + pixels - 1) / pixels; /* a pixel, at most */
    if (worst <= PIXEL_RAY_BUDGET) /* the rays fit, their shadow rays not */
        return parse_fail_on_line(
            err, who, line, PARSE_OVER_BUDGET,
            "%dx%d pixels of up to %lld primary rays each, and the lights' "
            "%ld shadow rays for each primary ray, would pass the budget "
            "of %lld rays an image", width, height, each, shadows,
            IMAGE_RAY_BUDGET);
    return parse_fail_on_line(err, who, line, PARSE_OVER_BUDGET,
                              "%dx%d pixels of up to %lld primary rays "
                              "each would pass the budget of %lld primary "
                              "rays an image", width, height, each,
                              PIXEL_RAY_BUDGET);
}
