/*
 * replay - runs a fuzz target's LLVMFuzzerTestOneInput on files, without
 * libFuzzer: make check replays tests/fuzz/regress/ with it (built by the
 * ordinary compiler, with the sanitizers in the sanitizer build), and AFL++
 * runs it as its target (one file, or standard input).
 *
 *   replay FILE...   each file once, in order; prints "N inputs" at the end
 *   replay           standard input once
 *
 * A crash or sanitizer report ends the process. An input that takes more
 * than REPLAY_CPU seconds of CPU (a hang, as the campaign counts one, with
 * room for the sanitizers) is named, and the exit status is 1; else 0.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "csf_int.h"

#define REPLAY_CPU 5.0

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int main(int argc, char **argv)
{
	int n = 0, slow = 0;
	for (int i = 1; i < argc || (argc == 1 && i == 1); i++) {
		size_t len;
		unsigned char *buf = csf_read_file(argc == 1 ? "-" : argv[i], &len); /* runtime/prog/file.c */
		if (!buf) {
			perror(argc == 1 ? "stdin" : argv[i]);
			return 2;
		}
		clock_t c0 = clock();
		LLVMFuzzerTestOneInput(buf, len);
		double cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
		if (cpu > REPLAY_CPU) {
			printf("%s: %.1f s of CPU, more than %g: a hang\n", argc == 1 ? "stdin" : argv[i], cpu, REPLAY_CPU);
			slow = 1;
		}
		free(buf);
		n++;
	}
	if (argc > 1) printf("%d inputs\n", n);
	return slow;
}
