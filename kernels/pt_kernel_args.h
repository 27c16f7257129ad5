/* What only the kernels need besides kernels/pt_path.h: 64-bit atomics for the statistics.
 * OpenCL C only. */
#ifndef PT_KERNEL_ARGS_H
#define PT_KERNEL_ARGS_H

#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

#include "pt_path.h"

/* stats[0]: rays traced, stats[1]: non-finite sample values. */
KD_INLINE void pt_add_stats(__global ulong* stats, ulong rays, uint nonfinite) {
  atom_add(&stats[0], rays);
  if (nonfinite) atom_add(&stats[1], (ulong)nonfinite);
}

#endif /* PT_KERNEL_ARGS_H */
