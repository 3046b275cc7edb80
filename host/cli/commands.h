/* commands.h - the subcommands of brdfbench; each returns an exit code (exitcodes.h). */
#ifndef BRDF_COMMANDS_H
#define BRDF_COMMANDS_H

int cmd_list(int argc, char **argv);
int cmd_accuracy(int argc, char **argv);
int cmd_all(int argc, char **argv);
int cmd_plot(int argc, char **argv);
int cmd_report(int argc, char **argv);
int cmd_rows(int argc, char **argv);
int cmd_store(int argc, char **argv);
int cmd_history(int argc, char **argv);
int cmd_heatmap(int argc, char **argv);
int cmd_gate(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_fit(int argc, char **argv);
int cmd_reproduce(int argc, char **argv);
int cmd_throughput(int argc, char **argv);
int cmd_version(int argc, char **argv);
int cmd_frontier(int argc, char **argv);
int cmd_compare(int argc, char **argv);
/* more commands below, one per line */
int cmd_measured(int argc, char **argv);

#endif
