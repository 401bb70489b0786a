/*
 * rd_sweep_slurm — the Slurm executor (rd_sweep_exec.h): a sweep as one job
 * array of deploy/slurm-sweep.sh tasks, as deploy/slurm-submit.sh submits
 * it, but without the reduce job (the service reads the chunks itself).
 *   submit   sbatch --parsable --job-name=ringdyn-sweep --array=0-(K-1)[%P]
 *                   --output=DIR/logs/%A_%a.log SCRIPT DIR/spec.json DIR K K
 *            with RINGDYN=<ringdyn> in its environment (sbatch exports it);
 *   poll     squeue -h -r -j JOB -o '%i %T' ("Invalid job id": gone);
 *   explain  scontrol show job -o JOB (each task's JobState and ExitCode)
 *            and the last line of the failed task's log;
 *   cancel   scancel JOB.
 * The tools are found in PATH and talk to the cluster SLURM_CONF names (the
 * server's environment).  Each runs under a time limit with bounded output
 * (rd_spawn.h).
 */
#ifndef RD_SWEEP_SLURM_H
#define RD_SWEEP_SLURM_H

#include "rd_sweep_exec.h"

typedef struct rd_sweep_slurm_config {
    const char *script;  /* deploy/slurm-sweep.sh, at the same path on every node */
    const char *ringdyn; /* the ringdyn binary, at the same path on every node */
    size_t max_running;  /* the array's %P; 0: no limit */
} rd_sweep_slurm_config;

typedef struct rd_sweep_slurm rd_sweep_slurm;

/* Copies the configuration; `exec` gets the table of operations (valid
 * until rd_sweep_slurm_free). */
int rd_sweep_slurm_create(const rd_sweep_slurm_config *cfg, rd_sweep_slurm **out,
                          rd_sweep_exec *exec, rd_error *err);

void rd_sweep_slurm_free(rd_sweep_slurm *slurm);

#endif
