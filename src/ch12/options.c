/* options.c: reading the command line (chapter 1). */
#include "options.h"

#include <stdlib.h>
#include <string.h>
#include "image.h"
#include "message.h"

/* <<the help text>> ch01 */
void options_usage(FILE *out, const char *program)
{
    fprintf(
        out,
        "usage: %s [SCENE] [-o OUT.png] [--size WxH] [--stats] [--help]\n"
        "Renders SCENE (default: this chapter's built-in scene) to OUT.png\n"
        "(default: out.png) as 8-bit sRGB.\n"
        "  -o FILE      where to write the PNG; - for standard output\n"
        "  --size WxH   image size in pixels, overriding the scene's\n"
        "  --stats      print rays traced and time per phase on stderr\n"
        /* <<usage of more options>> ch09 */
        /* <<the usage of --accelerator>> ch10 */
        "  --accelerator kdtree|bvh|bvh-float\n"
        "                        the meshes' trees, overriding the scene's\n"
        /* <<usage of more options>> += ch12 */
        "  --threads N  render on N threads, 1 to 256 (default: one per core)\n"
        "  --help       this text\n",
        program);
    /* <<more help>> ch05 */
    fprintf(out, "\nObject transforms apply in the order written: 'transform "
                 "scale 2 1 1\nrotate z 30 translate 0 0 5' scales, then "
                 "rotates, then moves (T R S).\n");
}

/* <<option errors>> ch01 */
static bool option_error(const char *program, const char *message,
                         const char *found)
{
    char text[512];
    snprintf(text, sizeof text, "%s%s%.400s%s", message,
             found ? ", found '" : "", found ? found : "", found ? "'" : "");
    message_print_error(program, 0, 0, text);
    fputs("Try '", stderr);
    message_print_escaped(program);
    fputs(" --help'.\n", stderr);
    return false;
}

/* <<parse a size>> ch01 */
static bool parse_size(const char *text, int *width, int *height)
{
    char *x, *end;
    if (text[0] < '0' || text[0] > '9')
        return false; /* strtol would take blanks and a sign */
    long w = strtol(text, &x, 10);
    if (*x != 'x' || x[1] < '0' || x[1] > '9')
        return false;
    long h = strtol(x + 1, &end, 10);
    if (*end != '\0' || w < 1 || h < 1 || w > IMAGE_MAX_SIDE ||
        h > IMAGE_MAX_SIDE || w * h > IMAGE_MAX_PIXELS)
        return false;
    *width = (int)w;
    *height = (int)h;
    return true;
}

/* <<parse the arguments>> ch01 */
bool options_parse(int argc, char **argv, options *opt)
{
    *opt = (options){.output = "out.png"};
    for (int k = 1; k < argc; k++) {
        const char *arg = argv[k];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            opt->help = true;
        } else if (strcmp(arg, "--stats") == 0) {
            opt->stats = true;
        } else if (strcmp(arg, "-o") == 0 || strcmp(arg, "--size") == 0) {
            if (k + 1 == argc)
                return option_error(argv[0], "this option needs a value", arg);
            const char *value = argv[++k];
            if (strcmp(arg, "-o") == 0 && value[0] == '\0')
                return option_error(argv[0], "-o expects a file name, or - "
                                             "for standard output", NULL);
            if (strcmp(arg, "-o") == 0)
                opt->output = value;
            else if (!parse_size(value, &opt->width, &opt->height))
                return option_error(
                    argv[0],
                    "--size expects WIDTHxHEIGHT within the image limits",
                    value);
        }
        /* <<more options>> ch09 */
        else if (strcmp(arg, "--accelerator") == 0) {
            if (k + 1 == argc)
                return option_error(argv[0], "this option needs a value", arg);
            const char *value = argv[++k];
            /* mesh_accelerator's names, from 1: options.c does not see mesh.h */
            const char *names[] = {
                "kdtree", "bvh",
                /* <<more accelerator names>> ch10 */
                "bvh-float",
            };
            opt->accelerator = 0;
            for (int j = 0; j < (int)(sizeof names / sizeof *names); j++)
                if (strcmp(value, names[j]) == 0)
                    opt->accelerator = j + 1;
            /* <<what --accelerator expects>> ch10 */
            const char *expects = "--accelerator expects kdtree, bvh or bvh-float";
            if (opt->accelerator == 0)
                return option_error(argv[0], expects, value);
        }
        /* <<more options>> += ch12 */
        else if (strcmp(arg, "--threads") == 0) {
            if (k + 1 == argc)
                return option_error(argv[0], "this option needs a value", arg);
            char *end;
            const char *value = argv[++k];
            long n = strtol(value, &end, 10);
            bool digits = value[0] >= '0' && value[0] <= '9'; /* no blank, sign */
            if (!digits || *end != '\0' || n < 1 || n > 256)
                return option_error(argv[0], "--threads expects a whole number "
                                             "from 1 to 256", value);
            opt->threads = (int)n;
        }
        else if (arg[0] == '-' && arg[1] != '\0') {
            return option_error(argv[0], "unknown option", arg);
        } else if (opt->scene_path == NULL) {
            opt->scene_path = arg;
        } else {
            return option_error(argv[0], "only one scene file can be rendered",
                                arg);
        }
    }
    return true;
}
