/* material_statement.c: the material statement of a scene file
 * (chapter 3). */
#include "material_statement.h"

#include <string.h>

/* <<finding a material by name>> ch03 */
int material_statement_find(const scene *s, const parser *p)
{
    if (parse_token_is(p, "default"))
        return 0;
    for (int k = 0; k < s->material_count; k++)
        if (parse_token_is(p, s->materials[k].name))
            return k + 1;
    return -1;
}

/* <<material setting readers>> ch07 */

static bool read_ior(parser *p, double *ior)
{
    if (!parse_number(p, "a refractive index", ior))
        return false;
    if (!(*ior >= 1e-3 && *ior <= 1e3)) /* eta^2 stays far from overflow */
        return parse_expected(
            p, "expected a refractive index from 0.001 to 1000");
    return true;
}

static bool read_fresnel_model(parser *p, int *model)
{
    bool named = parse_next_token(p);
    if (named && parse_token_is(p, "exact"))
        *model = FRESNEL_EXACT;
    else if (named && parse_token_is(p, "schlick"))
        *model = FRESNEL_SCHLICK;
    else
        return parse_expected(p, "expected 'exact' or 'schlick'");
    return true;
}

/* <<the material settings>> ch03 */
static const char material_setting_names[] =
    "emission, ambient, diffuse, specular, shininess, highlight"
    /* <<names of material settings>> ch06 */
    ", reflect"
    /* <<names of material settings>> += ch07 */
    ", ior, transparency, fresnel"
    ;

static bool read_highlight_model(parser *p, material *m)
{
    bool named = parse_next_token(p);
    if (named && parse_token_is(p, "phong"))
        m->highlight = HIGHLIGHT_PHONG;
    else if (named && parse_token_is(p, "blinn"))
        m->highlight = HIGHLIGHT_BLINN;
    else
        return parse_expected(p, "expected 'phong' or 'blinn'");
    return true;
}

static bool read_material_setting(parser *p, material *m)
{
    if (parse_token_is(p, "emission"))
        return parse_color(p, "an emitted intensity", &m->emission);
    if (parse_token_is(p, "ambient"))
        return parse_coefficient(p, "an ambient coefficient", &m->ambient);
    if (parse_token_is(p, "diffuse"))
        return parse_coefficient(p, "a diffuse coefficient", &m->diffuse);
    if (parse_token_is(p, "specular"))
        return parse_coefficient(p, "a specular coefficient", &m->specular);
    if (parse_token_is(p, "shininess")) {
        if (!parse_number(p, "a shininess", &m->shininess))
            return false;
        return m->shininess >= 1 ||
               parse_expected(p, "expected a shininess of at least 1");
    }
    if (parse_token_is(p, "highlight"))
        return read_highlight_model(p, m);
    /* <<material settings>> ch06 */
    if (parse_token_is(p, "reflect"))
        return parse_coefficient(p, "a reflectivity", &m->reflect);
    /* <<material settings>> += ch07 */
    if (parse_token_is(p, "ior"))
        return read_ior(p, &m->ior);
    if (parse_token_is(p, "transparency"))
        return parse_coefficient(p, "a transparency", &m->transparency);
    if (parse_token_is(p, "fresnel"))
        return read_fresnel_model(p, &m->fresnel);
    return parse_expected(p, "expected a material setting (%s)",
                          material_setting_names);
}

/* <<the material statement>> ch03 */
bool material_statement_parse(parser *p, scene *s)
{
    material m = material_default();
    if (!parse_next_token(p) || p->token_length >= (int)sizeof m.name)
        return parse_expected(p,
                              "expected a material name of 1 to %d characters",
                              (int)sizeof m.name - 1);
    int existing = material_statement_find(s, p);
    bool redefining_default = existing == 0 && s->default_material.line == 0;
    if (existing >= 0 && !redefining_default)
        return parse_expected(
            p, "expected a new material name (defined on line %d)",
            scene_material(s, existing)->line);
    memcpy(m.name, p->token, (size_t)p->token_length);
    m.name[p->token_length] = '\0';
    m.line = p->line_number;
    while (parse_next_token(p))
        if (!read_material_setting(p, &m))
            return false;
    if (redefining_default)
        s->default_material = m;
    else if (!scene_add_material(s, m))
        return parse_no_room(p, p->line, s->material_count,
                             SCENE_MAX_MATERIALS, "materials");
    return true;
}
