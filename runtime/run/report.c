/*
 * report.c - the run-time error reports: a value that is not finite (and the
 * rule that computed it), the rule of the last event, contacts that could
 * not be settled.
 */
#include <math.h>

#include "run_int.h"

/* Index of the first non-finite target computed by section sec, or -1. */
static long first_nonfinite(const csf_prog *p, int sec, const double *m)
{
	for (uint32_t i = 0; i < p->ntargets[sec]; i++) {
		const csf_target *tg = &p->targets[sec][i];
		for (uint32_t k = 0; k < tg->width; k++)
			if (!isfinite(m[tg->slot + k])) return (long)i;
	}
	return -1;
}

static void report_nonfinite_value(const csf_prog *p, int sec, const double *m, double t, const char *what, FILE *err);

/* Reports a non-finite value; with fixed steps, adds that the step is the likely cause. */
void report_nonfinite(const csf_prog *p, int sec, const double *m, double t, const char *what, int fixed,
                             FILE *err)
{
	report_nonfinite_value(p, sec, m, t, what, err);
	if (fixed)
		fprintf(err, "note: with --fixed, the step is probably too large for the method to be stable: "
		             "try a smaller --step, or leave out --fixed\n");
}

static void report_nonfinite_value(const csf_prog *p, int sec, const double *m, double t, const char *what, FILE *err)
{
	char tb[32], vb[32];
	csf_fmt_double(tb, t);
	long i = first_nonfinite(p, sec, m);
	if (i < 0) {
		/* no rule computed it: an initial value or a constant; name the column */
		for (uint32_t c = 0; c < p->ncols; c++)
			if (!isfinite(m[p->cols[c].slot])) {
				csf_fmt_double(vb, m[p->cols[c].slot]);
				fprintf(err, "error: non-finite value at t=%s: %s = %s, set by no rule (an initial value or a constant)\n",
				        tb, csf_str(p, p->cols[c].name), vb);
				return;
			}
		fprintf(err, "error: non-finite value at t=%s: %s\n", tb, what);
		return;
	}
	const csf_target *tg = &p->targets[sec][i];
	const csf_src *s = &p->srcs[tg->src];
	uint32_t k = 0;
	while (k + 1 < tg->width && isfinite(m[tg->slot + k])) k++;
	csf_fmt_double(vb, m[tg->slot + k]);
	fprintf(err, "%s:%lu: error: non-finite value at t=%s: %s%s%s (object %s) = %s, computed by: %s\n",
	        csf_str(p, p->files[s->file]), (unsigned long)s->line, tb, csf_str(p, tg->name),
	        tg->width == 3 ? "." : "", tg->width == 3 ? (const char *[]){ "x", "y", "z" }[k] : "",
	        csf_str(p, tg->object), vb, csf_str(p, s->text));
}

/* "file:line: " of statement src, the rule whose guard had the last event (a comparison, or a contact's). */
void report_event_src(const csf_prog *p, uint32_t src, FILE *err)
{
	const csf_src *sr = &p->srcs[src];
	fprintf(err, "%s:%lu: ", csf_str(p, p->files[sr->file]), (unsigned long)sr->line);
}

/* The impacts at r->unsettled_t did not come to an end or could not be solved (csf_contact_settle): why, and what to do. */
void report_unsettled(const run *r, FILE *err)
{
	char tb[32];
	csf_fmt_double(tb, r->unsettled_t);
	if (r->unsettled != CSF_SETTLE_ENDLESS) {
		/* the lightest and the heaviest mass point that can touch: blame the masses only if they differ */
		const csf_prog *p = r->p;
		uint32_t lo = 0, hi = 0; /* objects */
		double mlo = INFINITY, mhi = 0;
		for (uint32_t b = 0; b < p->ncbodies; b++) {
			if (p->cbodies[b].plane) continue;
			double mb = r->m[p->cbodies[b].s[CSF_CF_M]];
			if (mb < mlo) mlo = mb, lo = p->cbodies[b].object;
			if (mb > mhi) mhi = mb, hi = p->cbodies[b].object;
		}
		const char *what = r->unsettled == CSF_SETTLE_IMPULSES ? "impulses of an impact" : "contact forces";
		if (mhi > 1e9 * mlo) {
			fprintf(err,
			        "error: at t=%s, the %s among bodies in contact could not be solved: their masses differ by more "
			        "than about 1e10 ('%s' %g and '%s' %g, in the model's units); make them less different\n",
			        tb, what, csf_str(p, p->objects[lo]), mlo, csf_str(p, p->objects[hi]), mhi);
			return;
		}
		fprintf(err,
		        "error: at t=%s, the %s among bodies in contact could not be solved: the equations of the contacts "
		        "there are singular (more contacts than the bodies' motions can tell apart), though the masses "
		        "differ by a factor of %.3g at most\n",
		        tb, what, mhi / mlo);
		return;
	}
	fprintf(err,
	        "error: at t=%s, the impacts among touching bodies did not come to an end after %llu collisions "
	        "(%lu pairs near contact): a light body squeezed between heavy ones collides about "
	        "pi sqrt(M/m) times; make the masses less different\n",
	        tb, (unsigned long long)csf_contact_passes(csf_contacts_count(r->cs)),
	        (unsigned long)csf_contacts_count(r->cs));
}
