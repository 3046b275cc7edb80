// Lyon's lobe with k = 2: (1 - n (1 - c) / 4)^4, zeroed past its root, written as a shader would.
float lyon2(float c, float n)
{
    float b = max(1.0 - n * (1.0 - c) * 0.25, 0.0);
    for (int i = 0; i < 2; ++i)
        b *= b;
    return b;
}
