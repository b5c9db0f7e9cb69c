/*
 * eval.c - the model as the integrators see it: the right-hand side (the RHS
 * section, with a check that every derivative is finite) and the Jacobian
 * (the JAC section's tangents, or central differences).
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run_int.h"
#include "constraint.h"
#include "insn.h"

int csf_run_rhs(double t, const double *y, double *dydt, void *ctx)
{
	run *r = ctx;
	const csf_prog *p = r->p;
	double *m = r->m;
	m[p->tslot] = t;
	r->exec(p, &r->x, CSF_SEC_RHS, m, y, dydt);
	r->nrhs++;
	if (r->cons && csf_cons_failed(r->cons, &r->con_k, &r->con_off)) {
		r->fail = 1;
		r->fail_t = t;
		r->conflict = 1;
		return 1;
	}
	if (!csf_all_finite(dydt, p->ny)) {
		r->fail = 1;
		r->fail_t = t;
		/* every value the section computed, in m for report_nonfinite: the VM's, bit for bit the same */
		csf_vm_exec(p, &r->x, CSF_SEC_RHS, m, y, m + p->dstart);
		return 1;
	}
	return 0;
}

/*
 * The right-hand side as the integrators call it. Contact forces that
 * cannot be solved at a trial state fail the evaluation, and the step is
 * tried again shorter (as one whose state overflowed): a stage of a step
 * that reaches past an event sees pairs held in contact that have parted
 * there (in a column of nine balls bouncing in a narrow box, stages at
 * gaps of 6e-4 m and parting speeds of 0.08 m/s; the run stopped on
 * "contact forces ... could not be solved" though the forces of every
 * state it reached were solved). Only where no step is short enough do
 * they stop the run (advance_stop in run.c, from r->trial_unsolved).
 * Forces that could not be solved before the evaluation (at an event's
 * settling) are left as they were, for the driver to stop on.
 */
int csf_run_rhs_trial(double t, const double *y, double *dydt, void *ctx)
{
	run *r = ctx;
	int before = r->cs && csf_contacts_unsolved(r->cs);
	int st = csf_run_rhs(t, y, dydt, ctx);
	if (st || before || !r->cs || !csf_contacts_unsolved(r->cs)) return st;
	csf_contacts_set_unsolved(r->cs, 0);
	if (!r->trial_unsolved) r->trial_unsolved = 1, r->trial_unsolved_t = t;
	return 1;
}

/*
 * With contacts, the Jacobian by central differences of the RHS: the
 * contact routine's forces have no tangent code, and they are smooth while
 * the modes are frozen, as they are between events. Also for --method
 * auto's implicit method in a program without a JAC section. The step for component
 * j is cbrt(eps) times its size (at least its unit), which balances the
 * truncation and rounding errors of the difference.
 */
static int jac_differences(run *r, double t, const double *y, double *dfdy, double *dfdt)
{
	const csf_prog *p = r->p;
	uint32_t n = p->ny;
	double *yd = r->jw, *fp = yd + n, *fm = fp + n, c = cbrt(DBL_EPSILON);
	memcpy(yd, y, n * sizeof *y);
	for (uint32_t j = 0; j <= n; j++) {
		double x = j < n ? y[j] : t;
		double h = c * csf_max(fabs(x), j < n ? p->yscale[j] : p->by);
		double xp = x + h, xm = x - h; /* divided by the steps actually taken */
		if (j < n) yd[j] = xp;
		if (csf_run_rhs(j < n ? t : xp, yd, fp, r)) return 1;
		if (j < n) yd[j] = xm;
		if (csf_run_rhs(j < n ? t : xm, yd, fm, r)) return 1;
		if (j < n) yd[j] = y[j];
		for (uint32_t i = 0; i < n; i++) {
			double d = (fp[i] - fm[i]) / (xp - xm);
			if (j < n) dfdy[(size_t)i * n + j] = d;
			else dfdt[i] = d;
		}
	}
	return 0;
}

/*
 * The exact Jacobian: JAC run once per state component with that
 * component's tangent set to 1 (a column), then once with t's (dfdt).
 */
int csf_run_jac(double t, const double *y, double *dfdy, double *dfdt, void *ctx)
{
	run *r = ctx;
	const csf_prog *p = r->p;
	double *m = r->m, *tan = r->m + p->jtan;
	uint32_t n = p->ny;
	r->njac++;
	if (p->ncrules || p->ncons || !p->jtan) return jac_differences(r, t, y, dfdy, dfdt); /* (no JAC: --method auto) */
	m[p->tslot] = t;
	memcpy(m + p->ystart, y, n * sizeof *y);
	for (uint32_t j = 0; j <= n; j++) {
		memset(tan + p->ystart, 0, n * sizeof *tan);
		tan[p->tslot] = j == n ? 1.0 : 0.0;
		if (j < n) tan[p->ystart + j] = 1.0;
		r->exec(p, &r->x, CSF_SEC_JAC, m, m + p->ystart, m + p->dstart);
		for (uint32_t i = 0; i < n; i++) {
			double d = tan[p->dstart + i];
			if (j < n) dfdy[(size_t)i * n + j] = d;
			else dfdt[i] = d;
		}
	}
	return 0;
}

uint32_t *csf_run_row_state(const csf_prog *p, size_t *n)
{
	const uint32_t *code = p->code[CSF_SEC_OUT];
	uint64_t y0 = p->ystart, y1 = (uint64_t)p->ystart + p->ny;
	unsigned char *need = p->ncrules || p->ncons ? NULL : calloc(p->ny ? p->ny : 1, 1);
	uint32_t cnt[CSF_LOOP_MAX + 1] = { 0 }; /* the counts of the loops open, by level */
	if (!need) return NULL;
	for (uint32_t pc = 0; pc < p->ncode[CSF_SEC_OUT]; pc += csf_insn_len(code[pc])) {
		const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
		if (code[pc] == CSF_OP_LOOP) cnt[code[pc + 1]] = code[pc + 2];
		for (int k = 0; k < oi->nops; k++) {
			if (!csf_kind_slot(oi->kind[k])) continue;
			uint32_t w = code[pc + 1 + k], r = csf_reg(w);
			uint64_t lo = w & CSF_SLOT_MASK, hi = csf_operand_end(w, csf_kind_width(oi->kind[k]), r ? cnt[csf_reg_level(r)] : 1);
			for (uint64_t s = lo > y0 ? lo : y0; s < hi && s < y1; s++) need[s - y0] = 1;
		}
	}
	for (uint32_t i = 0; i < p->ncols; i++)
		if (p->cols[i].slot >= y0 && p->cols[i].slot < y1) need[p->cols[i].slot - y0] = 1;
	size_t k = 0;
	for (uint32_t i = 0; i < p->ny; i++) k += need[i];
	uint32_t *rows = k < p->ny ? malloc((k ? k : 1) * sizeof *rows) : NULL;
	if (rows) {
		*n = 0;
		for (uint32_t i = 0; i < p->ny; i++)
			if (need[i]) rows[(*n)++] = i;
	}
	free(need);
	return rows;
}
