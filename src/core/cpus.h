/* How many CPUs this process may use: not the machine's count, but its
 * affinity mask (taskset, a Slurm job's cpuset) and its cgroup's CPU quota
 * (a container, --cpus-per-task), whichever is smaller. */
#ifndef CAUSTICA_CPUS_H
#define CAUSTICA_CPUS_H

/* At least 1. */
int cpus_available(void);

#endif
