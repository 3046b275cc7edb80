/* brdfbench-model
 * name: unknownkey
 * colour: red
 */
REAL unknownkey(REAL c, REAL n) { return pow(c, n); }
