/*
 * run_int.h - what the files of runtime/run share (not installed): the
 * run's state, the stability guard's and --method auto's, and the functions
 * one file calls in another. The run reads top-down: options.c, signals.c,
 * progress.c, fmt.c; eval.c (the model for the integrators); report.c and
 * output.c; events.c, guard.c, advance.c; run.c (csf_run).
 */
#ifndef CSF_RUN_INT_H
#define CSF_RUN_INT_H

#include <signal.h>
#include <stdio.h>
#include <time.h>

#include "csf_int.h"
#include "ode.h"
#include "spectrum.h"

typedef struct run {
	const csf_prog *p;
	uint32_t *row_y; /* the state components the rows need (csf_run_row_state), or NULL: all */
	size_t nrow_y;
	csf_exec_fn exec;
	double *m;
	double fail_t; /* time of a non-finite derivative */
	int fail;
	/* contact forces that could not be solved at a trial state of the step being taken
	   (csf_run_rhs_trial), and the time of the first */
	int trial_unsolved;
	double trial_unsolved_t;
	unsigned long nrhs, njac; /* evaluations, for --stats */
	unsigned long max_rhs;    /* csf_opts.max_rhs: past it, ADV_BUDGET (0: no limit) */
	unsigned long nevents;
	long last; /* the guard of the last event */
	uint32_t last_src; /* its rule's statement */
	uint32_t last_oi, last_oj; /* a contact's: its objects, as the event found them (the candidates that
	                              follow are chosen again, and the guard's number names another pair) */
	int pending; /* it was located at an output time and happens after that row */
	double last_h; /* the last step's length */
	double zeno, tol; /* for csf_contact_settle */
	int dense;        /* the method's continuous extension gives the rows (advance_dense) */
	double ti, tend;  /* dense: the integrator's time (at or past the last row), the last output time */
	double *yi;       /* dense: the integrator's state at ti */
	/* events: guards (conditional rules' comparisons, then two per candidate contact), ng of them
	   (room for capg), and work vectors */
	uint32_t ng;
	size_t capg;
	double *ga, *gb, *gs, *gh, *gt, *gl, *ya, *fa, *fb, *ys, *fs, *ye;
	double *gp;       /* the guards at the sample before the first where one is negative */
	double *gx;       /* the exact guards at the lower end of locate's bracket */
	double *yk, *gk;  /* the state and guards at the upper end of locate's bracket, as they were found */
	uint32_t *order;  /* the guards negative there, by their crossings' estimates */
	double *est;      /* those estimates, as fractions of the bracket */
	double *jw; /* with contacts: 3 work vectors for the Jacobian by differences */
	double *yh; /* with contacts: the 3 interpolated states of a step, one after the other */
	csf_contacts *cs; /* with contacts: the candidate pairs (runtime/contact/) */
	csf_exec_ctx x;   /* what exec passes on to the code: cs, cons */
	csf_cons *cons;   /* with constraints: their work arrays and modes (runtime/constraint/) */
	double *cw, *cy;  /* with constraints: a derivative and a state to work in (constrain.c) */
	uint32_t con_k;   /* a constraint that failed (STOP_CON_START, STOP_CON_CONFLICT) */
	double con_off;   /* by how much */
	int conflict;     /* the constraints contradict each other (csf_cons_failed), or an impact broke one */
	int con_impact;   /* an impact broke constraint con_k (by con_off of its rate's terms) */
	uint32_t ncg;     /* the constraints' guards: one a constraint when one of them is one-sided, else none */
	uint32_t gcont;   /* the first contact guard: after the comparisons' and the constraints' */
	unsigned long nchoices, ncand, maxcand; /* for --stats: the choices of candidates, their sum and largest */
	int nomem; /* memory ran out */
	int unsettled;     /* why the contacts stopped the run: CSF_SETTLE_ENDLESS, _IMPULSES, _FORCES (csf.h) */
	double unsettled_t;
	double stop_t; /* a 'stop when' condition ended the run at stop_t: the statement stop_src's */
	uint32_t stop_src;
	int stopped;
	unsigned long nfired; /* `when` blocks fired (csf_run_whens), for --stats */
	uint32_t cycle[2];    /* ADV_WHEN_CYCLE: the first two blocks (indices into p->whens) that fired in its last rounds */
	int ncycle;
	int wround;           /* the rounds in which blocks fired at the instant of the event being taken */
	/* --rows-at-events: writes the row of the state y at an event at t, mark -1 (before it) or 1 (after); NULL: none */
	void (*event_row)(struct run *r, double t, const double *y, double mark);
	void *event_ctx;
	struct guard *g; /* the stability guard, or NULL */
	csf_ode *ode;     /* the method taking the steps (with --method auto, one of au->m) */
	int own;          /* the integrator has its own time and state (ti, yi), apart from the rows' */
	struct autom *au; /* --method auto, or NULL */
	FILE *err;
	double crowd_t;        /* the time of the first of the events counted in crowd_n (advance.c's crowd) */
	unsigned long crowd_n; /* the events since; whether their crowding was warned of */
	int crowd_warned;
	int prog, shown;  /* the progress line: drawn, and on the screen now */
	struct timespec start, drawn; /* when the run started, and the line was last drawn */
	unsigned long rows; /* rows written */
	int row_end;        /* a signal ends the run at the next row, not within a step (--checkpoint: one there) */
} run;

/*
 * What an advance returns (advance.c): one of csf_ode_step's statuses
 * (CSF_ODE_OK, _STOPPED, _FAILED, _HALTED: ode.h), or one of the run's own:
 * modes switch back and forth at one instant (ADV_CHATTER); more than
 * MAX_WORK steps (and events) in one output interval (ADV_TOO_MUCH), a run
 * that cannot get on, halted instead of hanging; a 'stop when' condition
 * became true (ADV_TERMINAL, at r->stop_t); more right-hand side
 * evaluations than r->max_rhs (ADV_BUDGET); `when` blocks that set each
 * other off at one instant without end (ADV_WHEN_CYCLE, csf_run_whens).
 * csf_run turns it into a stop.
 */
enum adv_status { ADV_CHATTER = CSF_ODE_HALTED + 1, ADV_TOO_MUCH, ADV_TERMINAL, ADV_BUDGET, ADV_WHEN_CYCLE };
/* The rounds of `when` blocks that fire at one instant, each set off by the one before, past which they are a cycle. */
enum { WHEN_ROUNDS = 100 };
enum { MAX_WORK = 1000000 };

/*
 * Why csf_run ended: one kind for each message, each with its exit status
 * (report_stop, report.c). The first three write no message.
 */
typedef enum stop_kind {
	STOP_END,          /* the last row, or a 'stop when' condition's, or a failed write: 0 (finish) */
	STOP_SIGNAL,       /* SIGINT or SIGTERM, after the last whole row: 128 + the signal */
	STOP_HALTED,       /* the stability guard halted a fixed step and said why: 1 */
	STOP_NOMEM,        /* memory ran out: 2 */
	STOP_SETUP,        /* the method could not be set up (msg): 2 */
	STOP_NO_CONTACTS,  /* the method cannot run contacts (method): 2 */
	STOP_BAD_MASS,     /* body which, in contact, has no positive mass: 1 */
	STOP_UNSETTLED,    /* contacts that could not be settled (r->unsettled, r->unsettled_t): 1 */
	STOP_NONFINITE,    /* a state derivative that is not finite at t: 1 */
	STOP_NONFINITE_ROW,/* a watched or state value that is not finite at the row at t: 1 */
	STOP_ASSERT,       /* assertion which failed at the row at t: 1 */
	STOP_TOO_MUCH,     /* ADV_TOO_MUCH at t, since the row at t_row (hs: the largest stable step, or INFINITY): 1 */
	STOP_CHATTER,      /* ADV_CHATTER at t (msg; the event r->last): 1 */
	STOP_FAILED,       /* the integration failed at t (msg): 1 */
	STOP_BUDGET,       /* ADV_BUDGET at t: 1 */
	STOP_CON_START,    /* the initial positions break constraint r->con_k by r->con_off: 1 */
	STOP_CON_CONFLICT, /* constraints that contradict each other at t (r->con_k, r->con_off): 1 */
	STOP_WHEN_CYCLE,   /* ADV_WHEN_CYCLE at t (r->cycle): 1 */
} stop_kind;

typedef struct stop {
	stop_kind kind;
	double t;           /* when */
	double t_row, hs;   /* STOP_TOO_MUCH */
	long which;         /* STOP_ASSERT: the assertion; STOP_BAD_MASS: the body (p->cbodies) */
	int events;         /* STOP_TOO_MUCH: the scene has events */
	const char *method; /* STOP_NO_CONTACTS */
	const char *msg;    /* STOP_SETUP, STOP_CHATTER, STOP_FAILED: the integrator's words */
} stop;

/* The default of --checkpoint-every: a checkpoint a minute (seconds of wall time). */
#define CSF_CHECKPOINT_EVERY 60.0

/* A look costs at most 1 / LOOK_EVERY of the evaluations before it (but for those a fixed step needs). */
enum { LOOK_EVERY = 100 };

/*
 * --method auto (the default): dop853 while its steps are held by its
 * accuracy. When a look of the guard, with a thousand steps or more to go,
 * finds them held by its stability, as the stiffness warning would (steps
 * at 0.8 of the largest stable step or more, a stiffness ratio of 100 or
 * more, or a second look that agrees), or about to be (steps at AUTO_NEAR
 * of it or more, the dominant eigenvalue nearer the negative real axis
 * than the imaginary one, a decaying mode, and a stiffness ratio of 1000
 * or more: the accuracy-held steps of Oregonator's and HIRES's starts,
 * which cost dop853 4 and 1.3 times what the whole run costs bsimp), the
 * next step is taken by AUTO_STIFF, implicit. Back to dop853 when two looks
 * in a row find the implicit method's own step (the one its error control
 * proposes) shorter than dop853's largest stable step, as in a fast
 * transient or once the fast modes are gone. The gap between the
 * thresholds and the second look are the hysteresis that keeps switches
 * few, as LSODA's. bsimp, not msbdf: on the four reference problems
 * (bench/stiff.sh) it takes 1.5 to 2.1 times msbdf's evaluations, but
 * restarts without a history to rebuild (every switch and every event
 * restarts) and reaches Robertson's kinetics at 1e11 s within 1e-10
 * relatively, where msbdf at its default tolerance is 7 % off.
 */
#define AUTO_STIFF "bsimp"
#define AUTO_NEAR 0.05
/*
 * bsimp works on the dense n-by-n Jacobian: n^2 memory and some n^3/3
 * operations a step for its LU decompositions. Past AUTO_MAX_N state
 * variables auto is dop853 alone, which warns of stiffness as when named.
 */
enum { AUTO_MAX_N = 200 };
enum { AUTO_SHOWN = 8 }; /* the switches --stats lists */

typedef struct autom {
	csf_ode *m[2];              /* dop853 and AUTO_STIFF */
	int cur;                    /* the one that takes the steps */
	int want;                   /* the guard asks for the other from the next step on */
	int soft;                   /* looks in a row (implicit) that found the stiffness passed */
	int failed;                 /* the implicit method failed (csf_run_advance_dense): dop853 on */
	unsigned long n;            /* switches */
	double at[AUTO_SHOWN];      /* the first ones' times (to m[1], m[0], m[1], ...: they alternate) */
} autom;

typedef struct guard {
	csf_spectrum *sp;
	FILE *err;
	double *y, *f0, *yd, *fd; /* the state looked at, f there; with differences, a state along v and f there */
	double t;
	int exact;                 /* J v from the JAC section, not by differences */
	int check_step;            /* a fixed step of an explicit method: halt past the limit */
	int auto_step;             /* verlet's own step (no --step), from the tolerance and the time scale */
	double vfrac;              /* verlet: sqrt(tol / 1e-4) */
	double user_step;          /* --step */
	int detect_stiff;          /* an explicit adaptive method: warn when stability holds its steps */
	int fixed;                 /* fixed steps */
	int stats;
	int due;                   /* look after the next step (an event happened) */
	int stiff_hits;
	double h;                  /* the fixed step (the longest a row's interval is cut into) */
	double span;               /* the run's length */
	double smin;               /* fixed steps: the method's least limit of h |lambda| on the two axes */
	unsigned long nexact;      /* J v products by the JAC section */
	double next;               /* look when guard_evals reaches this */
	unsigned long next_step;   /* fixed steps: look after this many */
	unsigned long steps, checks;
	double seconds;
	/* what it saw */
	csf_eigs last, at_max; /* the last look's eigenvalues, and those of the largest rho */
	double rho_max, ratio, ratio_rho, hrho, hlim_rho; /* fixed: the largest h / largest stable step, at rho */
	int ratio_exact, have_ratio;
	double auto_ratio;         /* auto: the largest ratio of the looks that decide (not --stats's) */
	double aside;              /* the evaluations of --stats's own ratios, left out of the schedule of looks */
	int warned; /* of stiffness */
	int warned_short; /* of steps far shorter than the scene's time scale */
	double hcap;      /* the least cap on a step: by, or --hmax (warn_short: steps far below it) */
	/* absolute tolerances raised to the rounding of the derivatives (rounding_floors) */
	int floor_looks;          /* looks that raised some */
	unsigned long floor_n;    /* components raised */
	long floor_i;             /* the first look's limiting component, and its new tolerance, at floor_t */
	double floor_atol, floor_t;
} guard;

typedef struct watch_ctx { run *r; csf_ode *ode; } watch_ctx;

/* guard.c: the name of state component i (NAME.PROP.x, a global's name), or "" */
void csf_run_state_name(const csf_prog *p, long i, char *buf, size_t len);

/* progress.c */
double csf_run_seconds(struct timespec a, struct timespec b);
void csf_run_progress(run *r, double t);
void csf_run_progress_off(run *r);

/* fmt.c */
/* csf_fmt_double's text and its NUL at dst, which has room for 32 bytes (all may be written): its length (24 at most) */
int csf_fmt_put(char *dst, double x);
double csf_run_round_down(double x);
void csf_run_fmt_ratio(char buf[32], double x);

/* eval.c */
int csf_run_rhs(double t, const double *y, double *dydt, void *ctx);
int csf_run_rhs_trial(double t, const double *y, double *dydt, void *ctx);

/*
 * The state components the rows need, ascending, their number in *n: those
 * the OUT section reads (an operand relative to a loop index: all that it
 * reaches) and the watched columns that are state. NULL when that is every
 * one, or when the section runs the contact routine or the constraints
 * (which read the whole state), or memory ran out: the rows need all.
 */
uint32_t *csf_run_row_state(const csf_prog *p, size_t *n);
int csf_run_jac(double t, const double *y, double *dfdy, double *dfdt, void *ctx);

/* report.c */
void csf_run_report_nonfinite(const csf_prog *p, int sec, const double *m, double t, const char *what, int fixed, FILE *err);
void csf_run_report_event_src(const csf_prog *p, uint32_t src, FILE *err);
void csf_run_report_unsettled(const run *r, FILE *err);
int csf_run_report_stop(run *r, const stop *s, int fixed, FILE *err);

/* signals.c: for the row thread */
/* Has the watchdog fired while a row thread was writing? */
int csf_watchdog_overdue(void);
/* Flushes out and ends the process as the watchdog does (128 + the signal). */
void csf_watchdog_exit(void);
/* f (NULL: none) is called by the watchdog's handler instead of ending the process (async-signal-safe). */
void csf_watchdog_wakes(void (*f)(void));

/* rowthread.c: wide rows formatted and written by a second thread */
typedef struct csf_rowthread csf_rowthread;
/* A thread writing p's rows to out (after the header), or NULL where rows are written as they come:
 * fewer than 64 columns, out a terminal or a stream with no descriptor (open_memstream's: a sweep's
 * variant, an embedder's), one processor, CSF_ROW_THREAD=0 in the environment. */
csf_rowthread *csf_rowthread_start(const csf_prog *p, FILE *out);
/* Hands over the row of memory m at t: 0, or -1 (errno set) after an earlier row failed to be written. */
int csf_rowthread_put(csf_rowthread *q, const double *m, double t);
/* Writes every row handed over, ends the thread: its write error (errno), or 0. out is not flushed. */
int csf_rowthread_stop(csf_rowthread *q);

/* output.c */
int csf_run_write_row(const csf_prog *p, const double *m, double t, FILE *out);
int csf_run_finish(FILE *out, FILE *err, int status, int werr);
void csf_run_write_header(const csf_prog *p, FILE *out);

/* events.c */
int csf_run_guards_at(run *r, double t, const double *y, double *g);
void csf_run_free_modes(run *r, double t, const double *y);
int csf_run_room_for_guards(run *r, size_t ng);
int csf_run_update_modes(run *r, double t, double *y, FILE *warn);
/*
 * The `when` blocks at an event at (t, y): the EVT section on the values of
 * an RHS evaluation there (with the modes as they are), and again after
 * each round in which a block fired (the new values can set another off);
 * *fired: whether one did. y takes the state variables they set. 0;
 * CSF_ODE_STOPPED if a derivative was not finite; ADV_WHEN_CYCLE (r->cycle)
 * when blocks fire in WHEN_ROUNDS rounds (r->wround counts them; the
 * caller sets it to 0 at each event). At t = 0 (every prev -1)
 * none fires: it records the conditions.
 */
int csf_run_whens(run *r, double t, double *y, int *fired);
double csf_run_location_tol(const csf_prog *p);
int csf_run_interp(run *r, csf_ode *ode, double ta, double tb, const double *yb, double s, double *out);
int csf_run_step_events(run *r, csf_ode *ode, double ta, double tb, const double *y, double *te, long *which, char *msg,
                size_t msglen);

/* constrain.c */
/* After the contacts' impulses at (t, y): nonzero (r->conflict, r->con_impact) if they broke a
   constraint's rate by more than 1e-6 of its terms: impulses are not solved together with constraints. */
int csf_run_cons_impact(run *r, double t, double *y);
/* The modes of the one-sided constraints at (t, y): taut (with an impulse) or slack. Nonzero if an
   evaluation failed or they do not come to rest (r->conflict). */
int csf_run_cons_modes(run *r, double t, double *y);
/* At t = 0: 0, or 1 (positions off a constraint: r->con_k, r->con_off), or -1 (an evaluation failed).
   Projects y's velocities onto the constraints, with a warning on err when they were off. */
int csf_run_cons_start(run *r, double *y, FILE *err);
/* After a step to (t, y): projects y back if it drifted, and restarts ode. Nonzero if an evaluation failed. */
int csf_run_cons_step(run *r, csf_ode *ode, double t, double *y);
/* A row's state y at t onto the constraints (to rounding). Nonzero if an evaluation failed. */
int csf_run_cons_row(run *r, double t, double *y);

/* guard.c */
double csf_run_stable_step(run *r, csf_ode *ode, const csf_eigs *e);
const char *csf_run_eig_kind(const csf_eigs *e);
int csf_run_guard_check(run *r, csf_ode *ode, double t, const double *y, double h);
int csf_run_step_watch(void *ctx, double t, const double *y, double h);

/* advance.c */
void csf_run_stop_now(run *r, double t);
int csf_run_take_event(run *r, csf_ode *ode, double t, double *y);
int csf_run_advance_plain(run *r, csf_ode *ode, double *t, double t1, double *y, char *msg, size_t msglen);
int csf_run_advance_events(run *r, csf_ode *ode, double *t, double t1, int fixed, double h, double *y, char *msg,
                   size_t msglen);
int csf_run_advance_dense(run *r, double tk, double *y, char *msg, size_t msglen);

#endif
