/* schemas.h - every schema string brdfbench writes or reads, once. A writer opens its document
 * with its kind's string (jw_doc_begin); a reader (compare, gate --baseline, plot, report)
 * checks against the same string, and accepts the older versions listed here (*_V<k>) where it
 * still reads them. A change of a document's layout bumps its version here and nowhere else. */
#ifndef BRDF_SCHEMAS_H
#define BRDF_SCHEMAS_H

#define ACCURACY_SCHEMA "brdfbench.accuracy/3"   /* /3: its rows carry what report.md shows */
/* the previous versions, read by their layout (rdoc_read.c: upgrade_accuracy_v1); /2 carries
   rows without the report's figures */
#define ACCURACY_SCHEMA_V2 "brdfbench.accuracy/2"
#define ACCURACY_SCHEMA_V1 "brdfbench.accuracy/1"
#define CLAIMS_SCHEMA "brdfbench.claims/2"        /* /2: the file carries its rows (rdoc.h) */
#define CLAIMS_SCHEMA_V1 "brdfbench.claims/1"     /* before the rows: read by its layout */
#define COMPARE_SCHEMA "brdfbench.compare/1"
#define ENERGY_SCHEMA "brdfbench.energy/2"       /* /2: the file carries its rows (rdoc.h) */
#define ENERGY_SCHEMA_V1 "brdfbench.energy/1"    /* before the rows: read by its layout */
#define FIELD_SCHEMA "brdfbench.field/2"          /* /2: the file carries its rows */
#define FIELD_SCHEMA_V1 "brdfbench.field/1"
#define FIT_SCHEMA "brdfbench.fit/3"              /* /3: its rows carry what report.md shows */
#define FIT_SCHEMA_V2 "brdfbench.fit/2"           /* rows without the report's: read by its layout */
#define FIT_SCHEMA_V1 "brdfbench.fit/1"           /* before the rows: read by its layout */
#define FIT_FAMILY_SCHEMA "brdfbench.fit_family/2"   /* /2: the file carries its rows */
#define FIT_FAMILY_SCHEMA_V1 "brdfbench.fit_family/1"
#define FRONTIER_SCHEMA "brdfbench.frontier/3"    /* /3: its rows carry what its page shows */
#define FRONTIER_SCHEMA_V2 "brdfbench.frontier/2" /* rows of the accuracy figures alone: read by its layout */
#define FRONTIER_SCHEMA_V1 "brdfbench.frontier/1" /* before the rows: read by its layout */
#define GATES_SCHEMA "brdfbench.gates/1"        /* the gates file (input) */
#define GATE_RESULT_SCHEMA "brdfbench.gate/1"   /* gate's --json result (output) */
#define LIST_SCHEMA "brdfbench.list/1"
#define MEASURED_SCHEMA "brdfbench.measured/2"    /* /2: the file carries its rows */
#define MEASURED_SCHEMA_V1 "brdfbench.measured/1" /* before the rows: read by its layout */
#define PBCOST_SCHEMA "brdfbench.physical/2"      /* /2: the file carries its rows */
#define PBCOST_SCHEMA_V1 "brdfbench.physical/1"   /* before the rows: read by its layout */
#define PLOTS_SCHEMA "brdfbench.plots/1"
#define Q_SWEEP_SCHEMA "brdfbench.q_sweep/2"      /* /2: the file carries its rows */
#define Q_SWEEP_SCHEMA_V1 "brdfbench.q_sweep/1"   /* before the rows: read by its layout */
#define RENDER_SCHEMA "brdfbench.render/3"        /* /3: its rows carry what report.md shows */
#define RENDER_SCHEMA_V2 "brdfbench.render/2"     /* rows without the report's: read by its layout */
#define RENDER_SCHEMA_V1 "brdfbench.render/1"     /* before the rows: read by its layout */
#define HISTORY_SCHEMA "brdfbench.history/1"  /* `brdfbench history` (history.h) */
#define ROWS_SCHEMA "brdfbench.rows/1"        /* `brdfbench rows`: any result file as rows (rdoc.h) */
#define RUN_SCHEMA "brdfbench.run/1"          /* run.json of `all`: what report.md is made of */
#define THROUGHPUT_SCHEMA "brdfbench.throughput/5"   /* /5: its rows carry what the throughput page shows */
#define THROUGHPUT_SCHEMA_V4 "brdfbench.throughput/4"   /* rows without the page's: read by its layout (/3's) */
/* older throughput documents the readers still take, by their layout: /3 is /4 without the
   rows member; /2 has the same results without the runner's normalised rates; /1 (plot only)
   has the rates alone */
#define THROUGHPUT_SCHEMA_V3 "brdfbench.throughput/3"
#define THROUGHPUT_SCHEMA_V2 "brdfbench.throughput/2"
#define THROUGHPUT_SCHEMA_V1 "brdfbench.throughput/1"
/* a /4 file written before its rows carried the throughput page's record (no "reps" text in
   them) is read by /3's layout, which it holds too (rdoc_read.c) */

#endif
