/*
 * sweep_mpi.c - csfvm-mpi: csfvm whose sweeps run across the ranks of an
 * MPI job (mpirun -np N csfvm-mpi --sweep ... MODEL.csfb).
 *
 * Every rank reads the model and the options and builds the same sweep.
 * The variants are dealt out in blocks of consecutive ones, block j to
 * rank j mod N: each rank runs its blocks in order, the others send each
 * block's result messages (csf_sweep_run) to rank 0, which takes every
 * variant in order, running its own blocks between receives, and is the
 * only one that writes. Messages from one rank arrive in the order sent
 * (MPI's non-overtaking rule), so rank 0 receives block j from rank
 * j mod N knowing no other message of that rank comes first. The
 * output is the bytes a run on one machine writes. Only this file (and
 * the csfvm-mpi program it makes) needs MPI: libcsfrt calls it through
 * csf_sweep_distribute.
 */
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mpi.h>

#include "csf_int.h"

/* Appends variant i's result message, after its length (8 bytes), to the buffer *b of *len bytes (room *cap). */
static int append(csf_sweep *s, size_t i, unsigned char **b, size_t *len, size_t *cap)
{
	size_t n = 0;
	unsigned char *m = csf_sweep_run(s, i, &n);
	if (!m) n = 0; /* rank 0 reports the result lost */
	if (*len + 8 + n > *cap) {
		size_t c = (*len + 8 + n) * 2;
		unsigned char *q = realloc(*b, c);
		if (!q) {
			free(m);
			return -1;
		}
		*b = q;
		*cap = c;
	}
	for (int k = 0; k < 8; k++) (*b)[*len + (size_t)k] = (unsigned char)((uint64_t)n >> (8 * k));
	if (n) memcpy(*b + *len + 8, m, n);
	*len += 8 + n;
	free(m);
	return 0;
}

/*
 * Variants go to the ranks in blocks of B consecutive ones, block j to
 * rank j mod size (B about 1/32 of a rank's share, at most 64: one message
 * a block, few beside short runs). A block's message is its variants'
 * result messages, each after its length.
 */
static int distribute(csf_sweep *s)
{
	int rank, size;
	MPI_Comm_rank(MPI_COMM_WORLD, &rank);
	MPI_Comm_size(MPI_COMM_WORLD, &size);
	if (size == 1) return 1;
	size_t n = csf_sweep_count(s), B = n / ((size_t)size * 32), nblocks;
	B = B < 1 ? 1 : B > 64 ? 64 : B;
	nblocks = (n + B - 1) / B;
	unsigned char *buf = NULL;
	size_t cap = 0;
	int bad = 0;
	for (size_t j = 0; j < nblocks; j++) {
		int owner = (int)(j % (size_t)size);
		if (owner != rank && rank != 0) continue;
		size_t first = j * B, last = first + B < n ? first + B : n, len = 0;
		if (owner == rank) {
			for (size_t i = first; i < last && !bad; i++) bad = append(s, i, &buf, &len, &cap);
			if (bad) len = 0;
		} else {
			MPI_Status st;
			int count;
			MPI_Probe(owner, 0, MPI_COMM_WORLD, &st);
			MPI_Get_count(&st, MPI_BYTE, &count);
			if ((size_t)count > cap) {
				free(buf);
				cap = (size_t)count;
				buf = malloc(cap);
				if (!buf) MPI_Abort(MPI_COMM_WORLD, 2);
			}
			MPI_Recv(buf, count, MPI_BYTE, owner, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
			len = (size_t)count;
		}
		if (rank != 0) {
			MPI_Send(buf, len > INT_MAX ? 0 : (int)len, MPI_BYTE, 0, 0, MPI_COMM_WORLD);
			continue;
		}
		/* rank 0 takes the block's variants in order; after an error it keeps receiving, so no rank waits forever */
		size_t at = 0;
		for (size_t i = first; i < last; i++) {
			uint64_t m = 0;
			if (at + 8 <= len)
				for (int k = 0; k < 8; k++) m |= (uint64_t)buf[at + (size_t)k] << (8 * k);
			const unsigned char *msg = at + 8 + m <= len ? buf + at + 8 : NULL;
			if (!bad && csf_sweep_take(s, i, msg, msg ? (size_t)m : 0)) bad = 1;
			at += 8 + (msg ? (size_t)m : 0);
		}
	}
	free(buf);
	return bad && rank == 0 ? -1 : 0;
}

int main(int argc, char **argv)
{
	MPI_Init(&argc, &argv);
	int rank;
	MPI_Comm_rank(MPI_COMM_WORLD, &rank);
	if (rank != 0) { /* rank 0 writes the output and the diagnostics */
		if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr)) MPI_Abort(MPI_COMM_WORLD, 2);
		csf_quiet = 1;
	}
	csf_sweep_distribute = distribute;
	int st = csf_main(argc, argv, NULL, 0, csf_vm_exec);
	MPI_Finalize();
	return st;
}
