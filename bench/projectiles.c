/*
 * projectiles.c - one evaluation of an array of projectiles: the VM beside hand-written C.
 *
 *   projectiles MODEL.csfb REPS
 *
 * MODEL is tests/arrays/gen_projectiles.sh's array of N projectiles with linear drag, compiled
 * with csfc --keep-all (every member integrated). It times REPS evaluations of the right-hand
 * side section by the VM (csf_vm_exec on the loaded memory image, as csfvm evaluates) and REPS
 * of the loop a physicist would write over arrays of the same values, and prints one line:
 *
 *   N vm_seconds hand_seconds identical
 *
 * the medians of one evaluation, and whether the two gave the same derivatives, bit for bit
 * (1 or 0). The hand-written loop does the VM's operations in its order, per member i
 *
 *   W = g * m_i; D = v_i * (-k_i); a = (W + D) / m_i; v' = a; pos' = v_i
 *
 * reading m, k and v from arrays of their own (its values from the image) and writing the
 * derivatives into arrays of its own. Compile with -O2 -ffp-contract=off, as the VM is.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "block.h"
#include "csf_int.h"
#include "timing.h"

static void die(const char *msg)
{
	fprintf(stderr, "projectiles: %s\n", msg);
	exit(2);
}

/* The slot of object o's property name; -1 if it has none. */
static long slot_of(const csf_prog *p, uint32_t o, const char *name)
{
	for (uint32_t i = 0; i < p->nprops; i++)
		if (p->props[i].object == o && !strcmp(csf_str(p, p->props[i].name), name)) return p->props[i].slot;
	return -1;
}

/* The slot of global name. */
static long global_slot(const csf_prog *p, const char *name)
{
	for (uint32_t i = 0; i < p->nglobals; i++)
		if (!strcmp(csf_str(p, p->globals[i].name), name)) return p->globals[i].slot;
	return -1;
}

int main(int argc, char **argv)
{
	size_t len;
	unsigned char *b = argc == 3 ? csf_read_file(argv[1], &len) : NULL;
	csf_prog p;
	char err[256];
	int reps = argc == 3 ? atoi(argv[2]) : 0;
	if (!b || reps < 1 || csf_decode(b, len, &p, err, sizeof err)) die("usage: projectiles MODEL.csfb REPS (a valid program)");
	free(b);
	size_t n = p.nobjects;
	long sm = slot_of(&p, 0, "m"), sk = slot_of(&p, 0, "k"), sv = slot_of(&p, 0, "v"), sp = slot_of(&p, 0, "pos"),
	     sg = global_slot(&p, "g");
	/* the members' properties are arrays: member i's at slot + i * width */
	if (n < 2 || sm < 0 || sk < 0 || sv < 0 || sp < 0 || sg < 0 || slot_of(&p, (uint32_t)n - 1, "m") != sm + (long)n - 1 ||
	    slot_of(&p, (uint32_t)n - 1, "k") != sk + (long)n - 1 || slot_of(&p, (uint32_t)n - 1, "v") != sv + 3 * ((long)n - 1) ||
	    slot_of(&p, (uint32_t)n - 1, "pos") != sp + 3 * ((long)n - 1) || (uint32_t)sv < p.ystart || (uint32_t)sp < p.ystart)
		die("not an array of projectiles compiled with --keep-all");
	double *mem = malloc(p.nmem * sizeof *mem), *m = malloc(n * sizeof *m), *k = malloc(n * sizeof *k);
	double *v = malloc(3 * n * sizeof *v), *dv = malloc(3 * n * sizeof *dv), *dp = malloc(3 * n * sizeof *dp);
	double *tv = malloc((size_t)reps * sizeof *tv), *th = malloc((size_t)reps * sizeof *th);
	if (!mem || !m || !k || !v || !dv || !dp || !tv || !th) die("out of memory");
	memcpy(mem, p.mem0, p.nmem * sizeof *mem);
	memcpy(m, mem + sm, n * sizeof *m);
	memcpy(k, mem + sk, n * sizeof *k);
	memcpy(v, mem + sv, 3 * n * sizeof *v);
	const double g[3] = { mem[sg], mem[sg + 1], mem[sg + 2] };
	csf_exec_ctx x = { 0 };
	x.blocks = csf_blocks_new(&p); /* as csfvm runs the loops: a block of iterations at a time (NULL: one by one) */
	for (int r = 0; r < reps; r++) {
		double t0 = now();
		csf_vm_exec(&p, &x, CSF_SEC_RHS, mem, mem + p.ystart, mem + p.dstart);
		double t1 = now();
		for (size_t i = 0; i < n; i++) {
			double nk = -k[i];
			for (int c = 0; c < 3; c++) {
				dv[3 * i + c] = (g[c] * m[i] + v[3 * i + c] * nk) / m[i];
				dp[3 * i + c] = v[3 * i + c];
			}
		}
		double t2 = now();
		tv[r] = t1 - t0;
		th[r] = t2 - t1;
	}
	/* the VM's derivative of slot s is at dstart + (s - ystart) */
	const double *vd = mem + p.dstart + (sv - p.ystart), *pd = mem + p.dstart + (sp - p.ystart);
	int same = !memcmp(vd, dv, 3 * n * sizeof *dv) && !memcmp(pd, dp, 3 * n * sizeof *dp);
	printf("%zu %.6e %.6e %d\n", n, median(tv, reps), median(th, reps), same);
	free(mem), free(m), free(k), free(v), free(dv), free(dp), free(tv), free(th);
	csf_blocks_free(x.blocks);
	csf_prog_free(&p);
	return 0;
}
