/*
 * test_signals.c - a run that cannot stop by itself still ends within a
 * second of SIGTERM or SIGINT, with every whole row it wrote and no half
 * row (the watchdog of csf_signals_install).
 */
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "suites.h"

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Spins for sec seconds of wall time (or for ever, sec < 0), looking at nothing. */
static void spin(double sec)
{
	double t0 = now();
	volatile unsigned long n = 0;
	while (sec < 0 || now() - t0 < sec) n++;
}

/*
 * A child writes three rows to a file through the guarded output, then
 * (mid_row) starts a fourth and spins for 0.8 s inside it before ending it,
 * then spins for ever. sig is sent 0.2 s in; returns the child's exit
 * status and how long it took to end, and the file's text in buf.
 */
static int child_run(int sig, int mid_row, double *took, char *buf, size_t len)
{
	char path[] = "/tmp/csf-signals-XXXXXX";
	int fd = mkstemp(path);
	ck_assert_int_ge(fd, 0);
	close(fd);
	pid_t pid = fork();
	ck_assert_int_ge(pid, 0);
	if (pid == 0) {
		FILE *out = fopen(path, "w");
		int null = open("/dev/null", O_WRONLY);
		if (!out || null < 0 || dup2(null, STDERR_FILENO) < 0) _exit(99); /* the watchdog's message */
		csf_signals_install(out, "test");
		for (int i = 0; i < 3; i++) {
			csf_out_begin();
			fprintf(out, "%d,row\n", i);
			csf_out_end();
		}
		if (mid_row) {
			csf_out_begin();
			fputs("3,", out);
			spin(0.8); /* the signal and the watchdog come while the row is half written */
			fputs("row\n", out);
			csf_out_end();
		}
		spin(-1);
		_exit(98);
	}
	spin(0.2);
	double t0 = now();
	kill(pid, sig);
	int status = 0;
	while (waitpid(pid, &status, WNOHANG) == 0 && now() - t0 < 5) usleep(1000);
	*took = now() - t0;
	if (now() - t0 >= 5) {
		kill(pid, SIGKILL);
		waitpid(pid, &status, 0);
	}
	FILE *f = fopen(path, "r");
	size_t n = f ? fread(buf, 1, len - 1, f) : 0;
	buf[n] = 0;
	if (f) fclose(f);
	unlink(path);
	return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

/* (signal, exit status, a row half written when it comes, what the file must hold) */
static const struct {
	int sig, want, mid_row;
	const char *rows;
} cases[] = {
	{ SIGTERM, 143, 0, "0,row\n1,row\n2,row\n" }, /* an endless loop: ended within a second */
	{ SIGINT, 130, 0, "0,row\n1,row\n2,row\n" },
	{ SIGTERM, 143, 1, "0,row\n1,row\n2,row\n3,row\n" }, /* the row being written is finished first */
};

START_TEST(watchdog_ends_a_deaf_run)
{
	double took;
	char buf[256];
	int st = child_run(cases[_i].sig, cases[_i].mid_row, &took, buf, sizeof buf);
	ck_assert_msg(st == cases[_i].want, "case %d: exit status %d, want %d", _i, st, cases[_i].want);
	ck_assert_msg(took < 1.0 && (!cases[_i].mid_row || took > 0.5),
	              "case %d: ended %.3f s after the signal, want under 1 s (and, mid-row, after the row's end at 0.6 s)",
	              _i, took);
	ck_assert_str_eq(buf, cases[_i].rows);
}
END_TEST

Suite *signals_suite(void)
{
	Suite *s = suite_create("signals");
	TCase *tc = tcase_create("watchdog");
	tcase_set_timeout(tc, 20);
	tcase_add_loop_test(tc, watchdog_ends_a_deaf_run, 0, (int)(sizeof cases / sizeof cases[0]));
	suite_add_tcase(s, tc);
	return s;
}
