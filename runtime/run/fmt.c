/*
 * fmt.c - numbers as the run writes them: a double in the fewest digits that
 * read back to it (every CSV cell), a step rounded down to suggest, and a
 * ratio or a count as a person writes it.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run_int.h"

void csf_fmt_double(char buf[32], double x)
{
	if (isnan(x)) {
		strcpy(buf, "nan");
		return;
	}
	if (isinf(x)) {
		strcpy(buf, x > 0 ? "inf" : "-inf");
		return;
	}
	for (int prec = 15; prec <= 17; prec++) {
		snprintf(buf, 32, "%.*g", prec, x);
		if (strtod(buf, NULL) == x) return;
	}
}

/* x rounded down to one significant digit: a step to suggest. */
double csf_run_round_down(double x)
{
	double e = pow(10, floor(log10(x))), d = floor(x / e * (1 + 1e-12));
	return d * e;
}

/* A ratio or a count as a person writes it: 350, 1e6, 2.5e6. */
void csf_run_fmt_ratio(char buf[32], double x)
{
	if (x < 1e4) {
		snprintf(buf, 32, "%.0f", x);
		return;
	}
	char m[16];
	int ex = (int)floor(log10(x));
	double mant = x / pow(10, ex);
	if (mant >= 9.95) mant /= 10, ex++;
	snprintf(m, sizeof m, "%.2g", mant);
	snprintf(buf, 32, "%se%d", m, ex);
}

