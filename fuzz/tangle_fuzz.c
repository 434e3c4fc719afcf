/* tangle_fuzz.c: libFuzzer target for the tangler (tools/book/tangle.c).
 *
 * Each input is written as a chapter file and tangled into a scratch folder
 * twice, as the build does: with --line --strict (what is compiled) and with
 * --strict alone (the plain tangle, with its markers); the tangler's main is
 * compiled under the name tangle_main. Anything but a clean return (a crash,
 * a leak, undefined behaviour, a hang) is a finding. Run by `make fuzz`. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

int tangle_main(int argc, char **argv);

#define SCRATCH "tangle-fuzz-XXXXXX"

/* Sized for exactly these names, so that none is ever cut short. */
static char chapter[sizeof SCRATCH "/01-fuzz.md"], outdir[sizeof SCRATCH "/out"],
    plain_outdir[sizeof SCRATCH "/plain"];

/* A scratch folder for the whole run, made on the first input in the
 * current folder (make fuzz runs from build/fuzz/scratch, which make clean
 * removes). */
static void make_scratch(void)
{
    char folder[] = SCRATCH;
    if (mkdtemp(folder) == NULL)
        abort();
    snprintf(chapter, sizeof chapter, "%s/01-fuzz.md", folder);
    snprintf(outdir, sizeof outdir, "%s/out", folder);
    snprintf(plain_outdir, sizeof plain_outdir, "%s/plain", folder);
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
    char *plain_argv[] = {"tangle", "--strict", "-o", plain_outdir, chapter, NULL};
    tangle_main(5, plain_argv);
    return 0;
}
