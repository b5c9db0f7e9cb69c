/*
 * par.h - the threads of one run (--threads N): a pool of N - 1 POSIX
 * threads beside the caller, which share the loops of a shape whose
 * iterations are independent (runtime/prog/parloop.h) among them, in
 * chunks of contiguous iterations. The VM hands it such a loop at its LOOP
 * instruction (csf_pool_vm); a generated program, the loop's function
 * (csf_par_for, csf.h).
 */
#ifndef CSF_PAR_H
#define CSF_PAR_H

#include "csf_int.h"

/*
 * A loop pays for the threads from this many instructions. For tests, the
 * environment's CSF_THREADS_MIN_WORK overrides it (0: every loop whose
 * iterations are independent, however small), and CSF_THREADS_MAX_JOBS
 * bounds the loops a run gives to its threads (the later ones run serially).
 */
#define CSF_PAR_MIN_WORK 65536

/*
 * A pool of n threads in all (the caller one of them) for program p, with
 * the analysis of p's loops; NULL when n < 2 or nothing could be set up
 * (the run is then serial, with the same result). csf_pool_free(NULL) does
 * nothing.
 */
csf_pool *csf_pool_new(const csf_prog *p, int n);
void csf_pool_free(csf_pool *pool);

/*
 * The VM at the level-1 LOOP at pc of section sec: runs the whole loop on
 * the pool's threads and returns 1 when the loop is independent and worth
 * it, else 0 (the VM runs it itself). Each thread but the caller works in
 * a memory of its own, given the slots the body reads and giving back its
 * iterations' cells; the caller works in m.
 */
int csf_pool_vm(csf_pool *pool, const csf_exec_ctx *x, int sec, uint32_t pc, double *m);

/* The VM's iterations lo to hi - 1 of the level-1 loop [pc, end) of section sec on m (vm.c). */
void csf_vm_loop_range(const csf_prog *p, const csf_exec_ctx *x, int sec, uint32_t pc, uint32_t end, double *m,
                       uint32_t lo, uint32_t hi);

#endif
