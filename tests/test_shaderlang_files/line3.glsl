float broken(float c, float n)
{
    float t = pow(c, n) * undefined_thing;
    return t;
}
