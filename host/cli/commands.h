/* commands.h - the subcommands of brdfbench; each returns an exit code (exitcodes.h). */
#ifndef BRDF_COMMANDS_H
#define BRDF_COMMANDS_H

/* Every command, in the order `brdfbench help` lists them: X(NAME, ABOUT, EXAMPLE), its function
 * cmd_NAME (cmd_help is main.c's), ABOUT its line in the list and EXAMPLE one command line shown
 * by its --help and man page. The declarations below and main.c's table are made from it. */
#define BRDF_COMMANDS(X) \
    X(list, "the models (formulas, parameters, references) and the OpenCL devices", \
      "brdfbench list --json -") \
    X(accuracy, "dense-grid accuracy sweep of models on the OpenCL device", \
      "brdfbench accuracy --models fq2,cq2,lyon:k=2 --n-min 2 --n-max 1000 --out results/acc") \
    X(all, "the main job: every sweep, heatmap, plot and report.md in results/<date-time>/", \
      "brdfbench all --quick --models fq2,cq2,phong") \
    X(plot, "redraw every picture of a run folder from its JSON (no device)", \
      "brdfbench plot results/latest") \
    X(report, "rebuild report.md of a run folder from its files alone (no device)", \
      "brdfbench report results/latest --output -") \
    X(rows, "the figures of result files as rows: keys, metrics with unit and direction (md, csv, json)", \
      "brdfbench rows results/latest/throughput.json --format csv") \
    X(heatmap, "redraw the heatmaps of a run folder from its field JSON (no device)", \
      "brdfbench heatmap results/latest --label fq2") \
    X(gate, "accuracy gates for CI: checks figures of a gates file against bounds (JUnit, JSON)", \
      "brdfbench gate gates.json --junit gates.xml") \
    X(render, "full-image shading passes (spheres, teapot, bunny): error images, metrics, Mpixel/s", \
      "brdfbench render --scene spheres --models phong,fq2,cq2") \
    X(reproduce, "re-derive every claim of both papers: claims.json, claims.md and a table", \
      "brdfbench reproduce --out results/claims") \
    X(fit, "the cosine-quadratic family's accuracy limit and its best affine k(n) (quad:a=..,b=..)", \
      "brdfbench fit --n-min 2 --n-max 1000") \
    X(throughput, "evaluations/s of every model vs pow(), tuned C and the device peak; build-option variants", \
      "brdfbench throughput --models fq2,phong,phongpow") \
    X(version, "the program's version and git revision (also --version after any command)", \
      "brdfbench version") \
    X(compare, "runs side by side against a baseline: faster/slower/same, accuracy changes (no device)", \
      "brdfbench compare results/before results/after") \
    /* more commands below, one per line */ \
    X(frontier, "cost against accuracy of every lobe approximation: the Pareto front, plots, which to ship", \
      "brdfbench frontier --out results/frontier") \
    X(measured, "measured materials (MERL files): Blinn-Phong and Cook-Torrance fits, every cheap lobe against them", \
      "brdfbench measured merl/gold-metallic-paint.binary") \
    X(store, "the store of runs (SQLite): add run folders, list them, export them as rows documents", \
      "brdfbench store add results/latest --db results/history.sqlite") \
    X(history, "each row's series over stored runs or run folders: change points, trend picture, CI check", \
      "brdfbench history --db results/history.sqlite --fail-if-slower 10") \
    X(help, "a command's options (help COMMAND), its man page, or the shell completions", \
      "brdfbench help accuracy")

#define BRDF_COMMAND_DECLARE(name, help, example) int cmd_##name(int argc, char **argv);
BRDF_COMMANDS(BRDF_COMMAND_DECLARE)
#undef BRDF_COMMAND_DECLARE

#endif
