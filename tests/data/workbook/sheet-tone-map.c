/* Sheet 3.2 as written: max(alpha I^beta, 1) */
double tone_map(double I, double alpha, double beta)
{
    if (!(I > 0))
        return 0;
    double mapped = alpha * pow(I, beta);
    return mapped > 1 ? mapped : 1;
}
