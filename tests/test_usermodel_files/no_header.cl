REAL lonely(REAL c, REAL n)
{
    return pow(c, n);
}
