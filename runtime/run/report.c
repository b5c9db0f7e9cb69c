/*
 * report.c - the run-time error reports: a value that is not finite (and the
 * rule that computed it), the rule of the last event, contacts that could
 * not be settled.
 */
#include <math.h>
#include <stdlib.h>

#include "run_int.h"

/* Index of the first non-finite target of section sec's (tgs), or -1. */
static long first_nonfinite(const csf_prog *p, int sec, const csf_target *tgs, const double *m)
{
	for (uint32_t i = 0; tgs && i < p->ntargets[sec]; i++) {
		const csf_target *tg = &tgs[i];
		for (uint32_t k = 0; k < tg->width; k++)
			if (!isfinite(m[tg->slot + k])) return (long)i;
	}
	return -1;
}

static void report_nonfinite_value(const csf_prog *p, int sec, const double *m, double t, const char *what, FILE *err);

/* Reports a non-finite value; with fixed steps, adds that the step is the likely cause. */
void csf_run_report_nonfinite(const csf_prog *p, int sec, const double *m, double t, const char *what, int fixed,
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
	csf_target *tgs = csf_targets_copy(p, sec); /* (out of memory: no rule named) */
	long i = first_nonfinite(p, sec, tgs, m);
	if (i < 0) {
		free(tgs);
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
	const csf_target *tg = &tgs[i];
	const csf_src *s = &p->srcs[tg->src];
	uint32_t k = 0;
	while (k + 1 < tg->width && isfinite(m[tg->slot + k])) k++;
	csf_fmt_double(vb, m[tg->slot + k]);
	fprintf(err, "%s:%lu: error: non-finite value at t=%s: %s%s%s (object %s) = %s, computed by: %s\n",
	        csf_str(p, p->files[s->file]), (unsigned long)s->line, tb, csf_str(p, tg->name),
	        tg->width == 3 ? "." : "", tg->width == 3 ? (const char *[]){ "x", "y", "z" }[k] : "",
	        csf_str(p, tg->object), vb, csf_str(p, s->text));
	free(tgs);
}

/* "file:line: " of statement src, the rule whose guard had the last event (a comparison, or a contact's). */
void csf_run_report_event_src(const csf_prog *p, uint32_t src, FILE *err)
{
	const csf_src *sr = &p->srcs[src];
	fprintf(err, "%s:%lu: ", csf_str(p, p->files[sr->file]), (unsigned long)sr->line);
}

/* The lightest and the heaviest mass point that can touch (objects *lo and *hi), and their masses. */
static void mass_range(const run *r, uint32_t *lo, uint32_t *hi, double *mlo, double *mhi)
{
	const csf_prog *p = r->p;
	*lo = *hi = 0, *mlo = INFINITY, *mhi = 0;
	for (uint32_t b = 0; b < p->ncbodies; b++) {
		if (p->cbodies[b].plane) continue;
		double mb = r->m[p->cbodies[b].s[CSF_CF_M]];
		if (mb < *mlo) *mlo = mb, *lo = p->cbodies[b].object;
		if (mb > *mhi) *mhi = mb, *hi = p->cbodies[b].object;
	}
}

/*
 * The impacts at r->unsettled_t did not come to an end or could not be
 * solved (csf_contact_settle): why, and what to do. The masses are blamed
 * only when they differ as the failure needs: by more than about 1e10 for
 * a solve, by more than 100 for impacts that do not end (a light body
 * between heavy ones collides about pi sqrt(M/m) times); otherwise the
 * message says what was measured instead.
 */
void csf_run_report_unsettled(const run *r, FILE *err)
{
	const csf_prog *p = r->p;
	char tb[32];
	csf_fmt_double(tb, r->unsettled_t);
	uint32_t lo, hi;
	double mlo, mhi;
	mass_range(r, &lo, &hi, &mlo, &mhi);
	if (r->unsettled != CSF_SETTLE_ENDLESS) {
		const char *what = r->unsettled == CSF_SETTLE_IMPULSES ? "impulses of an impact" : "contact forces";
		if (mhi > 1e9 * mlo) {
			fprintf(err,
			        "error: at t=%s, the %s among bodies in contact could not be solved: their masses differ by more "
			        "than about 1e10 ('%s' %g and '%s' %g, in the model's units); make them less different\n",
			        tb, what, csf_str(p, p->objects[lo]), mlo, csf_str(p, p->objects[hi]), mhi);
			return;
		}
		uint32_t k, np, oi, oj, big;
		csf_contacts_why(r->cs, &k, &np, &big);
		csf_contacts_objects(r->cs, k, &oi, &oj);
		char why[160];
		if (big)
			snprintf(why, sizeof why, "have more unknowns than the direct solve takes (%u), and the Gauss-Seidel "
			         "sweeps that take them did not converge", (unsigned)big);
		else if (r->unsettled == CSF_SETTLE_IMPULSES) /* impacts are frictionless: what was measured */
			snprintf(why, sizeof why, "take no set of pushing impulses that leaves none closing (the direct "
			         "solve found none, and 1000 Gauss-Seidel sweeps did not converge)");
		else
			snprintf(why, sizeof why, "contradict each other (no set of them holds: sticking and sliding, or "
			         "pressing and parting, decide each other there)");
		fprintf(err,
		        "error: at t=%s, the %s among bodies in contact could not be solved, though the masses differ "
		        "by a factor of %.3g at most: %u contacts there, among them '%s' with '%s', %s\n",
		        tb, what, mhi / mlo, np, csf_str(p, p->objects[oi]), csf_str(p, p->objects[oj]), why);
		return;
	}
	unsigned long long passes = (unsigned long long)csf_contact_passes(csf_contacts_count(r->cs));
	unsigned long pairs = (unsigned long)csf_contacts_count(r->cs);
	if (mhi > 100 * mlo) {
		fprintf(err,
		        "error: at t=%s, the impacts among touching bodies did not come to an end after %llu collisions "
		        "(%lu pairs near contact): a light body squeezed between heavy ones collides about "
		        "pi sqrt(M/m) times; make the masses less different\n",
		        tb, passes, pairs);
		return;
	}
	fprintf(err,
	        "error: at t=%s, the impacts among touching bodies did not come to an end after %llu collisions "
	        "(%lu pairs near contact), though the masses differ by a factor of %.3g at most: many bodies "
	        "touching at once (a pile), whose impacts are resolved pair by pair, went on colliding\n",
	        tb, passes, pairs, mhi / mlo);
}

/* Error: the method cannot run contacts; the methods that can. */
static void report_no_contacts(const char *method, FILE *err)
{
	fprintf(err, "error: method '%s' cannot run a model with contacts (mechanics/rules: their friction "
	        "depends on v); one of:", method);
	for (size_t k = 0; csf_method_name(k); k++)
		if (csf_method_contacts(csf_method_name(k))) fprintf(err, " %s", csf_method_name(k));
	fprintf(err, "\n");
}

/* Error: MAX_WORK steps in one output interval; why, when the guard measured it. */
static void report_too_much(const run *r, const stop *s, const char *tb, FILE *err)
{
	char ta[32], hb[32], why[160];
	csf_fmt_double(ta, s->t_row);
	csf_fmt_double(hb, r->last_h);
	/* stiff only when measured so: the step at the stability limit of the guard's last look */
	if (s->hs < INFINITY && r->last_h >= 0.8 * s->hs)
		snprintf(why, sizeof why,
		         "the problem is stiff: the explicit method's largest stable step is %.3g s here; try "
		         "--method msbdf or --method bsimp",
		         s->hs);
	else
		snprintf(why, sizeof why, "the steps are held by the error control, not by stability: the "
		                          "solution may be singular there");
	if (r->nevents) csf_run_report_event_src(r->p, r->last_src, err);
	fprintf(err,
	        "error: at t=%s, %d steps%s since the row at t=%s, the last of %s s: the run cannot get "
	        "on (%s)\n",
	        tb, MAX_WORK, s->events ? " and events" : "", ta, hb,
	        r->nevents ? "the last event was of the rule on this line: events that follow each other "
	                     "ever faster, or a force that switches within each step"
	                   : why);
}

/* Error: modes that switch back and forth at one instant (a contact's, or a conditional rule's). */
static void report_chatter(const run *r, const stop *s, const char *tb, FILE *err)
{
	const csf_prog *p = r->p;
	if (r->last >= (long)r->gcont) { /* a contact: the bodies are the user's, the rule the library's */
		uint32_t oi = r->last_oi, oj = r->last_oj;
		fprintf(err,
		        "error: at t=%s the contact of '%s' and '%s' switches between touching and parting, "
		        "or sticking and sliding, again and again (%s): no set of contacts among the "
		        "bodies touching there is consistent, and the run cannot go on\n",
		        tb, csf_str(p, p->objects[oi]), csf_str(p, p->objects[oj]), s->msg);
		return;
	}
	csf_run_report_event_src(p, r->last_src, err);
	fprintf(err,
	        "error: at t=%s the conditions switch back and forth without time advancing (%s): "
	        "the model has no solution past this point (a sliding mode; make the switching "
	        "condition depend on the mode, or smooth the force)\n",
	        tb, s->msg);
}

/*
 * Why the run ended: its message on err (after the progress line is
 * erased), and its exit status. fixed: --fixed, for a non-finite value's note.
 */
int csf_run_report_stop(run *r, const stop *s, int fixed, FILE *err)
{
	const csf_prog *p = r->p;
	char tb[32];
	csf_run_progress_off(r);
	csf_fmt_double(tb, s->t);
	switch (s->kind) {
	case STOP_END:
	case STOP_SIGNAL:
		return csf_signal ? 128 + csf_signal : 0;
	case STOP_HALTED:
		return 1;
	case STOP_NOMEM:
		fprintf(err, "error: out of memory\n");
		return 2;
	case STOP_SETUP:
		fprintf(err, "error: %s\n", s->msg);
		return 2;
	case STOP_NO_CONTACTS:
		report_no_contacts(s->method, err);
		return 2;
	case STOP_BAD_MASS: {
		const csf_cbody *b = &p->cbodies[s->which];
		fprintf(err, "error: the mass of %s is %g: a body in contact needs a positive mass\n",
		        csf_str(p, p->objects[b->object]), r->m[b->s[CSF_CF_M]]);
		return 1;
	}
	case STOP_UNSETTLED:
		csf_run_report_unsettled(r, err);
		return 1;
	case STOP_NONFINITE:
		csf_run_report_nonfinite(p, CSF_SEC_RHS, r->m, s->t, "a state derivative", fixed, err);
		return 1;
	case STOP_NONFINITE_ROW:
		csf_run_report_nonfinite(p, CSF_SEC_OUT, r->m, s->t, "a watched or state value", fixed, err);
		return 1;
	case STOP_ASSERT: {
		const csf_src *src = &p->srcs[p->asserts[s->which].src];
		fprintf(err, "%s:%lu: assertion failed at t=%s: %s (object %s)\n", csf_str(p, p->files[src->file]),
		        (unsigned long)src->line, tb, csf_str(p, src->text), csf_str(p, p->asserts[s->which].object));
		return 1;
	}
	case STOP_TOO_MUCH:
		report_too_much(r, s, tb, err);
		return 1;
	case STOP_CHATTER:
		report_chatter(r, s, tb, err);
		return 1;
	case STOP_WHEN_CYCLE: {
		const csf_src *a = &p->srcs[p->whens[r->cycle[0]].src], *b = &p->srcs[p->whens[r->cycle[r->ncycle > 1]].src];
		fprintf(err,
		        "%s:%lu: error: at t=%s the when blocks \"%s\" and \"%s\" (%s:%lu) set each other off without time "
		        "advancing (still firing after %d rounds at that instant): each one's assignments make the other's "
		        "condition true again\n",
		        csf_str(p, p->files[a->file]), (unsigned long)a->line, tb, csf_str(p, a->text), csf_str(p, b->text),
		        csf_str(p, p->files[b->file]), (unsigned long)b->line, WHEN_ROUNDS);
		return 1;
	}
	case STOP_CON_START:
	case STOP_CON_CONFLICT: {
		const csf_con *c = &p->cons[r->con_k];
		const csf_src *src = &p->srcs[c->src];
		char ob[32];
		csf_fmt_double(ob, r->con_off);
		if (r->con_impact) {
			uint32_t oi = r->last_oi, oj = r->last_oj;
			fprintf(err, "%s:%lu: error: at t=%s an impact", csf_str(p, p->files[src->file]), (unsigned long)src->line, tb);
			if (r->last >= (long)r->gcont)
				fprintf(err, " of '%s' and '%s'", csf_str(p, p->objects[oi]), csf_str(p, p->objects[oj]));
			fprintf(err, " changes the rate of rule C at line %lu (by %s of its terms): impacts are not yet solved "
			        "together with constraints, and only one across them is exact (%s)\n",
			        (unsigned long)src->line, ob, csf_str(p, src->text));
		} else if (s->kind == STOP_CON_START)
			fprintf(err, "%s:%lu: error: rule C at line %lu is off by %s%s%s at t = 0 (%s): the initial positions must "
			        "satisfy every constraint (to 1e-9 relative)\n", csf_str(p, p->files[src->file]),
			        (unsigned long)src->line, (unsigned long)src->line, ob, *csf_str(p, c->unit) ? " " : "",
			        csf_str(p, c->unit), csf_str(p, src->text));
		else if (r->con_off < 0)
			fprintf(err, "%s:%lu: error: at t=%s rule C at line %lu goes taut and slack again and again without time "
			        "advancing: no mode of the one-sided constraints there is consistent (%s)\n",
			        csf_str(p, p->files[src->file]), (unsigned long)src->line, tb, (unsigned long)src->line,
			        csf_str(p, src->text));
		else
			fprintf(err, "%s:%lu: error: at t=%s rule C at line %lu contradicts the constraints before it: where "
			        "they hold, its value or its rate is off by %s of the size of its terms (%s)\n", csf_str(p, p->files[src->file]),
			        (unsigned long)src->line, tb, (unsigned long)src->line, ob, csf_str(p, src->text));
		return 1;
	}
	case STOP_BUDGET:
		fprintf(err, "error: at t=%s, over the budget of %lu right-hand side evaluations\n", tb, r->max_rhs);
		return 1;
	case STOP_FAILED:
		fprintf(err,
		        "error: integration failed at t=%s: %s (the step size collapsed: the solution may be "
		        "singular there, or the problem stiff; try another --method or a smaller 'by')\n",
		        tb, s->msg);
		return 1;
	}
	return 1;
}
