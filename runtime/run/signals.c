/*
 * signals.c - SIGINT and SIGTERM end a run after its last whole row, and a
 * watchdog ends one that does not look in time.
 */
#include <signal.h>
#include <string.h>
#include <sys/time.h>
#include <unistd.h>

#include "run_int.h"

volatile sig_atomic_t csf_signal;

/*
 * Interruption. SIGINT and SIGTERM set csf_signal; every loop of a run that
 * can last looks at it, and the run ends after its last whole row with the
 * --stats line. A computation that does not look (a defect, or a library's
 * long loop) must not make a run deaf: the first signal also arms a
 * watchdog, and if the process is still running CSF_WATCHDOG_MS later the
 * watchdog flushes the rows already written and ends the process with the
 * same status. It never cuts a row: while one is being written
 * (csf_out_begin .. csf_out_end), it waits for the row's end.
 */
enum { CSF_WATCHDOG_MS = 500 };
static volatile sig_atomic_t writing, overdue;
static FILE *guarded_out;
static char watchdog_msg[160];
static void (*volatile wakes)(void); /* a thread that writes the rows (rowthread.c), woken to end it all */

/* Flushes the rows written (no row is half written) and ends the process: 128 + the signal. */
void csf_watchdog_exit(void)
{
	if (guarded_out) fflush(guarded_out);
	ssize_t w = write(STDERR_FILENO, watchdog_msg, strlen(watchdog_msg));
	(void)w;
	_exit(128 + csf_signal);
}

static void on_watchdog(int sig)
{
	(void)sig;
	if (wakes) { /* the row thread writes the rows handed to it, then ends the process */
		overdue = 1;
		wakes();
	} else if (writing) {
		overdue = 1; /* csf_out_end ends the process after the row */
	} else {
		csf_watchdog_exit();
	}
}

static void on_signal(int sig)
{
	if (csf_signal) return;
	csf_signal = sig;
	struct itimerval it = {{0, 0}, {0, CSF_WATCHDOG_MS * 1000}};
	setitimer(ITIMER_REAL, &it, NULL);
}

void csf_signals_install(FILE *out, const char *prog)
{
	guarded_out = out;
	snprintf(watchdog_msg, sizeof watchdog_msg,
	         "%s: interrupted: the run did not reach the end of a row within %d ms; the rows before it are "
	         "written\n",
	         prog, (int)CSF_WATCHDOG_MS);
	struct sigaction sa;
	memset(&sa, 0, sizeof sa);
	sigemptyset(&sa.sa_mask);
	sa.sa_flags = SA_RESTART;
	sa.sa_handler = on_signal;
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);
	sa.sa_handler = on_watchdog;
	sigaction(SIGALRM, &sa, NULL);
}

void csf_out_begin(void) { writing = 1; }

void csf_out_end(void)
{
	writing = 0;
	if (overdue) csf_watchdog_exit();
}

int csf_watchdog_overdue(void) { return overdue; }

void csf_watchdog_wakes(void (*f)(void)) { wakes = f; }
