#define _GNU_SOURCE /* sched_getaffinity, CPU_COUNT */
#include "core/cpus.h"

#include <math.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

/* cgroup v2's cpu.max: "QUOTA PERIOD" in microseconds, or "max PERIOD". */
static int cgroup_quota_cpus(void)
{
    FILE *f = fopen("/sys/fs/cgroup/cpu.max", "r");
    if (!f)
        return 0;
    char quota[32] = "";
    long period = 0;
    int n = fscanf(f, "%31s %ld", quota, &period);
    fclose(f);
    if (n != 2 || period <= 0 || quota[0] == 'm')
        return 0;
    long q = atol(quota);
    if (q <= 0)
        return 0;
    return (int)ceil((double)q / (double)period);
}

int cpus_available(void)
{
    int n = 0;
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0)
        n = CPU_COUNT(&set);
    if (n <= 0)
        n = (int)sysconf(_SC_NPROCESSORS_ONLN);
    int quota = cgroup_quota_cpus();
    if (quota > 0 && quota < n)
        n = quota;
    return n > 0 ? n : 1;
}
