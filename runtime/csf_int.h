/*
 * csf_int.h - the runtime's internal interface, shared by libcsfrt's files,
 * csfc (which builds programs with the same tables) and the tests: the
 * program's layout and tables, the bytecode loader and verifier,
 * parameters, the contact routine's state, signals, sweeps, units.
 * Generated programs and embedders use csf.h alone.
 */
#ifndef CSF_INT_H
#define CSF_INT_H

#include <signal.h>
#include <time.h>

#include "csf.h"



/* Opcodes, from opcodes.def. */
enum csf_opcode {
#define OP(name, n, a, b, c, d, syn) CSF_OP_##name,
#define CTRL OP
#include "opcodes.def"
#undef CTRL
#undef OP
	CSF_NOPCODES
};

/* Operand kinds of opcodes.def. */
enum csf_operand_kind { CSF_K___ = 0, CSF_K_DS, CSF_K_DV, CSF_K_S, CSF_K_V, CSF_K_J, CSF_K_AS, CSF_K_N, CSF_K_L, CSF_K_C,
                        CSF_K_B };

/*
 * Loops. LOOP L, n, end runs its body (up to the matching NEXT) n times with
 * the index of level L going 0, 1, ..., n - 1; loops nest, level 1
 * outermost, at most CSF_LOOP_MAX deep. A slot or assertion operand word w
 * is relative: its top bits name a register, whose value is added to the
 * rest of the word (csf_operand). Register 0 is 0; register 2L - 1 is the
 * index of loop level L, register 2L three times it (the stride of a vector
 * in an array of vectors); register 7 is invalid. So an array of one scalar
 * per object of a shape is read as base + index, one of vectors as
 * base + 3 index.
 */
#define CSF_LOOP_MAX 3
#define CSF_REG_SHIFT 29
#define CSF_SLOT_MASK ((1u << CSF_REG_SHIFT) - 1u)
#define CSF_NREGS 7
/* The register of operand word w, and w with register r. */
static inline uint32_t csf_reg(uint32_t w) { return w >> CSF_REG_SHIFT; }
static inline uint32_t csf_rel(uint32_t slot, uint32_t r) { return slot | r << CSF_REG_SHIFT; }
/* The slot (or assertion index) word w names, given the registers. */
static inline uint32_t csf_operand(uint32_t w, const uint32_t *reg) { return (w & CSF_SLOT_MASK) + reg[w >> CSF_REG_SHIFT]; }


typedef struct csf_opinfo {
	const char *name;     /* "ADD" */
	const char *synopsis; /* "R[A] := R[B] + R[C]" */
	uint8_t nops;         /* number of operands */
	uint8_t kind[4];      /* enum csf_operand_kind, CSF_K___ past nops */
} csf_opinfo;

/* Indexed by enum csf_opcode. */
extern const csf_opinfo csf_opinfo_table[CSF_NOPCODES];

/* One output column: header text and the memory slot printed. */
typedef struct csf_col { uint32_t name, slot; } csf_col;
/* A source statement: file (index into files), line, its text. */
typedef struct csf_src { uint32_t file, line, text; } csf_src;
/*
 * An object property in memory: its object (index into objects), name, slot,
 * width (1 or 3), and its class as a parameter (index into pclasses): what
 * -D NAME=VALUE needs to set its initial value, or why it cannot.
 */
typedef struct csf_prop { uint32_t object, name, slot, width, cls; } csf_prop;
/* A global constant in memory (predefined or declared): name, slot, width, class (pclasses). */
typedef struct csf_global { uint32_t name, slot, width, cls; } csf_global;
/*
 * A parameter class: the dimension of a value (exponents of length, mass,
 * time, current: CSF_NDIM; known 0: a bare number whose dimension nothing fixed, so only a
 * bare number may replace it), its unit in the model's unit system
 * ("m/s"; "" when dimensionless), and why (when not "") -D cannot set it:
 * its value was folded at compile time into another value, it is computed
 * by a rule, or it chose which contacts exist.
 */
/* The dimensions: exponents of length, mass, time and electric current, in this order. */
#define CSF_NDIM 4
typedef struct csf_pclass { uint32_t unit, why, known; double dim[CSF_NDIM]; } csf_pclass;
/* A value a code section computes, in the order it computes them. */
typedef struct csf_target { uint32_t slot, width, src, name, object; } csf_target;
/* An assertion: its statement and the object it was checked for. */
typedef struct csf_assert { uint32_t src, object; } csf_assert;
/* Line table entry: instructions from pc on belong to statement src. */
typedef struct csf_line { uint32_t pc, src; } csf_line;

/*
 * An event of a conditional rule: a comparison in its condition, compiled as
 * value = lhs - rhs (or rhs - lhs) and EVGT/EVGE. kind 0: true when value > 0;
 * 1: when value >= 0. The runtime keeps the side in slot mode (0 or 1; -1
 * before the first evaluation) and switches it only at the located crossing.
 */
typedef struct csf_event { uint32_t kind, value, mode, src; } csf_event;
/* kind | CSF_EVENT_TERMINAL: a 'stop when' condition, which ends the run at its crossing */
#define CSF_EVENT_TERMINAL 2u

/*
 * A `when` block (one per binding of its objects): its statement, and two
 * slots of memory the EVT section keeps. The runtime runs EVT at each
 * event, after an RHS evaluation at the event's instant with the modes
 * before it: for each block, in order, the section computes the condition
 * from the values there, sets fire to 1 if it is true and prev (its value
 * at the last event: 0 or 1; -1 before the first, so that a condition true
 * at the start does not fire) is 0, else 0, and prev to the condition;
 * then, for each block that fires, the new values from the values before
 * any is set, and then sets them. A property only `when` blocks assign is
 * latched: it lives in memory like prev, and changes only there. So the
 * run's state is t, the state vector, and the slots of every prev and of
 * the EVT section's targets (the latched values): a checkpoint keeps them.
 */
typedef struct csf_when { uint32_t src, fire, prev; } csf_when;

/*
 * The contact routine's tables (mechanics/rules, rules 1 to 4; runtime/contact/).
 * There is no list of pairs: the program lists the bodies that can touch,
 * and the routine finds the pairs near or in contact at run time.
 *
 * A contact body is of a kind, its field plane (nonzero: immovable, of
 * infinite mass, without v, a, m, FN and Ff): a mass point (CSF_CB_POINT)
 * with the slots of its pos, v, a, m, radius, cr, mu_s, mu_k, FN and Ff
 * (pos in the state); a plane (CSF_CB_PLANE) with its point in POS, its
 * edge in V, its normal in R and its cr, mu_s and mu_k; or an anchor
 * (CSF_CB_ANCHOR), an immovable sphere, with its pos, radius, cr, mu_s
 * and mu_k (pos not in the state). The fields a body lacks hold the slot
 * of t. object is its object; varies is 1 when its radius (a plane:
 * point, normal or edge; an anchor: pos or radius) is computed or
 * integrated, so that the routine cannot tell from positions alone how
 * near it is: it is then a candidate with every body of its rules at all
 * times.
 */
enum csf_contact_field {
	CSF_CF_POS, CSF_CF_V, CSF_CF_A, CSF_CF_M, CSF_CF_R, CSF_CF_CR, CSF_CF_MUS, CSF_CF_MUK, CSF_CF_FN, CSF_CF_FF,
	CSF_CF_N
};
enum csf_cbody_kind { CSF_CB_POINT, CSF_CB_PLANE, CSF_CB_ANCHOR };
typedef struct csf_cbody { uint32_t plane, object, varies, s[CSF_CF_N]; } csf_cbody;
/*
 * A contact rule (one contact() statement): its $0 bodies, mass points,
 * are cmembers[first0 .. first0 + n0), its $1 bodies, mass points,
 * planes or anchors, cmembers[first1 .. first1 + n1) (indices into
 * cbodies). every 1 (a rule without `for`): the pairs are every $0 with
 * every $1 of another object, two mass points once (the $0 defined
 * first), and not two points (a mass point or an anchor, both of radius
 * 0: they never touch); every 0 (a rule with `for`): the
 * k-th $0 with the k-th $1 (n0 = n1). The pairs are ordered by rule, then
 * by their $0's place in its list, then their $1's.
 */
typedef struct csf_crule { uint32_t src, every, first0, n0, first1, n1; } csf_crule;
/*
 * The constraints (rules with attribute C; runtime/constraint/). A
 * constraint k is the equation g = 0 (kind CSF_CON_EQ), or g <= 0 or
 * g >= 0 (a string: one-sided), g = LHS - RHS of its rule. The code of
 * the RHS and OUT sections computes, before the CONSTRAIN instruction, at
 * the slots the table names: g, its rate gd = dg/dt, the bias c (the part
 * of g's second derivative that is not J a: g'' = sum_b J_b . a_b + c),
 * the scale of the equation's terms (|LHS| + |RHS|), and per body b,
 * conbodies[first .. first + n), the gradient J_b of g with respect to b's
 * position (3 slots), and the restitution of going taut (a string), the
 * least cr of its objects (1 when none has one). The code computes g, gd,
 * scale and cr only while the slot want (the same for every constraint)
 * holds a nonzero value: the forces need only J and c. A body is a mass point: its pos and v in the state,
 * its a, m and FC (the force the constraints put on it). unit is the
 * unit of g (a string), for messages; src its rule's statement.
 */
enum { CSF_CON_EQ, CSF_CON_LE, CSF_CON_GE };
typedef struct csf_con { uint32_t src, kind, g, gd, c, scale, cr, want, first, n, unit; } csf_con;
typedef struct csf_conbody { uint32_t object, J, pos, v, a, m, fc; } csf_conbody;
/* The run-time state of the constraints: work arrays and modes (runtime/constraint/). */
typedef struct csf_cons csf_cons;

/* The run-time state of the contact routine: the candidate pairs and their modes (runtime/contact/broad.c). */
typedef struct csf_contacts csf_contacts;

/*
 * A program. Strings are offsets into strs (every one NUL-terminated).
 * Memory: slot tslot holds t; slots [ystart, ystart+ny) the state vector;
 * [dstart, dstart+ny) its derivative, written by the RHS section.
 */
struct csf_prog {
	char *strs;
	uint32_t nstrs;
	double *mem0;
	uint32_t nmem;
	uint32_t nspans; /* the stretches of mem0 that its runs do not make zeros, as decoded: (first slot,
	                    count) pairs, in order; spans NULL: not known (mem0 is to be copied whole). Not
	                    in the file: a decoded program's mem0 is zeroed memory whose pages of zeros a
	                    run can leave untouched, copying the spans alone (run.c) */
	uint32_t *spans;
	uint32_t tslot, ystart, dstart, ny;
	uint32_t jtan;  /* JAC: the tangent of slot s is slot s + jtan (0: no Jacobian) */
	uint32_t *vpair; /* per state component: 1 + its velocity's index if it is a position (Verlet), else 0 */
	double *yscale; /* per state component: the absolute tolerance's scale (the unit system's
	                   measure of one SI unit of that component), so accuracy is unit-independent */
	double *yatol;  /* per state component: the absolute tolerance the scene sets (`atol A` on the
	                   property's line), in the model's units; 0: none (--atol, else tol * yscale) */
	double till, by;
	uint32_t ncols, nfiles, nsrcs, nasserts, nobjects, nprops, nevents, nwhens;
	csf_col *cols;
	csf_event *events;
	csf_when *whens; /* the `when` blocks, in the order the EVT section runs them */
	uint32_t ncbodies, ncmembers, ncrules; /* the contact routine's tables (no rules: no contacts) */
	csf_cbody *cbodies;
	uint32_t *cmembers;
	csf_crule *crules;
	uint32_t ncons, nconbodies; /* the constraints (no constraints: none) */
	csf_con *cons;
	csf_conbody *conbodies;
	uint32_t *objects; /* object names, in definition order */
	csf_prop *props;
	double ubase[CSF_NDIM]; /* the model's unit system: its units of length, mass, time, current in SI */
	uint32_t nglobals, npclasses;
	csf_global *globals; /* the globals -D can name */
	csf_pclass *pclasses;
	uint32_t *files;
	csf_src *srcs;
	csf_assert *asserts;
	uint32_t ntargets[CSF_NSEC], ncode[CSF_NSEC], nlines[CSF_NSEC];
	csf_target *targets[CSF_NSEC]; /* NULL in a decoded program: see targets_file */
	/* A decoded program's targets as the file has them (progressions, bytecode.h: targets_file_len[s]
	   bytes), not expanded: read only to name the rule of a value that is not finite
	   (csf_targets_copy), they would be a million members' largest table. NULL in a program csfc
	   builds, which has targets. */
	unsigned char *targets_file[CSF_NSEC];
	uint32_t targets_file_len[CSF_NSEC];
	/* The same for vpair, which only verlet reads (csf_vpair_copy): NULL vpair in a decoded program. */
	unsigned char *vpair_file;
	uint32_t vpair_file_len;
	uint32_t *code[CSF_NSEC];
	csf_line *lines[CSF_NSEC];
};

/*
 * The ntargets[sec] targets of section sec of p, in a malloc'd array (the caller frees it), expanded
 * from targets_file in a decoded program. NULL when memory runs out. (bytecode.c)
 */
csf_target *csf_targets_copy(const csf_prog *p, int sec);

/* p's ny state pairs (vpair) in a malloc'd array, expanded from vpair_file in a decoded program.
   NULL when memory runs out. (bytecode.c) */
uint32_t *csf_vpair_copy(const csf_prog *p);

/* String at offset off of p's string table. */
static inline const char *csf_str(const csf_prog *p, uint32_t off) { return p->strs + off; }

/*
 * Serialises p into a malloc'd buffer (*out, *len); the caller frees it.
 * Returns 0, or -1 when memory runs out.
 */
int csf_encode(const csf_prog *p, unsigned char **out, size_t *len);

/*
 * Parses and verifies a bytecode image. On success fills *p (free with
 * csf_prog_free) and returns 0. On any defect returns -1 and writes a
 * one-line reason into err (never crashes, never allocates more than the
 * image justifies).
 */
int csf_decode(const unsigned char *buf, size_t len, csf_prog *p, char *err, size_t errlen);

/* Writes a reason (printf format) into err[errlen] and returns -1: the loader's, verifier's and -D's failures. */
int csf_fail(char *err, size_t errlen, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* Verifies a program's tables and code (csf_decode calls it). 0 or -1 + reason. */
int csf_verify(const csf_prog *p, char *err, size_t errlen);

/*
 * Parameters (param.c): a value named NAME (a global) or OBJECT.PROP,
 * found in p's tables; its slot, width and class.
 */
typedef struct csf_pref { uint32_t slot, width; const csf_pclass *cls; } csf_pref;

/*
 * Finds the parameter name (a global or OBJECT.PROP, either followed by
 * .x, .y or .z for one component of a vector). Returns 0 and fills *r, or
 * -1 with a one-line reason in err ("unknown name", "ball has no property
 * x that the run uses", with "did you mean 'NAME'?" for a near miss).
 */
int csf_param_find(const csf_prog *p, const char *name, csf_pref *r, char *err, size_t errlen);

/*
 * Reads a value for parameter r (named name) from text, as the source writes one: a
 * number or a vector (x, y, z), each optionally followed by a unit, and a
 * unit after the whole (`3 m/s`, `(3, 0, 4) m/s`, `90 deg`, `2000 g/s^2`;
 * a bare number is in the model's units). Checks its kind (scalar or
 * vector) and dimension, converts it to the model's units into v[0..width).
 * Returns 0, or -1 with a one-line reason in err naming the expected unit.
 */
int csf_param_value(const csf_prog *p, const char *name, const csf_pref *r, const char *text, double v[3], char *err,
                    size_t errlen);

/*
 * A parameter overlay: initial values that replace the program's, set by
 * -D and by each variant of a sweep, so that the program stays as it was
 * loaded. csf_run applies them in order (a later value of a slot wins) to
 * the run's memory after copying p->mem0 into it (csf_opts.init).
 */
typedef struct csf_setting { uint32_t slot; double value; } csf_setting;
struct csf_overlay { csf_setting *v; size_t n, cap; };
/* Appends slot := value. Returns 0, or -1 when memory runs out. */
int csf_overlay_add(csf_overlay *ov, uint32_t slot, double value);
/* Writes ov's values (NULL: none) into m, a memory of the program's nmem slots. */
void csf_overlay_apply(const csf_overlay *ov, double *m);
/* Frees ov's values; ov is then empty. */
void csf_overlay_free(csf_overlay *ov);

/*
 * -D NAME=VALUE: sets the initial value of a global or an object's
 * property in the overlay ov (p is not changed). Returns 0, or -1 with the
 * reason in err ("-D NAME=VALUE: ..."): an unknown name, a value that
 * cannot be overridden (and why), a wrong kind or dimension.
 */
int csf_param_set(const csf_prog *p, csf_overlay *ov, const char *assign, char *err, size_t errlen);

/* Lists every parameter of p with its initial value and unit, or why -D cannot set it (csfc --explain). */
void csf_params_list(const csf_prog *p, FILE *f);

/* Frees everything a decoded or compiler-built program owns. */
void csf_prog_free(csf_prog *p);

/* Writes a human-readable listing of p's code to f. */
void csf_disassemble(const csf_prog *p, FILE *f);


/*
 * The run-time state an execution function passes on, which the program
 * (const, as loaded) does not hold: the contact routine's candidate pairs
 * and modes, for the CONTACT instruction (csf_run owns them; NULL: no
 * contacts, and CONTACT does nothing); the constraints' work arrays and
 * modes, for the CONSTRAIN instruction (NULL: CONSTRAIN does nothing);
 * the threads that share the loops of a shape (--threads N; NULL: one);
 * the loops the VM runs a block of iterations at a time (runtime/prog/block.h;
 * NULL: none, every loop an iteration at a time, with the same results).
 */
typedef struct csf_blocks csf_blocks;
struct csf_exec_ctx {
	csf_contacts *contacts;
	csf_cons *cons;
	csf_pool *pool;
	csf_blocks *blocks;
};



/* Evaluates the RHS section on m (the current state): for csf_contact_settle. */
typedef int (*csf_eval_fn)(void *ctx);

/*
 * Makes every contact's mode consistent at the current instant, changing
 * the velocities (and positions, by rounding-size amounts) in m: impacts
 * (restitution), the contacts that come to rest, lift-off, stick and slip,
 * as the guards of the current modes call for, over the candidates cs
 * (NULL: none; chosen at this instant: csf_contacts_find with one state).
 * zeno: the time below which a train of bounces counts as at rest; tol:
 * the integrator's relative tolerance (the accuracy of the positions it
 * computes). Returns 0; -1 if eval failed; CSF_SETTLE_ENDLESS if the
 * impacts did not come to an end within csf_contact_passes(n) of them (n
 * candidate pairs); CSF_SETTLE_IMPULSES if the impulses of one could not be
 * solved (masses in a cluster that differ by more than about 1e10).
 */
enum { CSF_SETTLE_ENDLESS = 1, CSF_SETTLE_IMPULSES = 2, CSF_SETTLE_FORCES = 3 /* csf_contacts_unsolved */ };
int csf_contact_settle(const csf_prog *p, csf_contacts *cs, double *m, double zeno, double tol, csf_eval_fn eval,
                       void *ctx);
uint64_t csf_contact_passes(uint32_t n);

/*
 * The contact routine's state during a run (csf_run keeps it, and passes it to the code in csf_exec_ctx):
 * the candidate pairs, those that can touch soon enough to matter, in the
 * order of the pairs (csf_crule), each with its mode and work values.
 * NULL when memory runs out.
 */
csf_contacts *csf_contacts_new(const csf_prog *p);
void csf_contacts_free(csf_contacts *c);
/*
 * The first mass point of p's contact rules whose mass in m is not a positive number with a finite
 * inverse (an impact divides by it), or -1. A body of mass -1 kg or 1e-320 kg makes every impact
 * and every contact force meaningless: csf_run refuses the run.
 */
long csf_contacts_bad_mass(const csf_prog *p, const double *m);
/*
 * Around velocities changed at an event by something other than an impact (a `when` block): before,
 * each pair in contact's relative velocity is kept; after, each pair in contact whose relative
 * velocity changed takes its mode afresh as after an impact: a ball resting on the floor kicked
 * upwards leaves it (zeno: as csf_contact_settle's). m holds the velocities.
 */
void csf_contacts_before_kick(csf_contacts *cs, const double *m);
void csf_contacts_after_kick(csf_contacts *cs, double *m, double zeno);
/* The number of candidate pairs (two guards each, after the events'). */
uint32_t csf_contacts_count(const csf_contacts *c);
/* The contact systems solved directly so far, and how many of them were recalled (not solved again). */
void csf_contacts_solves(const csf_contacts *c, unsigned long *solved, unsigned long *recalled);
void csf_contacts_searches(const csf_contacts *c, unsigned long *searches, unsigned long *unfound);
/* Whether the contact forces of some evaluation could not be solved (masses that differ by more than about 1e10,
   or a cluster that neither the direct solve nor the sweeps solve); set back (the stability guard's
   evaluations at states near the run's, which are not the run's). */
int csf_contacts_unsolved(const csf_contacts *c);
void csf_contacts_set_unsolved(csf_contacts *c, int unsolved);
/* Of the cluster whose forces or impulses could not be solved: a pair of it (a candidate), its pairs, and,
   when its unknowns were too many for the direct solve, the most it takes (else 0). */
void csf_contacts_why(const csf_contacts *c, uint32_t *pair, uint32_t *np, uint32_t *big);
/* The guards of candidate pairs as the last csf_contact_apply left them, into g[0 .. 2 count). */
void csf_contacts_guards(const csf_contacts *c, double *g);
/* The source statement of candidate k (its rule). */
uint32_t csf_contacts_src(const csf_contacts *c, uint32_t k);
/* The objects (indices into objects) of candidate k's two bodies. */
void csf_contacts_objects(const csf_contacts *c, uint32_t k, uint32_t *oi, uint32_t *oj);
/*
 * The candidate pairs that overlap at m's positions by more than the
 * touching tolerance (1e-12 of their scale), where an overlap counts (a
 * plane's edge); the deepest of them into *deepest, its depth into *depth
 * (0 if none). The start reports them (csf_run_update_modes).
 */
uint32_t csf_contacts_overlaps(const csf_contacts *c, const double *m, uint32_t *deepest, double *depth);
/*
 * Chooses the next candidates from the ns states ys[0..ns) (state vectors,
 * in time order, h apart: the instants at which the guards will be looked
 * at): the pairs in contact or hopping, and every pair whose gap is
 * (nearly) closed at one of them or on the paths between them. m holds the
 * radii and the planes (and is otherwise left alone). Returns how many
 * there will be, or -1 when memory runs out; then csf_contacts_commit
 * switches to them.
 */
long csf_contacts_find(csf_contacts *c, const double *m, const double *const *ys, int ns, double h);
/*
 * Switches to the candidates csf_contacts_find chose. For q < ng, g[q]
 * holds the guards (two per candidate) of the old candidates, and becomes
 * those of the new ones (room for 2 count values): a kept pair's are
 * moved, a new pair's (apart: its gap) computed from the positions of
 * state gy[q] and m's radii and planes, as csf_contact_apply would.
 */
void csf_contacts_commit(csf_contacts *c, const double *m, double *const *g, const double *const *gy, int ng);
/*
 * Candidate k's gap and its rate at the state y (m holds the radii, the
 * planes and the anchors): the guard csf_contact_apply gives an apart pair
 * at that state, into *gap, and its derivative, the relative velocity
 * along the normal, into *rate (negative: closing). 1, or 0 (nothing
 * written) when the pair is not apart: its guard is not its gap.
 */
int csf_contacts_gap_rate(const csf_contacts *cs, uint32_t k, const double *m, const double *y, double *gap,
                          double *rate);
/* The slots of the state (indices from its start) that candidate k's gap and rate read: its bodies'
   positions and velocities (3 each; a plane's, an anchor's are not the state's). 0 when the pair is
   not apart. */
uint32_t csf_contacts_gap_slots(const csf_contacts *cs, uint32_t k, uint32_t idx[12]);


/*
 * The signal (SIGINT, SIGTERM) that asked the run to end, 0 if none:
 * csf_main's handlers set it; csf_run ends after the current row, with
 * the --stats line, and returns 128 + the signal's number.
 */
extern volatile sig_atomic_t csf_signal;

/*
 * Installs the handlers of csfvm and of generated programs: SIGINT and
 * SIGTERM set csf_signal and arm a watchdog that, if the process still runs
 * half a second later, flushes the rows written to out and exits with
 * 128 + the signal (a message on stderr naming prog). Every write to out
 * stands between csf_out_begin() and csf_out_end(), so that the watchdog
 * never flushes half a row.
 */
void csf_signals_install(FILE *out, const char *prog);
void csf_out_begin(void);
void csf_out_end(void);





/*
 * A sweep (sweep.c): the variants of a scene, the Cartesian product of the
 * --sweep-file rows and the --sweep axes, in that order, the last varying fastest. Each
 * variant's result is one message (csf_sweep_run) that the writer takes
 * in variant order (csf_sweep_take); where it was made does not matter.
 */
typedef struct csf_sweep csf_sweep;
/* The number of variants. */
size_t csf_sweep_count(const csf_sweep *s);
/* Runs variant i; returns its result message (malloc'd, *len bytes; NULL when memory ran out). */
unsigned char *csf_sweep_run(csf_sweep *s, size_t i, size_t *len);
/* Writes the result of variant i, which must be the next in order; 0, or -1 after an error (reported). */
int csf_sweep_take(csf_sweep *s, size_t i, const unsigned char *msg, size_t len);
/*
 * Runs the variants of s elsewhere (csfvm-mpi sets it: sweep_mpi.c):
 * returns 0 when it did, 1 when it did not (one MPI rank: the sweep forks
 * its -j workers instead), -1 after an error. NULL in csfvm.
 */
extern int (*csf_sweep_distribute)(csf_sweep *s);
/* Set on csfvm-mpi's ranks but rank 0, which write nothing: csf_main opens no -o FILE.csv there. */
extern int csf_quiet;
/* What an HDF5 file says ran, beside the options: the model's source (its name) and the command line. */
typedef struct csf_h5_origin {
	const char *model;
	int argc;
	char **argv;
} csf_h5_origin;
/*
 * csfvm --sweep / --sweep-file: runs the variants of p (each with o->init, -D's
 * values, and then its own in an overlay of its own; p is not changed) with -j worker processes and writes one CSV to out
 * (or one file per run under o->out_dir; with h5 not NULL, an HDF5 file at o->output, which
 * h5 describes, but on csfvm-mpi's quiet ranks, whose variants' rows go to rank 0 as doubles), a failing variant's diagnostics
 * to err with its run number. Returns the exit status: 0, 1 when a variant
 * failed (its rows up to the failure are written), 2 on bad options or an
 * output error.
 */
int csf_sweep_main(const csf_prog *p, csf_exec_fn exec, const csf_opts *o, const char *prog, const csf_h5_origin *h5,
                   FILE *out, FILE *err);





/*
 * -o RUN.h5 (h5.c): the rows of a run of p in a new HDF5 file at path, its
 * layout described in h5.c and csfvm(1); the root's attributes from o, model
 * (the source's name) and the command line. NULL with the reason in err
 * ("cannot create PATH: ...") when the file cannot be made. csf_h5_row is
 * a csf_sink's row function (ctx: the csf_h5): it keeps the rows and writes
 * them a block at a time; -1 (errno set) when a write failed, and every
 * row after is refused. csf_h5_close writes the rows kept and closes the
 * file, which then holds every row given before a failed write; it frees
 * h and returns 0, or -1 (errno set) for a failure the rows did not
 * already report.
 */
typedef struct csf_h5 csf_h5;
csf_h5 *csf_h5_create(const char *path, const csf_prog *p, const csf_opts *o, const char *model, int argc, char **argv,
                      char *err, size_t errlen);
int csf_h5_row(void *h, const double *v, size_t n);
int csf_h5_close(csf_h5 *h);
/*
 * --sweep ... -o RUN.h5 (h5.c): a new HDF5 file at path for the rows of the
 * nvariants variants of a sweep of p, its layout described in h5.c and
 * csfvm(1): a run's datasets with a leading axis of variants, and the
 * values of the npar swept parameters, named by heads as the sweep's CSV
 * header names them ("v0 [m/s]"). NULL with the reason in err, as
 * csf_h5_create. csf_h5_sweep_variant takes variant i's result, i the
 * next in order from 0: its swept values par[npar], its exit status
 * (-1: never run), and its nrows rows of p->ncols + 1 doubles each (rows:
 * their bytes in the machine's order, at any alignment); it writes them a
 * block of variants at a time, and returns 0, or -1 (errno set) when a
 * write failed (every variant after is refused). csf_h5_close writes the
 * variants kept and closes the file, as for a run.
 */
csf_h5 *csf_h5_sweep_create(const char *path, const csf_prog *p, const csf_opts *o, const char *model, int argc,
                            char **argv, size_t nvariants, int npar, const char *const *heads, char *err, size_t errlen);
int csf_h5_sweep_variant(csf_h5 *h, size_t i, const double *par, int status, const void *rows, size_t nrows);
/*
 * --dump FILE.h5: the rows of a file of csf_h5_create on out as the run's CSV, byte for byte (of
 * csf_h5_sweep_create: the sweep's CSV); an exit status.
 */
int csf_h5_dump(const char *path, FILE *out, FILE *err, const char *prog);

/*
 * csfvm --compare-methods: runs p with a range of methods and tolerances,
 * compares each run's output with the most accurate run's, and prints a
 * table (method, tolerance, seconds, steps, evaluations, largest
 * difference) to out. Every run starts from p's initial memory with init
 * (-D's values; NULL: none) over it. Returns an exit status.
 */
int csf_compare_methods(const csf_prog *p, csf_exec_fn exec, const csf_overlay *init, FILE *out, FILE *err);

/*
 * Reads all of path (- : standard input) into a malloc'd buffer (the caller frees it) with one
 * spare byte after the *len bytes read. Returns NULL with errno set on failure. (file.c)
 */
unsigned char *csf_read_file(const char *path, size_t *len);

/*
 * The unit table (units.c), defined once for the compiler and the runtime:
 * name, factor to SI, exponents of length, mass, time and current, whether
 * the SI prefixes (csf_unit_find) apply to the name, and the factor's
 * source. A unit that takes prefixes has the factor 10^decade exactly
 * (1, or 1e-3 for the gram). Ends with a NULL name.
 */
typedef struct csf_unit {
	const char *name;
	double factor;
	signed char dim[CSF_NDIM];
	unsigned char prefixes;
	signed char decade;
	const char *source;
} csf_unit;
extern const csf_unit csf_unit_table[];
/*
 * The unit named by the len bytes at name: a name of the table, or an SI
 * prefix (f p n u m c k M G T) and a name that takes prefixes (`kV`, `uC`,
 * `ns`), whose factor is the power of ten as the literal 1eN reads.
 * Returns 1 and fills *u (name and source NULL for a prefixed name), or 0.
 */
int csf_unit_find(const char *name, size_t len, csf_unit *u);
/* Does a unit expression start at s: a unit name, '(' and one, or `1/` (`1/s`, as CSF prints one)? */
int csf_unit_starts(const char *s);
/*
 * Parses a unit expression at s (`m/s^2`, `kg*m/(s^2)`, `g/cm^3`, `1/s`):
 * its factor and dimension into *u, *end past it. Returns 0, or -1 with
 * *why set to the reason.
 */
int csf_unit_parse(const char *s, const char **end, csf_unit *u, const char **why);
/* Converts si, a value of dimension d in SI, to the unit system whose units are base (in SI). */
double csf_units_to_system(double si, const double d[CSF_NDIM], const double base[CSF_NDIM]);

/*
 * The candidate nearest to name (of 3 letters or more), within 2 edits, or
 * the symbol it begins with ("velocity": "v"); NULL if none. For the
 * suggestions "did you mean 'NAME'?" of csfc and of -D.
 */
const char *csf_suggest_name(const char *name, const char *const *cands, int n);


/*
 * csf_parse_opts with its --help and --version text to out and its usage
 * errors to err (csf_parse_opts: stdout and stderr; the embedding API
 * keeps both in the run's diagnostics).
 */
int csf_parse_opts_to(int argc, char **argv, int first, csf_opts *o, int *pos, int npos, int *npos_out,
                      const char *usage, FILE *out, FILE *err);

/*
 * The index of p's last output row, kmax: the rows are t_k = k*by for k = 0 .. kmax, the
 * last k with k*by <= till allowing for till/by's rounding (run.c). A run writes at most
 * kmax + 1 rows.
 */
double csf_run_kmax(const csf_prog *p);

/* Name of the i-th available ODE method (the default is 0), NULL past the last. */
const char *csf_method_name(size_t i);

/*
 * Checkpoints (checkpoint.c): a run's state as named parts. Each module
 * describes its state once as csf_keep calls, which write the parts (a
 * keeper from csf_keep_write) or read them back (csf_keep_read's).
 * csf_keep: 0, or -1 (a write failed; reading: no part name of n bytes,
 * the reason for csf_keep_why). csf_kept: the size of part name when
 * reading, else -1. csf_keep_commit writes the end, flushes the file to
 * the disk, renames it over path and frees k: 0, or -1 with the reason
 * in err (the previous checkpoint stays whole).
 */
typedef struct csf_keeper csf_keeper;
int csf_keep(csf_keeper *k, const char *name, void *p, size_t n);
long csf_kept(const csf_keeper *k, const char *name);
int csf_keep_reading(const csf_keeper *k);
csf_keeper *csf_keep_write(const char *path, char *err, size_t errlen);
int csf_keep_commit(csf_keeper *k, const char *path, char *err, size_t errlen);
csf_keeper *csf_keep_read(const char *path, char *err, size_t errlen);
const char *csf_keep_why(const csf_keeper *k);
void csf_keep_free(csf_keeper *k);
/* The options a checkpoint holds a resumed run to: those that change the rows, and a sweep's (len: CSF_KEEP_OPTS). */
enum { CSF_KEEP_OPTS = 2048 };
void csf_keep_options(const csf_opts *o, char *buf, size_t len);
/* A checkpoint's head: the bytecode's hash, the options (optlen bytes), the output's length (-1: unknown). */
int csf_keep_header(csf_keeper *k, unsigned long long *hash, char *opts, size_t optlen, long long *off);
/* Reading: the head checked against this run's hash and opts (0), or -1 with the reason in err; *off. */
int csf_keep_check(csf_keeper *k, const char *path, unsigned long long hash, const char *opts, size_t optlen,
                   long long *off, char *err, size_t errlen);
/* --resume: out (a regular file; else nothing is done) cut back to off bytes: 0, or -1 with the reason in err. */
int csf_keep_output(FILE *out, long long off, const char *path, char *err, size_t errlen);
/* The length of out after its rows are flushed (-1: not a file, or the flush failed). */
long long csf_keep_offset(FILE *out);
/* Saves or restores the variable x under its own expression's name. */
#define CSF_KEEP(k, x) csf_keep((k), #x, &(x), sizeof(x))
/* The FNV-1a hash of n bytes (a checkpoint's and a record's name of the bytecode). */
uint64_t csf_hash_bytes(const unsigned char *b, size_t n);
/* The state of the contacts and of the constraints, for a checkpoint (broad.c, constraint.c). */
int csf_contacts_keep(csf_contacts *c, csf_keeper *k);
int csf_cons_keep(csf_cons *cs, csf_keeper *k);

/*
 * The run record (record.c): its fields, in order, each a string, a number
 * or a list of strings; written as JSON (--record) and as HDF5 attributes
 * of the same names (csf_h5_record).
 */
enum { CSF_RF_STR, CSF_RF_NUM, CSF_RF_STRS };
enum { CSF_RECORD_MAX = 40 };
typedef struct csf_rfield {
	const char *name;
	int kind;
	const char *s;
	double x;
	const char *const *v;
	int nv;
} csf_rfield;
typedef struct csf_record {
	csf_rfield f[CSF_RECORD_MAX];
	int n;
	char hash[24], start[32], end[32], host[256];
	char *cmd; /* the command line (owned) */
} csf_record;
/* The record of a run of p with options o (and what csf_run filled in), from source, by the command line argv,
   from start to end, that ended with exit status; its strings are o's, argv's and its own (csf_record_free). */
void csf_record_make(csf_record *rec, const csf_prog *p, const csf_opts *o, const char *source, int argc, char **argv,
                     time_t start, time_t end, int status);
void csf_record_free(csf_record *rec);
/* The record as a JSON object to path (- : stderr): 0, or -1 with the reason in err. */
int csf_record_json(const csf_record *rec, const char *path, char *err, size_t errlen);
/* The record's fields as root attributes of h (replacing those of the same names): 0, or -1. */
int csf_h5_record(csf_h5 *h, const csf_record *rec);
/* The command line as a shell reads it (malloc'd; NULL when memory runs out). */
char *csf_command_line(int argc, char **argv);

/*
 * --estimate-error, --accuracy A (estimate.c): csf_run_sink of p with o,
 * and the estimate of its global error against a run 100 times tighter,
 * on err (and in o->err_*); with o->accuracy, at the tolerance that meets
 * it. The exit status (1 when the accuracy cannot be met).
 */
int csf_estimate_run(const csf_prog *p, csf_exec_fn exec, csf_opts *o, FILE *out, const csf_sink *fwd, FILE *err);

#endif
