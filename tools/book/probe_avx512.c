/* probe_avx512.c: does this compiler, with these flags, pass a struct of
 * doubles built from a compound literal by value correctly? GCC 12.2 with
 * -mavx512f at -O2 does not: its SLP vectorizer stores the literal wrongly.
 * Exits 0 when the struct arrives whole, 1 when it arrives damaged. Run by
 * tools/book/probe_native.sh for make NATIVE=1. The functions are external so
 * that the compiler keeps the by-value calling convention the bug is in. */
typedef struct {
    double x, y, z;
} vec3;

typedef struct {
    vec3 origin, dir;
} ray;

__attribute__((noinline)) int arrives_whole(ray r)
{
    return r.origin.x == 0.25 && r.origin.y == 0.25 && r.origin.z == 0 &&
           r.dir.x == 0 && r.dir.y == 0 && r.dir.z == 1;
}

__attribute__((noinline)) int pass_a_literal(void)
{
    return arrives_whole((ray){{0.25, 0.25, 0}, {0, 0, 1}});
}

int main(void)
{
    return pass_a_literal() ? 0 : 1;
}
