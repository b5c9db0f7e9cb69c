/*
 * record.c - the run record (--record FILE.json, and the root attributes
 * of -o FILE.h5): what ran, how, where, when, with what result. The fields
 * are made once (csf_record_make), then written as a JSON object here and
 * as HDF5 attributes of the same names by h5.c (csf_h5_record).
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "csf_int.h"
#include "ode.h"

char *csf_command_line(int argc, char **argv)
{
	size_t n = 1;
	for (int i = 0; i < argc; i++) n += 4 * strlen(argv[i]) + 3;
	char *s = malloc(n), *q = s;
	for (int i = 0; s && i < argc; i++) {
		const char *a = argv[i];
		int plain = *a && strspn(a, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_./=:+,-@%") == strlen(a);
		if (i) *q++ = ' ';
		if (!plain) *q++ = '\'';
		for (; *a; a++)
			if (*a == '\'' && !plain) memcpy(q, "'\\''", 4), q += 4;
			else *q++ = *a;
		if (!plain) *q++ = '\'';
	}
	if (s) *q = '\0';
	return s;
}

/* The unit system of base (csfc --units): mks, cgs or fps, else "other". */
static const char *unit_system(const double *base)
{
	if (base[0] == 1 && base[1] == 1) return "mks";
	if (base[0] == 0.01 && base[1] == 0.001) return "cgs";
	if (base[0] == 0.3048) return "fps";
	return "other";
}

/* ISO 8601 in UTC, to the second. */
static void iso_time(char buf[32], time_t t)
{
	struct tm tm;
	if (!gmtime_r(&t, &tm) || !strftime(buf, 32, "%Y-%m-%dT%H:%M:%SZ", &tm)) snprintf(buf, 32, "unknown");
}

static void add_str(csf_record *rec, const char *name, const char *s)
{
	if (rec->n < CSF_RECORD_MAX) rec->f[rec->n++] = (csf_rfield){ .name = name, .kind = CSF_RF_STR, .s = s ? s : "" };
}

static void add_num(csf_record *rec, const char *name, double x)
{
	if (rec->n < CSF_RECORD_MAX) rec->f[rec->n++] = (csf_rfield){ .name = name, .kind = CSF_RF_NUM, .x = x };
}

void csf_record_make(csf_record *rec, const csf_prog *p, const csf_opts *o, const char *source, int argc, char **argv,
                     time_t start, time_t end, int status)
{
	memset(rec, 0, sizeof *rec);
	rec->cmd = csf_command_line(argc, argv);
	snprintf(rec->hash, sizeof rec->hash, "%016llx", o->hash);
	iso_time(rec->start, start);
	iso_time(rec->end, end);
	if (gethostname(rec->host, sizeof rec->host)) snprintf(rec->host, sizeof rec->host, "unknown");
	rec->host[sizeof rec->host - 1] = '\0';
	const char *m = o->method ? o->method : "auto";
	add_str(rec, "csf_version", CSF_VERSION_STRING);
	add_str(rec, "bytecode_hash", rec->hash);
	add_str(rec, "source", source);
	add_str(rec, "units", unit_system(p->ubase));
	add_str(rec, "method", m);
	add_num(rec, "tolerance", o->tol > 0 ? o->tol : csf_method_tol(strcmp(m, "auto") ? m : NULL));
	add_num(rec, "atol", o->atol > 0 ? o->atol : 0);
	add_num(rec, "fixed", o->fixed);
	add_num(rec, "step", o->step > 0 ? o->step : 0);
	add_num(rec, "hmax", o->hmax > 0 ? o->hmax : 0);
	add_num(rec, "every", o->every > 1 ? (double)o->every : 1);
	add_num(rec, "till", p->till);
	add_num(rec, "by", p->by);
	if (rec->n < CSF_RECORD_MAX)
		rec->f[rec->n++] = (csf_rfield){ .name = "defines", .kind = CSF_RF_STRS, .v = o->defs, .nv = o->ndefs };
	add_str(rec, "command_line", rec->cmd);
	add_str(rec, "host", rec->host);
	add_str(rec, "start", rec->start);
	add_str(rec, "end", rec->end);
	add_num(rec, "steps", (double)o->run_steps);
	add_num(rec, "rejected_steps", (double)o->run_rejected);
	add_num(rec, "rhs_evaluations", (double)o->run_rhs);
	add_num(rec, "jacobian_evaluations", (double)o->run_jac);
	add_num(rec, "events", (double)o->run_events);
	add_num(rec, "rows", (double)o->run_rows);
	add_num(rec, "seconds", o->run_seconds);
	add_str(rec, "checkpoint", o->checkpoint ? o->checkpoint : o->resume);
	add_str(rec, "resumed_from", o->resume);
	if (o->estimate) {
		add_num(rec, "error_estimate", o->err_estimate);
		add_str(rec, "error_estimate_column", o->err_column);
		add_num(rec, "error_estimate_t", o->err_t);
		add_num(rec, "error_estimate_tolerance", o->err_tol);
	}
	add_num(rec, "exit_status", status);
}

void csf_record_free(csf_record *rec)
{
	free(rec->cmd);
	rec->cmd = NULL;
}

/* s as a JSON string. */
static void json_str(FILE *f, const char *s)
{
	fputc('"', f);
	for (; *s; s++) {
		unsigned char c = (unsigned char)*s;
		if (c == '"' || c == '\\') fprintf(f, "\\%c", c);
		else if (c == '\n') fputs("\\n", f);
		else if (c == '\t') fputs("\\t", f);
		else if (c < 0x20) fprintf(f, "\\u%04x", c);
		else fputc(c, f);
	}
	fputc('"', f);
}

int csf_record_json(const csf_record *rec, const char *path, char *err, size_t errlen)
{
	FILE *f = strcmp(path, "-") ? fopen(path, "w") : stderr;
	if (!f) {
		snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
		return -1;
	}
	fputs("{\n", f);
	for (int i = 0; i < rec->n; i++) {
		const csf_rfield *x = &rec->f[i];
		fprintf(f, "  ");
		json_str(f, x->name);
		fputs(": ", f);
		if (x->kind == CSF_RF_STR) json_str(f, x->s);
		else if (x->kind == CSF_RF_NUM && isfinite(x->x)) {
			char b[32];
			csf_fmt_double(b, x->x);
			fputs(b, f);
		} else if (x->kind == CSF_RF_NUM) fputs("null", f);
		else {
			fputc('[', f);
			for (int k = 0; k < x->nv; k++) {
				if (k) fputs(", ", f);
				json_str(f, x->v[k]);
			}
			fputc(']', f);
		}
		fputs(i + 1 < rec->n ? ",\n" : "\n", f);
	}
	fputs("}\n", f);
	int bad = ferror(f) != 0;
	if (f != stderr) bad |= fclose(f) != 0;
	else fflush(f);
	if (bad) snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno ? errno : EIO));
	return bad ? -1 : 0;
}
