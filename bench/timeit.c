/*
 * timeit.c - run a command and print its wall-clock time.
 *
 *   timeit OUT_FILE COMMAND [ARG...]
 *
 * Runs COMMAND with its standard output sent to OUT_FILE (/dev/null to
 * discard it) and prints on standard output one line: the wall-clock
 * seconds from fork to exit (CLOCK_MONOTONIC), then the user and system CPU
 * seconds of the child, then its peak resident memory in KiB (ru_maxrss). Exits with the command's status, 127 if it could not
 * be started. POSIX only: the benchmark must not need GNU date's %N.
 */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static double tv(struct timeval t) { return (double)t.tv_sec + (double)t.tv_usec * 1e-6; }

int main(int argc, char **argv)
{
	if (argc < 3) {
		fputs("usage: timeit OUT_FILE COMMAND [ARG...]\n", stderr);
		return 2;
	}
	int fd = open(argv[1], O_WRONLY | O_CREAT | O_TRUNC, 0644);
	if (fd < 0) {
		perror(argv[1]);
		return 2;
	}
	fflush(stdout);
	double t0 = now();
	pid_t pid = fork();
	if (pid < 0) {
		perror("fork");
		return 2;
	}
	if (pid == 0) {
		if (dup2(fd, 1) < 0) _exit(127);
		close(fd);
		execvp(argv[2], argv + 2);
		perror(argv[2]);
		_exit(127);
	}
	close(fd);
	int st;
	if (waitpid(pid, &st, 0) < 0) {
		perror("waitpid");
		return 2;
	}
	double t1 = now();
	struct rusage ru;
	getrusage(RUSAGE_CHILDREN, &ru);
	printf("%.6f %.6f %.6f %ld\n", t1 - t0, tv(ru.ru_utime), tv(ru.ru_stime), ru.ru_maxrss);
	if (WIFEXITED(st)) return WEXITSTATUS(st);
	return 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
}
