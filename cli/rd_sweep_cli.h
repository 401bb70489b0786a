/* rd_sweep_cli — the `ringdyn sweep` subcommands (rd_sweep_cli.c). */
#ifndef RD_SWEEP_CLI_H
#define RD_SWEEP_CLI_H

/* argv[0] is the subcommand (count, scene, run, reduce); returns the exit
 * status (0 ok, 2 invalid input, 1 the run could not finish). */
int rd_sweep_cli_main(int argc, char **argv);

#endif
