/*
 * fuzz_bytecode - the corrupted-bytecode test.
 *
 * Given a valid .csfb file, it (1) truncates it at every length, (2) flips
 * every byte (XOR 0xFF), and (3) flips every byte again but then repairs the
 * payload size and checksum, so that the change reaches the verifier as a
 * hostile file would. Every variant must either be rejected by csf_decode
 * with a reason, or pass verification and then run both code sections,
 * and the contact routine on its tables (the broad phase and the settling
 * of modes), without touching memory outside the model (the sanitizer
 * build checks that). Prints a summary; exits 1 if a variant that should have been
 * rejected was accepted.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csf_int.h"
#include "bytecode.h"

typedef struct exec_ctx { const csf_prog *p; double *m; csf_exec_ctx x; } exec_ctx;
static int exec_rhs(void *ctx)
{
	exec_ctx *e = ctx;
	csf_vm_exec(e->p, &e->x, CSF_SEC_RHS, e->m, e->m + e->p->ystart, e->m + e->p->dstart);
	return 0;
}

static int try_one(const unsigned char *buf, size_t len, int must_fail, long *rejected, long *accepted)
{
	csf_prog p;
	char err[256] = "";
	if (csf_decode(buf, len, &p, err, sizeof err)) {
		if (!err[0]) {
			fprintf(stderr, "rejected without a reason (length %zu)\n", len);
			return 1;
		}
		(*rejected)++;
		return 0;
	}
	(*accepted)++;
	double *m = malloc((p.nmem ? p.nmem : 1) * sizeof *m);
	if (m) {
		memcpy(m, p.mem0, p.nmem * sizeof *m);
		/* the contact routine's tables too: the candidates at this state, settled */
		csf_contacts *cs = p.ncrules ? csf_contacts_new(&p) : NULL;
		csf_exec_ctx x = { .contacts = cs };
		if (cs) {
			const double *ys[1] = { m + p.ystart };
			if (csf_contacts_find(cs, m, ys, 1, 0) >= 0) csf_contacts_commit(cs, m, NULL, NULL, 0);
			exec_ctx e = { &p, m, x };
			csf_contact_settle(&p, cs, m, 1e-7, 1e-10, exec_rhs, &e);
		}
		csf_vm_exec(&p, &x, CSF_SEC_RHS, m, m + p.ystart, m + p.dstart);
		csf_vm_exec(&p, &x, CSF_SEC_OUT, m, m + p.ystart, m + p.dstart);
		csf_contacts_free(cs);
		free(m);
	}
	csf_prog_free(&p);
	if (must_fail) {
		fprintf(stderr, "accepted a corrupted file (length %zu)\n", len);
		return 1;
	}
	return 0;
}

static void repair(unsigned char *b, size_t len)
{
	size_t plen = len - CSFB_HEADER_SIZE;
	unsigned long crc = csf_crc32(b + CSFB_HEADER_SIZE, plen);
	for (int i = 0; i < 4; i++) {
		b[20 + i] = (unsigned char)(plen >> (8 * i));
		b[24 + i] = (unsigned char)(crc >> (8 * i));
	}
}

int main(int argc, char **argv)
{
	if (argc != 2) {
		fprintf(stderr, "usage: fuzz-bytecode FILE.csfb\n");
		return 2;
	}
	FILE *f = fopen(argv[1], "rb");
	if (!f) {
		perror(argv[1]);
		return 2;
	}
	static unsigned char buf[1 << 20];
	size_t len = fread(buf, 1, sizeof buf, f);
	fclose(f);
	unsigned char *b = malloc(len);
	long rej = 0, acc = 0, hostile_rej = 0, hostile_acc = 0;
	int bad = 0;
	if (try_one(buf, len, 0, &rej, &acc)) bad = 1;
	acc = 0;
	for (size_t n = 0; n < len; n++) bad |= try_one(buf, n, 1, &rej, &acc);
	for (size_t i = 0; i < len; i++) {
		memcpy(b, buf, len);
		b[i] ^= 0xFF;
		bad |= try_one(b, len, 1, &rej, &acc);
	}
	for (size_t i = CSFB_HEADER_SIZE; i < len; i++) {
		memcpy(b, buf, len);
		b[i] ^= 0xFF;
		repair(b, len);
		bad |= try_one(b, len, 0, &hostile_rej, &hostile_acc);
	}
	free(b);
	printf("%zu-byte file: %ld truncations and flips rejected; hostile flips with a repaired checksum: "
	       "%ld rejected by the verifier, %ld accepted and executed safely\n",
	       len, rej, hostile_rej, hostile_acc);
	return bad;
}
