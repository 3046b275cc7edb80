/* brdfbench-model
 * name: nofunction
 */
REAL other_name(REAL c, REAL n) { return pow(c, n); }
