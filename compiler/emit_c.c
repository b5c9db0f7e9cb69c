/*
 * emit_c.c - translates a compiled program (bytecode) to C.
 *
 * The C is a translation of the bytecode, instruction by instruction, not a
 * second compiler from the AST: every instruction becomes a call of the
 * runtime function the VM's case calls (csf_op_NAME of csf_ops.h) with its
 * operands as constants (an operand relative to a loop register as base +
 * the loop's index), jumps become gotos, assertions early returns, a
 * LOOP ... NEXT a for statement over its own index variable. The
 * program's tables travel as the bytecode image itself, embedded as a byte
 * array and loaded by the same loader csfvm uses; the integrator driver,
 * output and diagnostics are libcsfrt's. So the executable and csfvm print
 * the same bytes.
 */
#include <errno.h>
#include <limits.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "csfc.h"
#include "emit_c.h"

extern char **environ;

static void comment(FILE *f, const char *s)
{
	fputs("/* ", f);
	for (; *s; s++) {
		if (s[0] == '*' && s[1] == '/') {
			fputs("* /", f);
			s++;
			continue;
		}
		fputc(*s, f);
	}
	fputs(" */", f);
}

/* Instructions per generated function: C compilers slow down badly on huge functions. */
#define CHUNK 1000
/* Consecutive instances of one rule with the same instructions that become a loop. */
#define MIN_GROUP 4
/* Consecutive instructions with the same opcode that become a loop. */
#define MIN_RUN 8

typedef struct Emit {
	const csf_prog *p;
	int sec;
	const char *fname;
	FILE *f;          /* the functions */
	FILE *tabs;       /* operand tables, written before the functions */
	int ntabs;
	int nchunks;
	int count;        /* instructions in the current function */
	int depth;        /* loops open: the C for statements the next instruction is inside */
	const unsigned char *target;
} Emit;

static void open_chunk(Emit *E)
{
	fprintf(E->f, "CSF_CHUNK int %s_%d(const csf_prog *p, double *m)\n{\n\t(void)p;\n", E->fname, E->nchunks++);
	E->count = 0;
}

static void close_chunk(Emit *E) { fputs("\treturn -1;\n}\n\n", E->f); }

/* The tabs that start a line depth + extra levels deep. */
static void indent(Emit *E, int extra) { fprintf(E->f, "%.*s", E->depth + extra, "\t\t\t\t\t\t\t\t"); }

static void src_comment(Emit *E, uint32_t src, const char *more)
{
	const csf_src *s = &E->p->srcs[src];
	indent(E, 1);
	comment(E->f, xprintf("%s:%lu: %s%s", csf_str(E->p, E->p->files[s->file]), (unsigned long)s->line,
	                      csf_str(E->p, s->text), more));
	fputc('\n', E->f);
}

static uint32_t insn_len(const uint32_t *code, uint32_t pc) { return 1u + csf_opinfo_table[code[pc]].nops; }

/* Operand kinds whose words may be relative to a loop register (csf_operand). */
static int relative_kind(int kind)
{
	return kind == CSF_K_DS || kind == CSF_K_DV || kind == CSF_K_S || kind == CSF_K_V || kind == CSF_K_AS;
}

/* Does the instruction at pc belong to a loop's machinery: a loop instruction or a relative operand? */
static int uses_loop(const uint32_t *code, uint32_t pc)
{
	const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
	if (code[pc] == CSF_OP_LOOP || code[pc] == CSF_OP_NEXT || code[pc] == CSF_OP_JEQ) return 1;
	for (int k = 0; k < oi->nops; k++)
		if (relative_kind(oi->kind[k]) && csf_reg(code[pc + 1 + k])) return 1;
	return 0;
}

/*
 * Can the instruction at pc be a row of an operand table? Not control flow,
 * and not a loop's: a table holds operand words as constants, and a
 * relative word is no constant.
 */
static int tabular(const uint32_t *code, uint32_t pc)
{
	uint32_t op = code[pc];
	return op != CSF_OP_JMP && op != CSF_OP_JZ && op != CSF_OP_ASSERT && op != CSF_OP_CONTACT && !uses_loop(code, pc);
}

/* Operand word w of kind kind as a C expression: a constant, or base + loop index i1..i3 (times 3). */
static void put_operand(FILE *f, int kind, uint32_t w)
{
	uint32_t r = relative_kind(kind) ? csf_reg(w) : 0;
	if (kind == CSF_K_N) fprintf(f, "%d", csf_imm(w));
	else if (r == 0) fprintf(f, "%lu", (unsigned long)w);
	else fprintf(f, "%luu + %si%lu", (unsigned long)(w & CSF_SLOT_MASK), r % 2 ? "" : "3u * ", (unsigned long)(r + 1) / 2);
}

/*
 * A control instruction as C: jumps become gotos, assertions returns,
 * LOOP ... NEXT a for statement. Returns 0 for any other instruction.
 */
static int emit_control(Emit *E, const uint32_t *code, uint32_t pc)
{
	const uint32_t *a = code + pc + 1; /* only the instruction's own operands: a CONTACT has none */
	switch (code[pc]) {
	case CSF_OP_JMP:
		fprintf(E->f, "goto L%lu;\n", (unsigned long)a[0]);
		return 1;
	case CSF_OP_JZ:
		fputs("if (m[", E->f);
		put_operand(E->f, CSF_K_S, a[0]);
		fprintf(E->f, "] == 0.0) goto L%lu;\n", (unsigned long)a[1]);
		return 1;
	case CSF_OP_ASSERT:
		fputs("if (m[", E->f);
		put_operand(E->f, CSF_K_S, a[0]);
		fputs(csf_reg(a[1]) ? "] == 0.0) return (int)(" : "] == 0.0) return ", E->f);
		put_operand(E->f, CSF_K_AS, a[1]);
		fputs(csf_reg(a[1]) ? ");\n" : ";\n", E->f);
		return 1;
	case CSF_OP_CONTACT:
		fputs("csf_contact_apply(p, m);\n", E->f);
		return 1;
	case CSF_OP_LOOP: { /* a count of 0 runs no iteration, as the VM's jump to the end */
		unsigned long l = a[0];
		fprintf(E->f, "for (uint32_t i%lu = 0; i%lu < %luu; i%lu++) {\n", l, l, (unsigned long)a[1], l);
		E->depth++;
		return 1;
	}
	case CSF_OP_NEXT:
		fputs("}\n", E->f);
		return 1;
	case CSF_OP_JEQ:
		fprintf(E->f, "if (i%lu == i%lu) goto L%lu;\n", (unsigned long)a[0], (unsigned long)a[1], (unsigned long)a[2]);
		return 1;
	}
	return 0;
}

/* One instruction as C; operands from o[] when o is given (inside a loop over a table), else constants. */
static void emit_insn(Emit *E, const uint32_t *code, uint32_t pc, const char *o, int base)
{
	const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
	const uint32_t *a = code + pc + 1;
	if (code[pc] == CSF_OP_NEXT) E->depth--; /* the closing brace lines up with its for */
	indent(E, o ? 2 : 1);
	if (emit_control(E, code, pc)) return;
	fprintf(E->f, "csf_op_%s(m", oi->name);
	for (int k = 0; k < oi->nops; k++) {
		fputs(", ", E->f);
		if (o) fprintf(E->f, "%s[%d]", o, base + k);
		else put_operand(E->f, oi->kind[k], a[k]);
	}
	fputs(");\n", E->f);
}

/* Starts operand table csf_tN of n rows of w words (the caller writes the rows); returns N. */
static int open_table(Emit *E, size_t n, int w)
{
	int t = E->ntabs++;
	fprintf(E->tabs, "static const uint32_t csf_t%d[%zu][%d] = {\n", t, n, w);
	return t;
}

/* Can the unit [from, to) be a row of an operand table: every instruction tabular? */
static int no_control(const uint32_t *code, uint32_t from, uint32_t to)
{
	for (uint32_t pc = from; pc < to; pc += insn_len(code, pc))
		if (!tabular(code, pc)) return 0;
	return 1;
}

static int same_shape(const uint32_t *code, uint32_t a, uint32_t alen, uint32_t b, uint32_t blen)
{
	if (alen != blen) return 0;
	for (uint32_t k = 0; k < alen; k += insn_len(code, a + k))
		if (code[a + k] != code[b + k]) return 0;
	return 1;
}

/* Straight code [from, to): runs of one opcode become loops over a table, the rest plain calls. */
static void emit_straight(Emit *E, uint32_t from, uint32_t to)
{
	const uint32_t *code = E->p->code[E->sec];
	for (uint32_t pc = from; pc < to;) {
		/* a label right before a loop's closing brace needs a statement to label */
		if (E->target[pc]) fprintf(E->f, "L%lu:%s\n", (unsigned long)pc, code[pc] == CSF_OP_NEXT ? " ;" : "");
		uint32_t len = insn_len(code, pc), n = 0, q = pc;
		while (q < to && code[q] == code[pc] && !E->target[q] && tabular(code, q)) q += len, n++;
		if (n >= MIN_RUN) {
			int w = (int)len - 1, t = open_table(E, n, w);
			for (uint32_t r = pc; r < q; r += len) {
				fputs("\t{", E->tabs);
				for (int k = 0; k < w; k++) fprintf(E->tabs, "%s%lu", k ? ", " : " ", (unsigned long)code[r + 1 + k]);
				fputs(" },\n", E->tabs);
			}
			fputs("};\n\n", E->tabs);
			indent(E, 1);
			fprintf(E->f, "for (size_t k = 0; k < %lu; k++) {\n", (unsigned long)n);
			indent(E, 2);
			fprintf(E->f, "const uint32_t *o = csf_t%d[k];\n", t);
			emit_insn(E, code, pc, "o", 0);
			indent(E, 1);
			fputs("}\n", E->f);
			E->count += 4;
			pc = q;
			continue;
		}
		emit_insn(E, code, pc, NULL, 0);
		E->count++;
		pc += len;
	}
}

/*
 * The control flow of a section's n words of code: target[pc] when a goto
 * jumps to pc; nosplit[pc] when the code cannot be split into two functions
 * at pc, because a loop's for statement or a jump spans it (a goto cannot
 * leave its function). The LOOP's own jump to its end is the for's exit,
 * no goto.
 */
static void mark_flow(const uint32_t *code, uint32_t n, unsigned char *target, unsigned char *nosplit)
{
	long *span = calloc((size_t)n + 2, sizeof *span); /* +1 where a span starts, -1 past its end */
	if (!span) exit(2);
	for (uint32_t pc = 0; pc < n; pc += insn_len(code, pc)) {
		uint32_t op = code[pc], to;
		if (op == CSF_OP_LOOP) { /* the loop is [pc, its end): no split in (pc, end) */
			span[pc + 1]++;
			span[code[pc + 3]]--;
			continue;
		}
		if (op == CSF_OP_JMP) to = code[pc + 1];
		else if (op == CSF_OP_JZ) to = code[pc + 2];
		else if (op == CSF_OP_JEQ) to = code[pc + 3];
		else continue;
		target[to] = 1; /* and no split in (pc, to]: the label must be in the goto's function */
		span[pc + 1]++;
		span[to + 1]--;
	}
	long open = 0;
	for (uint32_t pc = 0; pc <= n; pc++) nosplit[pc] = (open += span[pc]) > 0;
	free(span);
}

/*
 * Writes section sec as functions fname_0, fname_1, ... of about CHUNK
 * instructions each, split only where a statement's code starts and no
 * loop or jump spans (mark_flow), and fname calling them in order.
 * Consecutive instances of one rule whose instructions differ only in their
 * operands (a $n rule over every pair of objects) become one loop over a
 * table of operands: the same calls in the same order, in a fraction of the
 * code. Code with loops (LOOP ... NEXT, relative operands) is written as C
 * for statements instead.
 */
static void emit_section(const csf_prog *p, int sec, const char *fname, FILE *f, FILE *tabs, int *ntabs)
{
	uint32_t n = p->ncode[sec];
	const uint32_t *code = p->code[sec];
	unsigned char *target = calloc((size_t)n + 1, 1), *nosplit = calloc((size_t)n + 1, 1);
	if (!target || !nosplit) exit(2);
	mark_flow(code, n, target, nosplit);
	Emit E = { p, sec, fname, f, tabs, *ntabs, 0, 0, 0, target };
	/* units: the code of one statement instance, from one line-table entry to the next */
	uint32_t nl = p->nlines[sec];
	open_chunk(&E);
	if (nl == 0 || p->lines[sec][0].pc > 0) emit_straight(&E, 0, nl ? p->lines[sec][0].pc : n);
	for (uint32_t i = 0; i < nl;) {
		uint32_t from = p->lines[sec][i].pc, to = i + 1 < nl ? p->lines[sec][i + 1].pc : n;
		uint32_t src = p->lines[sec][i].src, len = to - from;
		/* how many following units repeat this one's shape */
		uint32_t g = 1;
		if (len && E.depth == 0 && no_control(code, from, to) && !target[from])
			while (i + g < nl && p->lines[sec][i + g].src == src) {
				uint32_t f2 = p->lines[sec][i + g].pc, t2 = i + g + 1 < nl ? p->lines[sec][i + g + 1].pc : n;
				if (target[f2] || !same_shape(code, from, len, f2, t2 - f2) || !no_control(code, f2, t2)) break;
				g++;
			}
		if (E.count >= CHUNK && !nosplit[from]) {
			close_chunk(&E);
			open_chunk(&E);
		}
		if (g >= MIN_GROUP) {
			uint32_t w = 0;
			for (uint32_t pc = from; pc < to; pc += insn_len(code, pc)) w += insn_len(code, pc) - 1;
			int t = open_table(&E, g, (int)w);
			for (uint32_t u = 0; u < g; u++) {
				uint32_t f2 = p->lines[sec][i + u].pc;
				fputs("\t{", tabs);
				int first = 1;
				for (uint32_t pc = f2; pc < f2 + len; pc += insn_len(code, pc))
					for (uint32_t k = 1; k < insn_len(code, pc); k++, first = 0)
						fprintf(tabs, "%s%lu", first ? " " : ", ", (unsigned long)code[pc + k]);
				fputs(" },\n", tabs);
			}
			fputs("};\n\n", tabs);
			src_comment(&E, src, xprintf(" (%lu instances)", (unsigned long)g));
			fprintf(f, "\tfor (size_t k = 0; k < %lu; k++) {\n\t\tconst uint32_t *o = csf_t%d[k];\n", (unsigned long)g, t);
			int base = 0;
			for (uint32_t pc = from; pc < to;) {
				uint32_t il = insn_len(code, pc), q = pc, r = 0;
				while (q < to && code[q] == code[pc]) q += il, r++;
				if (r >= MIN_RUN) { /* a run of one opcode inside the body: an inner loop */
					const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
					fprintf(f, "\t\tfor (size_t j = 0; j < %lu; j++)\n\t\t\tcsf_op_%s(m", (unsigned long)r, oi->name);
					for (int k = 0; k < oi->nops; k++) fprintf(f, ", o[%d + %d * j]", base + k, oi->nops);
					fputs(");\n", f);
					base += (int)r * oi->nops;
					pc = q;
					continue;
				}
				emit_insn(&E, code, pc, "o", base);
				base += (int)il - 1;
				pc += il;
			}
			fputs("\t}\n", f);
			E.count += (int)(len / 3) + 4;
			i += g;
			continue;
		}
		src_comment(&E, src, "");
		emit_straight(&E, from, to);
		i++;
	}
	if (target[n]) fprintf(f, "L%lu:\n", (unsigned long)n);
	close_chunk(&E);
	fprintf(f, "static int %s(const csf_prog *p, double *m)\n{\n", fname);
	if (E.nchunks == 1) {
		fprintf(f, "\treturn %s_0(p, m);\n}\n\n", fname);
	} else {
		fputs("\tint r;\n", f);
		for (int i = 0; i < E.nchunks; i++) fprintf(f, "\tif ((r = %s_%d(p, m)) >= 0) return r;\n", fname, i);
		fputs("\treturn -1;\n}\n\n", f);
	}
	*ntabs = E.ntabs;
	free(target);
	free(nosplit);
}

void emit_c(const csf_prog *p, const unsigned char *image, size_t len, const char *model, FILE *f)
{
	fputs("/*\n * Generated by csfc --emit-c from ", f);
	fputs(model, f);
	fputs(".\n * Each function is one code section of the model's bytecode, translated\n"
	      " * instruction by instruction; the embedded image carries its tables.\n"
	      " * Build: cc -O2 -ffp-contract=off model.c $(pkg-config --cflags --libs csfrt)\n */\n",
	      f);
	fputs("#include \"csf.h\"\n\n"
	      "#if defined(__GNUC__)\n#define CSF_CHUNK static __attribute__((noinline))\n#else\n#define CSF_CHUNK static\n#endif\n\n",
	      f);
	fprintf(f, "static const unsigned char csf_model_image[%zu] = {", len);
	for (size_t i = 0; i < len; i++) fprintf(f, "%s%u,", i % 16 ? " " : "\n\t", image[i]);
	fputs("\n};\n\n", f);
	char *fbuf = NULL, *tbuf = NULL;
	size_t flen = 0, tlen = 0;
	FILE *fs = open_memstream(&fbuf, &flen), *ts = open_memstream(&tbuf, &tlen);
	if (!fs || !ts) exit(2);
	int ntabs = 0;
	emit_section(p, CSF_SEC_RHS, "csf_model_rhs", fs, ts, &ntabs);
	emit_section(p, CSF_SEC_OUT, "csf_model_out", fs, ts, &ntabs);
	emit_section(p, CSF_SEC_JAC, "csf_model_jac", fs, ts, &ntabs);
	fclose(fs);
	fclose(ts);
	fwrite(tbuf, 1, tlen, f);
	fwrite(fbuf, 1, flen, f);
	free(fbuf);
	free(tbuf);
	fputs("static int csf_model_exec(const csf_prog *p, int sec, double *m)\n{\n"
	      "\treturn sec == CSF_SEC_RHS ? csf_model_rhs(p, m) : sec == CSF_SEC_OUT ? csf_model_out(p, m) : csf_model_jac(p, m);\n}\n\n"
	      "int main(int argc, char **argv)\n{\n"
	      "\treturn csf_main(argc, argv, csf_model_image, sizeof csf_model_image, csf_model_exec);\n}\n",
	      f);
}

/* Directory of the running csfc. */
static char *exe_dir(void)
{
	char exe[PATH_MAX];
	ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
	if (n <= 0) return xstrdup(".");
	exe[n] = '\0';
	char *slash = strrchr(exe, '/');
	if (slash) *slash = '\0';
	return xstrdup(exe);
}

/* Finds the runtime's header and library: installed (../include/csf, ../lib) or in the build tree. */
static int find_runtime(char **inc, char **lib)
{
	char *d = exe_dir();
	const char *incs[] = { "%s/../include/csf", "%s/../runtime" };
	const char *libs[] = { "%s/../lib", "%s" };
	for (int i = 0; i < 2; i++) {
		char *ic = xprintf(incs[i], d), *lc = xprintf(libs[i], d);
		if (access(xprintf("%s/csf.h", ic), R_OK) == 0 && access(xprintf("%s/libcsfrt.a", lc), R_OK) == 0) {
			*inc = ic;
			*lib = lc;
			return 0;
		}
	}
	return -1;
}

/* Splits s at blanks into argv entries appended to a. */
static void split_words(Vec *a, const char *s)
{
	while (s && *s) {
		while (*s == ' ' || *s == '\t') s++;
		const char *e = s;
		while (*e && *e != ' ' && *e != '\t') e++;
		if (e > s) vec_push(a, xstrndup(s, (size_t)(e - s)));
		s = e;
	}
}

int emit_c_executable(const char *csource, const char *out)
{
	char *inc, *lib;
	if (find_runtime(&inc, &lib)) {
		fprintf(stderr, "csfc: cannot find the CSF runtime (csf.h and libcsfrt.a) next to csfc\n");
		return 2;
	}
	const char *cc = getenv("CC");
	const char *cflags = getenv("CFLAGS");
	Vec a = { 0 };
	split_words(&a, cc && *cc ? cc : "cc");
	split_words(&a, cflags && *cflags ? cflags : "-O2");
	vec_push(&a, "-ffp-contract=off");
	vec_push(&a, xprintf("-I%s", inc));
	vec_push(&a, (void *)csource);
	vec_push(&a, "-o");
	vec_push(&a, (void *)out);
	vec_push(&a, xprintf("-L%s", lib));
	vec_push(&a, "-lcsfrt");
	vec_push(&a, "-lgsl");
	vec_push(&a, "-lgslcblas");
	vec_push(&a, "-lm");
	vec_push(&a, NULL);
	pid_t pid;
	int st = posix_spawnp(&pid, a.v[0], NULL, NULL, (char **)a.v, environ);
	if (st) {
		fprintf(stderr, "csfc: cannot run %s: %s\n", (char *)a.v[0], strerror(st));
		return 2;
	}
	int ws;
	while (waitpid(pid, &ws, 0) < 0)
		if (errno != EINTR) return 2;
	if (!WIFEXITED(ws) || WEXITSTATUS(ws) != 0) {
		fprintf(stderr, "csfc: the C compiler failed to build %s\n", out);
		return 2;
	}
	return 0;
}
