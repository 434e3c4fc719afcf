/* Independent points for every pattern: no cells, so no stratification. */
void sample_square(enum sample_pattern pattern, int k, int n,
                   sample_stream *g, double *u, double *v)
{
    (void)pattern, (void)k, (void)n;
    *u = sample_next(g), *v = sample_next(g);
}
