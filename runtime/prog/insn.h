/*
 * insn.h - the facts of an instruction's layout, each in one place: its
 * length, which operand kinds (opcodes.def, enum csf_operand_kind) name
 * memory slots and which of those the instruction writes, how many slots
 * one word names, and which slots a word relative to a loop register
 * (csf_operand) can reach. The verifier (bytecode.c), the generator
 * (scratch placement, the Jacobian's dependence analysis) and the C
 * emitter all ask these.
 */
#ifndef CSF_INSN_H
#define CSF_INSN_H

#include <stdint.h>
#include <string.h>

#include "csf_int.h"

/*
 * The words of the instruction headed by opcode op (< CSF_NOPCODES): the
 * opcode and its operands. A constant for a constant op, as the VM's
 * control-flow cases need.
 */
static inline uint32_t csf_insn_len(uint32_t op)
{
	switch (op) {
#define OP(name, n, a, b, c, d, syn) case CSF_OP_##name: return 1u + (n);
#define CTRL OP
#include "opcodes.def"
#undef CTRL
#undef OP
	default: return 1u; /* not an opcode: only a program that is not verified has it */
	}
}

/* Does an operand of this kind name memory slots (and so may be relative to a loop register)? */
static inline int csf_kind_slot(int kind)
{
	return kind == CSF_K_DS || kind == CSF_K_DV || kind == CSF_K_S || kind == CSF_K_V;
}

/* Does it name slots the instruction writes? */
static inline int csf_kind_write(int kind) { return kind == CSF_K_DS || kind == CSF_K_DV; }

/* The slots one word of this kind names: 3 for a vector, 1 for a scalar, 0 for a kind that names none. */
static inline uint32_t csf_kind_width(int kind)
{
	return kind == CSF_K_DV || kind == CSF_K_V ? 3u : kind == CSF_K_DS || kind == CSF_K_S ? 1u : 0u;
}

/*
 * Is op's result a differentiable function of its operands? Not for a STEP
 * row of opcodes.def (comparisons, logic); control flow has no result.
 */
static inline int csf_op_differentiable(uint32_t op)
{
	switch (op) {
#define OP(name, n, a, b, c, d, syn)
#define CTRL OP
#define STEP(name, n, a, b, c, d, syn) case CSF_OP_##name: return 0;
#include "opcodes.def"
#undef STEP
#undef CTRL
#undef OP
	default: return 1;
	}
}

/* The loop level register r (1 to CSF_NREGS - 1) follows. */
static inline uint32_t csf_reg_level(uint32_t r) { return (r + 1) / 2; }

/* How far register r moves from one iteration to the next: 1 (the index), 3 (three times it), 0 for register 0. */
static inline uint32_t csf_reg_stride(uint32_t r) { return r == 0 ? 0u : r % 2 ? 1u : 3u; }

/*
 * One past the last slot operand word w, naming width slots, can reach
 * when the loop its register follows runs count times (count: any value
 * for register 0; 0 counts as 1). The first is w & CSF_SLOT_MASK. With
 * width 0 (an assertion index): the largest index. 64-bit: no count wraps it.
 */
static inline uint64_t csf_operand_end(uint32_t w, uint32_t width, uint64_t count)
{
	return (uint64_t)(w & CSF_SLOT_MASK) + (count ? count - 1 : 0) * csf_reg_stride(csf_reg(w)) + width;
}

/*
 * The index of the record for pc in a[0 .. n): records of size bytes, each
 * starting with its uint32_t pc, ascending by pc (the loops of a section a
 * run's tables keep: csf_parloop, csf_bloop); n when there is none.
 */
static inline uint32_t csf_find_pc(const void *a, uint32_t n, size_t size, uint32_t pc)
{
	const unsigned char *b = a;
	uint32_t lo = 0, hi = n, at;
	while (lo < hi) {
		uint32_t mid = lo + (hi - lo) / 2;
		memcpy(&at, b + (size_t)mid * size, sizeof at);
		if (at < pc) lo = mid + 1;
		else hi = mid;
	}
	if (lo < n) memcpy(&at, b + (size_t)lo * size, sizeof at);
	return lo < n && at == pc ? lo : n;
}

#endif
