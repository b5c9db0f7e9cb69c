/*
 * sweep_int.h - what the files of csfvm --sweep share (sweep.c): the sweep's
 * state, its parameters, axes and summaries.
 */
#ifndef SWEEP_INT_H
#define SWEEP_INT_H

#include <stdio.h>

#include "csf_int.h"

enum { SUM_FINAL, SUM_MAX, SUM_MIN, SUM_MEAN, SUM_RMS };

typedef struct sparam { char *name, *head; csf_pref ref; } sparam;
/* An axis: params [first, first + n), count entries of n values each (vals[entry * n + k]). */
typedef struct axis { int first, n; size_t count; double *vals; } axis;
/* A summary: func of column col over the rows with from <= t <= to. */
typedef struct sumcol { int func; uint32_t col; double from, to; char *head; } sumcol;

struct csf_sweep {
	const csf_prog *p;
	csf_exec_fn exec;
	csf_opts o;
	const char *prog;
	int npar, nax, nsum;
	sparam *par;
	axis *ax;
	sumcol *sum;
	size_t nvar;
	const char *out_dir;
	int binary;       /* --sweep-binary: a variant's text is the header line, then its rows as doubles */
	int h5rows;       /* -o RUN.h5: a variant's text is its rows as doubles, alone */
	csf_h5 *h5;       /* where they go (NULL on csfvm-mpi's quiet ranks) */
	int h5err;        /* a write to it failed (reported) */
	size_t taken;     /* the variants taken, in order */
	FILE *index;
	FILE *out, *err;
	int status, header_done;
	csf_overlay init; /* o->init (-D's values), then the variant's: the run's initial values over p's */
	size_t ninit;     /* how many of them are -D's */
	/* --checkpoint, --resume: a checkpoint after a variant written, every ck_every seconds (sweep.c) */
	const char *ck;
	double ck_every;
	struct timespec ck_last;
	int ck_warned;
	char ck_opts[CSF_KEEP_OPTS];
	size_t first;     /* the first variant to run (--resume: the first not written) */
};

/* sweep.c: after variant S->taken - 1 written, a checkpoint when one is due (or a signal ends the sweep) */
void csf_sweep_checkpoint(csf_sweep *S);

/* message: u64 index, u32 status, u64 text length, u64 diagnostics length, the text, the diagnostics */
enum { MSG_HEAD = 28 };

static inline void put64(unsigned char *b, uint64_t v)
{
	for (int k = 0; k < 8; k++) b[k] = (unsigned char)(v >> (8 * k));
}
static inline uint64_t get64(const unsigned char *b)
{
	uint64_t v = 0;
	for (int k = 0; k < 8; k++) v |= (uint64_t)b[k] << (8 * k);
	return v;
}

/* sweep.c: an error about the sweep's options, on S->err; -1 */
int csf_sweep_err(csf_sweep *S, const char *fmt, ...);
/* sweep.c: the name of column c of p's output (0: t), and the length of its header with the unit */
const char *csf_sweep_col_head(const csf_prog *p, uint32_t c);
size_t csf_sweep_head_len(const csf_prog *p, uint32_t k);
/* sweep_variant.c: the variants after those taken (an interrupted sweep's) into S->h5, never run; 0 or -1 */
int csf_sweep_h5_rest(csf_sweep *S);
/* sweep_fork.c: every variant here, in order; or in nw worker processes (-j) */
int csf_sweep_run_serial(csf_sweep *S);
int csf_sweep_run_forked(csf_sweep *S, int nw);

#endif
