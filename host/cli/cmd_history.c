/* cmd_history.c - placeholder until the history command lands. */
#include "commands.h"
#include "exitcodes.h"
int cmd_history(int argc, char **argv) { (void)argc; (void)argv; return EXIT_USAGE; }
