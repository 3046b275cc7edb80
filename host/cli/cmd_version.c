/* cmd_version.c - `brdfbench version`: the program's version and git revision, as every
 * command's --version prints them. */
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"

int cmd_version(int argc, char **argv)
{
    char err[512];
    const struct cli_command cmd = {
        .name = "version",
        .about = "  Prints the program's version and the git revision it was built from.\n",
    };
    int prc = cli_parse(&cmd, argc, argv, NULL, err, sizeof err);
    if (prc == CLI_ANSWERED)
        return EXIT_OK;
    if (prc) {
        fprintf(stderr, "brdfbench version: %s\n", err);
        return EXIT_USAGE;
    }
    cli_print_version(stdout);
    return EXIT_OK;
}
