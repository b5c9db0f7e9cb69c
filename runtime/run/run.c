/*
 * run.c - csf_run, shared by csfvm and by every generated executable: it
 * owns the model's memory, integrates the state between output times
 * t_k = k*by, runs the OUT section at each t_k, checks assertions and
 * finiteness, and writes one CSV row per t_k as it goes. Rows are written
 * through stdio and flushed on every exit path; a write error is reported,
 * never ignored.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "run_int.h"

int csf_run(const csf_prog *p, csf_exec_fn exec, csf_opts *o, FILE *out, FILE *err)
{
	run r = { .p = p, .exec = exec };
	guard gd = { 0 };
	autom au = { 0 };
	watch_ctx wc = { &r, NULL }, wc_stiff = { &r, NULL };
	/* --method auto (the default, but for fixed steps and large scenes: dop853) is dop853 with
	   AUTO_STIFF beside it */
	const char *method = o->method && strcmp(o->method, "auto") != 0 ? o->method : NULL;
	int autom_on = !method && !o->fixed && p->ny <= AUTO_MAX_N;
	double *y = NULL;
	int fixed = 0;
	struct timespec t0, t1;
	clock_gettime(CLOCK_MONOTONIC, &t0);
	csf_ode *ode = NULL;
	int status = 0, werr = 0;
	char msg[256];
	r.err = err;
	r.start = r.drawn = t0;
	r.prog = o->progress == CSF_PROGRESS_ON || (o->progress == CSF_PROGRESS_AUTO && isatty(fileno(err)));

	r.m = malloc((p->nmem ? p->nmem : 1) * sizeof(double));
	y = malloc((p->ny ? p->ny : 1) * sizeof(double));
	r.ng = p->nevents; /* and two per candidate contact, none yet */
	/* events: comparisons, or contacts (whose candidates come and go) */
	int events = p->nevents || p->ncrules;
	double *work = NULL;
	if (events || autom_on) { /* (auto: jw, for a Jacobian by differences) */
		size_t n = p->ny ? p->ny : 1;
		work = malloc(12 * n * sizeof *work);
		if (work) {
			r.ya = work, r.fa = r.ya + n, r.fb = r.fa + n, r.ys = r.fb + n, r.fs = r.ys + n, r.ye = r.fs + n;
			r.jw = r.ye + n;
			r.yh = r.jw + 3 * n;
		}
	}
	if (events) room_for_guards(&r, r.ng ? r.ng : 1);
	if (p->ncrules) {
		r.cs = csf_contacts_new(p);
		((csf_prog *)p)->crun = r.cs; /* the CONTACT instruction's state (p is the caller's, not const data) */
	}
	if (!r.m || !y || ((events || autom_on) && !work) || r.nomem || (p->ncrules && !r.cs)) {
		fprintf(err, "error: out of memory\n");
		status = 2;
		goto done;
	}
	memcpy(r.m, p->mem0, p->nmem * sizeof(double));
	memcpy(y, p->mem0 + p->ystart, p->ny * sizeof(double));
	if (p->ncrules && !csf_method_contacts(method)) {
		fprintf(err, "error: method '%s' cannot run a model with contacts (mechanics/rules: their friction "
		        "depends on v); one of:", method);
		for (size_t k = 0; csf_method_name(k); k++)
			if (csf_method_contacts(csf_method_name(k))) fprintf(err, " %s", csf_method_name(k));
		fprintf(err, "\n");
		status = 2;
		goto done;
	}
	/* The last k with k*by <= till, allowing for till/by's rounding. */
	double kmax = floor(p->till / p->by);
	if ((kmax + 1) * p->by <= p->till * (1 + 1e-12)) kmax += 1;
	r.tend = kmax * p->by;
	if (p->ny) {
		/* a dense method steps as far as its error control allows (--hmax caps it), the others
		   to each output time; with events, steps of at most by, so that a guard that dips below
		   zero and back is not missed between the points each step looks at (events, below) */
		int unbounded = !o->fixed && csf_method_dense(method) && !events;
		double hmax = unbounded ? (r.tend > p->by ? r.tend : p->by) : p->by;
		if (o->hmax > 0 && o->hmax < hmax) hmax = o->hmax;
		ode = csf_ode_new(method, o->fixed, p->ny, p->by, hmax, o->tol, o->atol, p->yatol, p->yscale, p->vpair, rhs,
		                  p->jtan ? jac : NULL, &r, msg, sizeof msg);
		if (ode && autom_on) { /* the implicit method ends its steps on the rows: at most by */
			au.m[0] = ode;
			au.m[1] = csf_ode_new(AUTO_STIFF, 0, p->ny, p->by, o->hmax > 0 && o->hmax < p->by ? o->hmax : p->by,
			                      o->tol, o->atol, p->yatol, p->yscale, p->vpair, rhs, jac, &r, msg, sizeof msg);
			r.au = &au;
			if (!au.m[1]) {
				csf_ode_free(ode);
				ode = NULL;
			}
		}
		if (!ode) {
			fprintf(err, "error: %s\n", msg);
			status = 2;
			goto done;
		}
	}

	csf_out_begin();
	fputs("t", out);
	for (uint32_t i = 0; i < p->ncols; i++) fprintf(out, ",%s", csf_str(p, p->cols[i].name));
	putc('\n', out);
	csf_out_end();

	fixed = ode && (o->fixed || csf_ode_fixed_only(ode));
	double fixed_h = ode ? csf_ode_fixed_step(ode, p->by, o->step) : p->by;
	int verlet = ode && csf_ode_fixed_only(ode);
	if (ode) {
		gd.fixed = fixed;
		gd.check_step = fixed && csf_ode_explicit(ode);
		gd.auto_step = verlet && o->step <= 0;
		gd.user_step = o->step;
		gd.vfrac = sqrt((o->tol > 0 ? o->tol : csf_method_tol("verlet")) / 1e-4);
		gd.detect_stiff = !fixed && csf_ode_explicit(ode);
		gd.stats = o->stats;
	}
	if (gd.check_step || gd.auto_step || gd.detect_stiff || gd.stats) {
		size_t n = p->ny;
		gd.sp = csf_spectrum_new(n);
		gd.y = malloc(4 * n * sizeof *gd.y);
		if (!gd.sp || !gd.y) {
			fprintf(err, "error: out of memory\n");
			status = 2;
			goto done;
		}
		gd.f0 = gd.y + n, gd.yd = gd.f0 + n, gd.fd = gd.yd + n;
		gd.exact = p->jtan && !p->ncrules;
		gd.err = err;
		gd.span = r.tend;
		gd.h = p->by / ceil(p->by / fixed_h * (1 - 1e-12)); /* the step a row's interval is cut into */
		r.g = &gd;
	}
	if (ode) {
		wc.ode = ode;
		csf_ode_watch(ode, step_watch, &wc);
		if (r.au) {
			wc_stiff.ode = au.m[1];
			csf_ode_watch(au.m[1], step_watch, &wc_stiff);
		}
	}
	/* a train of bounces that would end within zeno is at rest; the integrator's accuracy (contact.c) */
	r.zeno = 1e-6 * p->by;
	r.tol = o->tol > 0 ? o->tol : csf_method_tol(method);
	if (events) {
		/* the masses first, as the rules make them: the impulses and forces of contacts divide
		   by them (a derivative that is not finite is reported by update_modes below) */
		long b = r.cs && !rhs(0, y, r.fs, &r) ? csf_contacts_bad_mass(p, r.m) : -1;
		r.fail = 0;
		if (b >= 0) {
			fprintf(err, "error: the mass of %s is %g: a body in contact needs a positive mass\n",
			        csf_str(p, p->objects[p->cbodies[b].object]), r.m[p->cbodies[b].s[CSF_CF_M]]);
			status = 1;
			goto done;
		}
		/* the modes at t = 0: each comparison's side, contacts at rest or colliding */
		if (update_modes(&r, 0, y) || (p->ny && guards_at(&r, 0, y, r.ga))) {
			if (r.unsettled) {
				report_unsettled(&r, err);
				status = 1;
				goto done;
			}
			if (r.nomem) {
				fprintf(err, "error: out of memory\n");
				status = 2;
				goto done;
			}
			report_nonfinite(p, CSF_SEC_RHS, r.m, 0, "a state derivative", o->fixed, err);
			status = 1;
			goto done;
		}
		memcpy(r.fa, r.fs, p->ny * sizeof *r.fa);
		stop_now(&r, 0); /* a 'stop when' condition true at the start: the row at t = 0 is the last */
	}
	r.dense = ode && !fixed && csf_ode_dense(ode);
	r.own = r.dense; /* (auto: dop853, dense) */
	r.ode = ode;
	if (r.own) { /* the integrator's own state, apart from the rows' */
		if (!(r.yi = malloc(p->ny * sizeof *r.yi))) {
			fprintf(err, "error: out of memory\n");
			status = 2;
			goto done;
		}
		memcpy(r.yi, y, p->ny * sizeof *y);
	}
	/* adaptive steps start at the scene's own size, not at by */
	if (ode && !fixed) {
		if (csf_ode_first_step(ode, 0, y)) {
			report_nonfinite(p, CSF_SEC_RHS, r.m, r.fail_t, "a state derivative", o->fixed, err);
			status = 1;
			goto done;
		}
		r.fail = 0; /* an Euler step of the estimate that failed was tried again shorter */
	}

	if (r.g && !gd.fixed) /* the first look when the run has spent LOOK_EVERY times what one may cost */
		gd.next = LOOK_EVERY * 2.0 * (p->ny < 12 ? p->ny + 1 : 12);
	if (r.g && gd.fixed) { /* the first look, before any step */
		if (guard_check(&r, ode, 0, y, 0)) {
			status = 1;
			goto done;
		}
		if (gd.auto_step) fixed_h = gd.h;
	}

	double t = 0;
	for (double k = 0; k <= kmax; k++) {
		double tk = k * p->by;
		if (csf_signal) break; /* after the last whole row */
		if (r.prog) progress(&r, t);
		if (ode && tk > t) {
			double trow = t; /* the last row's time */
			int st = r.own    ? advance_dense(&r, tk, y, msg, sizeof msg)
			         : events ? advance_events(&r, ode, &t, tk, fixed, fixed_h, y, msg, sizeof msg)
			         : fixed  ? csf_ode_advance_fixed(ode, &t, tk, fixed_h, y, msg, sizeof msg)
			                  : advance_plain(&r, ode, &t, tk, y, msg, sizeof msg);
			if (st == CSF_ODE_HALTED && csf_signal) break;
			if (st == TERMINAL) { /* a 'stop when' condition: the last row at its instant */
				r.stopped = 1;
				if (r.stop_t <= trow) break; /* at the last row's time: that row was the last */
				tk = r.stop_t;
				st = CSF_ODE_OK;
			}
			if (st != CSF_ODE_OK) progress_off(&r);
			if (st == CSF_ODE_HALTED) { /* the guard said why */
				status = 1;
				goto done;
			}
			if (st == CSF_ODE_STOPPED && r.unsettled) {
				report_unsettled(&r, err);
				status = 1;
				goto done;
			}
			if (st == CSF_ODE_STOPPED && r.nomem) {
				fprintf(err, "error: out of memory\n");
				status = 2;
				goto done;
			}
			if (st == CSF_ODE_STOPPED) {
				report_nonfinite(p, CSF_SEC_RHS, r.m, r.fail_t, "a state derivative", o->fixed, err);
				status = 1;
				goto done;
			}
			if (st == TOO_MUCH) {
				char tb[32], ta[32], hb[32], why[160];
				csf_fmt_double(tb, r.own ? r.ti : t);
				csf_fmt_double(ta, tk - p->by);
				csf_fmt_double(hb, r.last_h);
				/* stiff only when measured so: the step at the stability limit of the guard's last look */
				double hs = r.g && gd.checks && !fixed && !au.cur ? stable_step(&r, ode, &gd.last) : INFINITY;
				if (hs < INFINITY && r.last_h >= 0.8 * hs)
					snprintf(why, sizeof why,
					         "the problem is stiff: the explicit method's largest stable step is %.3g s here; try "
					         "--method msbdf or --method bsimp",
					         hs);
				else
					snprintf(why, sizeof why, "the steps are held by the error control, not by stability: the "
					                          "solution may be singular there");
				if (r.nevents) report_event_src(p, r.last_src, err);
				fprintf(err,
				        "error: at t=%s, %d steps%s since the row at t=%s, the last of %s s: the run cannot get "
				        "on (%s)\n",
				        tb, MAX_WORK, events ? " and events" : "", ta, hb,
				        r.nevents ? "the last event was of the rule on this line: events that follow each other "
				                    "ever faster, or a force that switches within each step"
				                  : why);
				status = 1;
				goto done;
			}
			if (st == CHATTER) {
				char tb[32];
				csf_fmt_double(tb, r.own ? r.ti : t);
				if (r.last >= (long)p->nevents) { /* a contact: the bodies are the user's, the rule the library's */
					uint32_t oi, oj;
					csf_contacts_objects(r.cs, (uint32_t)(r.last - (long)p->nevents) / 2, &oi, &oj);
					fprintf(err,
					        "error: at t=%s the contact of '%s' and '%s' switches between touching and parting, "
					        "or sticking and sliding, again and again (%s): no set of contacts among the "
					        "bodies touching there is consistent, and the run cannot go on\n",
					        tb, csf_str(p, p->objects[oi]), csf_str(p, p->objects[oj]), msg);
					status = 1;
					goto done;
				}
				report_event_src(p, r.last_src, err);
				fprintf(err,
				        "error: at t=%s the conditions switch back and forth without time advancing (%s): "
				        "the model has no solution past this point (a sliding mode; make the switching "
				        "condition depend on the mode, or smooth the force)\n",
				        tb, msg);
				status = 1;
				goto done;
			}
			if (st == CSF_ODE_FAILED) {
				char tb[32];
				csf_fmt_double(tb, r.own ? r.ti : t);
				fprintf(err,
				        "error: integration failed at t=%s: %s (the step size collapsed: the solution may be "
				        "singular there, or the problem stiff; try another --method or a smaller 'by')\n",
				        tb, msg);
				status = 1;
				goto done;
			}
		}
		t = tk;
		if (events && !ode) { /* no state: the conditions depend on t alone, and are looked at on the rows */
			free_modes(&r, tk, y);
			stop_now(&r, tk);
		}
		r.m[p->tslot] = tk;
		memcpy(r.m + p->ystart, y, p->ny * sizeof(double));
		int a = exec(p, CSF_SEC_OUT, r.m, r.m + p->ystart, r.m + p->dstart);
		if (a >= 0) {
			progress_off(&r);
			const csf_src *s = &p->srcs[p->asserts[a].src];
			char tb[32];
			csf_fmt_double(tb, tk);
			fprintf(err, "%s:%lu: assertion failed at t=%s: %s (object %s)\n", csf_str(p, p->files[s->file]),
			        (unsigned long)s->line, tb, csf_str(p, s->text), csf_str(p, p->asserts[a].object));
			status = 1;
			goto done;
		}
		int bad = 0;
		for (uint32_t i = 0; i < p->ny; i++) bad |= !isfinite(r.m[p->ystart + i]);
		for (uint32_t i = 0; i < p->ncols; i++) bad |= !isfinite(r.m[p->cols[i].slot]);
		if (bad) {
			progress_off(&r);
			csf_vm_exec(p, CSF_SEC_OUT, r.m, r.m + p->ystart, r.m + p->dstart); /* every value, for the report */
			report_nonfinite(p, CSF_SEC_OUT, r.m, tk, "a watched or state value", o->fixed, err);
			status = 1;
			goto done;
		}
		if (write_row(p, r.m, tk, out)) {
			werr = errno;
			break;
		}
		r.rows++;
		if (r.stopped) break;
	}
	if (csf_signal && !status) status = 128 + csf_signal;
done:
	progress_off(&r);
	clock_gettime(CLOCK_MONOTONIC, &t1);
	unsigned long steps = 0, rejected = 0;
	if (ode) csf_ode_stats(ode, &steps, &rejected);
	if (au.m[1]) {
		unsigned long s1, r1;
		csf_ode_stats(au.m[1], &s1, &r1);
		steps += s1, rejected += r1;
	}
	o->run_steps = steps;
	o->run_rhs = r.nrhs;
	o->run_seconds = seconds(t0, t1);
	if (o->stats) {
		char cand[96] = "";
		if (r.cs)
			snprintf(cand, sizeof cand, ", %.1f contact pairs watched (candidates) on average, at most %lu",
			         r.nchoices ? (double)r.ncand / (double)r.nchoices : 0.0, r.maxcand);
		char name[64];
		snprintf(name, sizeof name, "%s%s%s%s", r.au ? "auto (" : "", ode ? csf_ode_method(ode) : "none",
		         r.au && au.n ? " and " AUTO_STIFF : "", r.au ? ")" : "");
		fprintf(err,
		        "stats: method %s%s, %lu steps (%lu rejected), %lu right-hand side and %lu Jacobian evaluations, "
		        "%lu events%s, %.6f s\n",
		        name, fixed ? " (fixed steps)" : "", steps, rejected, r.nrhs, r.njac, r.nevents, cand,
		        o->run_seconds);
	}
	if (o->stats && au.n) { /* the switches, alternately to the implicit method and back */
		fprintf(err, "stats: auto: %lu switch%s:", au.n, au.n > 1 ? "es" : "");
		for (unsigned long i = 0; i < au.n && i < AUTO_SHOWN; i++)
			fprintf(err, "%s at t=%.6g to %s", i ? "," : "", au.at[i], i % 2 ? csf_ode_method(ode) : AUTO_STIFF);
		fprintf(err, "%s\n", au.n > AUTO_SHOWN ? ", ..." : "");
	}
	if (o->stats && r.g && gd.checks) {
		char rb[64] = "", hb[160] = "";
		if (gd.have_ratio && gd.ratio > 0) {
			char x[32];
			fmt_ratio(x, gd.ratio);
			snprintf(rb, sizeof rb, ", stiffness ratio %s%s", gd.ratio_exact ? "" : "about ", x);
		}
		if (fixed && gd.hrho > 0)
			snprintf(hb, sizeof hb, "; step %g s: h*rho %.3g against %s's limit %.3g there (largest stable step %.3g s)",
			         gd.h, gd.h * gd.rho_max, csf_ode_method(ode), gd.hlim_rho, gd.h / gd.hrho);
		else if (fixed)
			snprintf(hb, sizeof hb, "; step %g s: h*rho %.3g, %s not limited there", gd.h, gd.h * gd.rho_max,
			         csf_ode_method(ode));
		fprintf(err,
		        "stats: stability: rho %.3g 1/s (fastest time scale %.3g s, dominant eigenvalues %s)%s%s; %lu looks, "
		        "%lu Jacobian-vector products, %.6f s\n",
		        gd.rho_max, gd.rho_max > 0 ? 1 / gd.rho_max : INFINITY, eig_kind(&gd.at_max), rb, hb, gd.checks,
		        csf_spectrum_products(gd.sp), gd.seconds);
	}
	if (o->stats && r.stopped) {
		char tb[32];
		csf_fmt_double(tb, r.stop_t);
		const csf_src *s = &p->srcs[r.stop_src];
		fprintf(err, "stats: stopped at t=%s by %s:%lu: stop when %s\n", tb, csf_str(p, p->files[s->file]),
		        (unsigned long)s->line, csf_str(p, s->text));
	}
	if (o->stats && r.g && !gd.checks)
		fprintf(err,
		        "stats: stability: not looked at (the run ended after %lu evaluations, before its first look, due "
		        "after %.0f)\n",
		        r.nrhs, gd.next);
	csf_spectrum_free(gd.sp);
	free(gd.y);
	csf_ode_free(ode);
	csf_ode_free(au.m[1]);
	if (r.cs) ((csf_prog *)p)->crun = NULL;
	csf_contacts_free(r.cs);
	free(r.ga);
	free(r.gb);
	free(r.gs);
	free(r.gh);
	free(r.gt);
	free(r.gl);
	free(work);
	free(y);
	free(r.yi);
	free(r.m);
	return finish(out, err, status, werr);
}
