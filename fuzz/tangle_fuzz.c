/* tangle_fuzz.c: libFuzzer target for the tangler (tools/tangle.c).
 *
 * Each input is written as a chapter file and tangled with --line --strict
 * into a scratch folder, exactly as the build does; the tangler's main is
 * compiled under the name tangle_main. Anything but a clean return (a crash,
 * a leak, undefined behaviour, a hang) is a finding. Run by `make fuzz`. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

int tangle_main(int argc, char **argv);

static char chapter[256], outdir[256];

/* A scratch folder for the whole run, made on the first input in the
 * current folder (make fuzz runs from build/fuzz/scratch, which make clean
 * removes). */
static void make_scratch(void)
{
    char folder[] = "tangle-fuzz-XXXXXX";
    if (mkdtemp(folder) == NULL)
        abort();
    snprintf(chapter, sizeof chapter, "%s/01-fuzz.md", folder);
    snprintf(outdir, sizeof outdir, "%s/out", folder);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (chapter[0] == '\0')
        make_scratch();
    FILE *f = fopen(chapter, "wb");
    if (f == NULL || fwrite(data, 1, size, f) != size || fclose(f) != 0)
        abort();
    char *argv[] = {"tangle", "--line", "--strict", "-o", outdir, chapter, NULL};
    tangle_main(6, argv);
    return 0;
}
