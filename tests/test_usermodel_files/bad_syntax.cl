/* brdfbench-model
 * name: broken
 * description: line 6 lacks its semicolon
 */
REAL broken(REAL c, REAL n)
{   REAL x = c * n
    return x;
}
