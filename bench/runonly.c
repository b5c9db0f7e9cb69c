/*
 * runonly.c - the run itself, writing no text: loads a .csfb and runs it REPS times with
 * csf_run_sink and no CSV, printing each run's wall seconds (csf_opts.run_seconds), one a line.
 * The baselines of python.sh's 10 000-object run, which Python's m.run() gives as arrays:
 *   runonly MODEL.csfb REPS        no row sink: the rows are computed (their OUT section run) and
 *                                  dropped, their values never read
 *   runonly MODEL.csfb REPS sink   a row sink that keeps nothing: each row's values are gathered
 *                                  into one buffer and handed over, as to any embedder
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csf_int.h"

static int drop(void *ctx, const double *v, size_t n)
{
	(void)v, (void)n;
	++*(size_t *)ctx;
	return 0;
}

int main(int argc, char **argv)
{
	size_t len, rows = 0;
	unsigned char *b = argc >= 3 ? csf_read_file(argv[1], &len) : NULL;
	csf_prog p;
	char err[256];
	if (!b || csf_decode(b, len, &p, err, sizeof err)) {
		fprintf(stderr, "usage: runonly MODEL.csfb REPS [sink] (a valid program)\n");
		return 2;
	}
	free(b);
	csf_sink sink = { drop, &rows, NULL };
	for (int i = 0; i < atoi(argv[2]); i++) {
		csf_opts o = { .progress = CSF_PROGRESS_OFF };
		if (csf_run_sink(&p, csf_vm_exec, &o, NULL, argc > 3 && !strcmp(argv[3], "sink") ? &sink : NULL, stderr)) return 1;
		printf("%.6f\n", o.run_seconds);
	}
	csf_prog_free(&p);
	return 0;
}
