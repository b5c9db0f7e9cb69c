/*
 * dop853.c - Hairer's DOP853 (Dormand-Prince 8(5,3), with its 7th-order
 * continuous extension) as a GSL odeiv2 step type.
 *
 * A step takes 12 stages k0..k11 (k0 = f(t, y0) may come in as dydt_in),
 * y1 = y0 + h sum b_j k_j with b = row 12 of a, and k12 = f(t + h, y1),
 * which is the exact dydt_out, a stage of the continuous extension and the
 * next step's k0 (first same as last: GSL's evolve, which would evaluate a
 * dydt_in for every step, is told the method takes none; a step from where
 * the last ended reuses k12, and a step tried again from the same start
 * its k0). So a step costs 12 evaluations, 11 after a rejected one.
 * The error estimate is the one of dop853.f: err5 (the 8th- minus the
 * 5th-order solution) and err3 (the 8th- minus a 3rd-order solution), in
 * the weighted RMS norm, make err = err5^2 / sqrt(err5^2 + 0.01 err3^2),
 * which behaves like h^8; GSL's control sees it as yerr = err5 scaled by
 * err / |err5|, so that its per-component test on yerr follows Hairer's.
 *
 * The dense output needs 3 more stages k13..k15, evaluated on request
 * (csf_erk_dense_prepare) only, since most steps are never
 * interpolated. The stepping, first same as last and the extension are
 * erk.c's, shared with dopri5.c; this file has the tables and the error
 * estimate. The extension is Hairer's
 *   y(t0 + s h) = y0 + s (F0 + s' (F1 + s (F2 + s' (F3 + s (F4 + s' (F5 + s F6))))))
 * with s' = 1 - s, F0 = y1 - y0, F1 = h k0 - F0, F2 = F0 - h k12 - F1 and
 * F3..F6 = h sum_j d_rj k_j.
 *
 * Coefficients: the published values of Hairer's dop853.f, as tabulated in
 * SciPy's scipy/integrate/_ivp/dop853_coefficients.py (a[i][j], c[i] for
 * the 12 stages, the end stage 12 and the dense stages 13..15; e5, the
 * weights of err5; bhh, the 3rd-order weights; d, the dense output).
 *
 * Every sum runs over its stages in ascending order, skipping zero
 * coefficients, so that results do not depend on the compiler (the project
 * builds with -ffp-contract=off).
 */
#include <float.h>
#include <math.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "csf_ops.h"
#include "dop853.h"
#include "erk.h"

enum {
	NSTAGE = 12, /* stages of a step: k0..k11 */
	NK = 16,     /* with the dense stages k13..k15 */
};

static const double a[NK][NK] = {
	[1] = {
		[0] = 5.26001519587677318785587544488e-2,
	},
	[2] = {
		[0] = 1.97250569845378994544595329183e-2, [1] = 5.91751709536136983633785987549e-2,
	},
	[3] = {
		[0] = 2.95875854768068491816892993775e-2, [2] = 8.87627564304205475450678981324e-2,
	},
	[4] = {
		[0] = 2.41365134159266685502369798665e-1, [2] = -8.84549479328286085344864962717e-1,
		[3] = 9.24834003261792003115737966543e-1,
	},
	[5] = {
		[0] = 3.7037037037037037037037037037e-2, [3] = 1.70828608729473871279604482173e-1,
		[4] = 1.25467687566822425016691814123e-1,
	},
	[6] = {
		[0] = 3.7109375e-2, [3] = 1.70252211019544039314978060272e-1,
		[4] = 6.02165389804559606850219397283e-2, [5] = -1.7578125e-2,
	},
	[7] = {
		[0] = 3.70920001185047927108779319836e-2, [3] = 1.70383925712239993810214054705e-1,
		[4] = 1.07262030446373284651809199168e-1, [5] = -1.53194377486244017527936158236e-2,
		[6] = 8.27378916381402288758473766002e-3,
	},
	[8] = {
		[0] = 6.24110958716075717114429577812e-1, [3] = -3.36089262944694129406857109825,
		[4] = -8.68219346841726006818189891453e-1, [5] = 2.75920996994467083049415600797e1,
		[6] = 2.01540675504778934086186788979e1, [7] = -4.34898841810699588477366255144e1,
	},
	[9] = {
		[0] = 4.77662536438264365890433908527e-1, [3] = -2.48811461997166764192642586468,
		[4] = -5.90290826836842996371446475743e-1, [5] = 2.12300514481811942347288949897e1,
		[6] = 1.52792336328824235832596922938e1, [7] = -3.32882109689848629194453265587e1,
		[8] = -2.03312017085086261358222928593e-2,
	},
	[10] = {
		[0] = -9.3714243008598732571704021658e-1, [3] = 5.18637242884406370830023853209,
		[4] = 1.09143734899672957818500254654, [5] = -8.14978701074692612513997267357,
		[6] = -1.85200656599969598641566180701e1, [7] = 2.27394870993505042818970056734e1,
		[8] = 2.49360555267965238987089396762, [9] = -3.0467644718982195003823669022,
	},
	[11] = {
		[0] = 2.27331014751653820792359768449, [3] = -1.05344954667372501984066689879e1,
		[4] = -2.00087205822486249909675718444, [5] = -1.79589318631187989172765950534e1,
		[6] = 2.79488845294199600508499808837e1, [7] = -2.85899827713502369474065508674,
		[8] = -8.87285693353062954433549289258, [9] = 1.23605671757943030647266201528e1,
		[10] = 6.43392746015763530355970484046e-1,
	},
	[12] = {
		[0] = 5.42937341165687622380535766363e-2, [5] = 4.45031289275240888144113950566,
		[6] = 1.89151789931450038304281599044, [7] = -5.8012039600105847814672114227,
		[8] = 3.1116436695781989440891606237e-1, [9] = -1.52160949662516078556178806805e-1,
		[10] = 2.01365400804030348374776537501e-1, [11] = 4.47106157277725905176885569043e-2,
	},
	[13] = {
		[0] = 5.61675022830479523392909219681e-2, [6] = 2.53500210216624811088794765333e-1,
		[7] = -2.46239037470802489917441475441e-1, [8] = -1.24191423263816360469010140626e-1,
		[9] = 1.5329179827876569731206322685e-1, [10] = 8.20105229563468988491666602057e-3,
		[11] = 7.56789766054569976138603589584e-3, [12] = -8.298e-3,
	},
	[14] = {
		[0] = 3.18346481635021405060768473261e-2, [5] = 2.83009096723667755288322961402e-2,
		[6] = 5.35419883074385676223797384372e-2, [7] = -5.49237485713909884646569340306e-2,
		[10] = -1.08347328697249322858509316994e-4, [11] = 3.82571090835658412954920192323e-4,
		[12] = -3.40465008687404560802977114492e-4, [13] = 1.41312443674632500278074618366e-1,
	},
	[15] = {
		[0] = -4.28896301583791923408573538692e-1, [5] = -4.69762141536116384314449447206,
		[6] = 7.68342119606259904184240953878, [7] = 4.06898981839711007970213554331,
		[8] = 3.56727187455281109270669543021e-1, [12] = -1.39902416515901462129418009734e-3,
		[13] = 2.9475147891527723389556272149, [14] = -9.15095847217987001081870187138,
	},
};

static const double d[4][NK] = {
	{
		[0] = -0.84289382761090128651353491142e1, [5] = 0.56671495351937776962531783590,
		[6] = -0.30689499459498916912797304727e1, [7] = 0.23846676565120698287728149680e1,
		[8] = 0.21170345824450282767155149946e1, [9] = -0.87139158377797299206789907490,
		[10] = 0.22404374302607882758541771650e1, [11] = 0.63157877876946881815570249290,
		[12] = -0.88990336451333310820698117400e-1, [13] = 0.18148505520854727256656404962e2,
		[14] = -0.91946323924783554000451984436e1, [15] = -0.44360363875948939664310572000e1,
	},
	{
		[0] = 0.10427508642579134603413151009e2, [5] = 0.24228349177525818288430175319e3,
		[6] = 0.16520045171727028198505394887e3, [7] = -0.37454675472269020279518312152e3,
		[8] = -0.22113666853125306036270938578e2, [9] = 0.77334326684722638389603898808e1,
		[10] = -0.30674084731089398182061213626e2, [11] = -0.93321305264302278729567221706e1,
		[12] = 0.15697238121770843886131091075e2, [13] = -0.31139403219565177677282850411e2,
		[14] = -0.93529243588444783865713862664e1, [15] = 0.35816841486394083752465898540e2,
	},
	{
		[0] = 0.19985053242002433820987653617e2, [5] = -0.38703730874935176555105901742e3,
		[6] = -0.18917813819516756882830838328e3, [7] = 0.52780815920542364900561016686e3,
		[8] = -0.11573902539959630126141871134e2, [9] = 0.68812326946963000169666922661e1,
		[10] = -0.10006050966910838403183860980e1, [11] = 0.77771377980534432092869265740,
		[12] = -0.27782057523535084065932004339e1, [13] = -0.60196695231264120758267380846e2,
		[14] = 0.84320405506677161018159903784e2, [15] = 0.11992291136182789328035130030e2,
	},
	{
		[0] = -0.25693933462703749003312586129e2, [5] = -0.15418974869023643374053993627e3,
		[6] = -0.23152937917604549567536039109e3, [7] = 0.35763911791061412378285349910e3,
		[8] = 0.93405324183624310003907691704e2, [9] = -0.37458323136451633156875139351e2,
		[10] = 0.10409964950896230045147246184e3, [11] = 0.29840293426660503123344363579e2,
		[12] = -0.43533456590011143754432175058e2, [13] = 0.96324553959188282948394950600e2,
		[14] = -0.39177261675615439165231486172e2, [15] = -0.14972683625798562581422125276e3,
	},
};

static const double c[NK] = {
	[0] = 0.0, [1] = 0.526001519587677318785587544488e-01, [2] = 0.789002279381515978178381316732e-01,
	[3] = 0.118350341907227396726757197510, [4] = 0.281649658092772603273242802490,
	[5] = 0.333333333333333333333333333333, [6] = 0.25, [7] = 0.307692307692307692307692307692,
	[8] = 0.651282051282051282051282051282, [9] = 0.6, [10] = 0.857142857142857142857142857142, [11] = 1.0,
	[12] = 1.0, [13] = 0.1, [14] = 0.2, [15] = 0.777777777777777777777777777778,
};

static const double e5[NSTAGE] = {
	[0] = 0.1312004499419488073250102996e-1, [5] = -0.1225156446376204440720569753e1,
	[6] = -0.4957589496572501915214079952, [7] = 0.1664377182454986536961530415e1,
	[8] = -0.3503288487499736816886487290, [9] = 0.3341791187130174790297318841,
	[10] = 0.8192320648511571246570742613e-1, [11] = -0.2235530786388629525884427845e-1,
};

/* the 3rd-order weights (on k0, k8 and k11) */
static const double bhh0 = 0.244094488188976377952755905512;
static const double bhh8 = 0.733846688281611857341361741547;
static const double bhh11 = 0.220588235294117647058823529412e-1;

/*
 * The factor q = e5 / sqrt(e5^2 + 0.01 e3^2) that turns err5 into Hairer's
 * error, e5 and e3 the weighted norms of err5 and err3. The weights are
 * 1 / (scale_i + max(|y0_i|, |y1_i|)); a component whose weight scale is 0
 * (no absolute scale, and y 0 at both ends) is measured absolutely, not
 * divided by 0. The sums of squares are scaled by their largest term, so
 * that a large error cannot overflow them; the norms' common 1/n cancels.
 */
static double weight_scale(const csf_erk_state *st, size_t i)
{
	double sk = (st->scale ? st->scale[i] : 1.0) + csf_fmax(fabs(st->y0[i]), fabs(st->y1[i]));
	return sk > 0 ? sk : 1.0;
}

/*
 * Hairer's factor sqrt(s5 / (s5 + 0.01 s3)) of the sums of squares of the
 * weighted errors r = |err| / sk, each over their largest m. The first pass
 * keeps r5 in w5 and r3 in err3's place, which the second reads.
 */
static double err_factor(const csf_erk_state *st, const double *err5, double *err3, double *w5)
{
	double m = 0;
	for (size_t i = 0; i < st->dim; i++) {
		double sk = weight_scale(st, i), r5 = fabs(err5[i]) / sk, r3 = fabs(err3[i]) / sk;
		if (!(r5 <= DBL_MAX && r3 <= DBL_MAX)) return 1; /* inf or NaN: yerr = err5, as unusable as the step */
		m = csf_fmax(m, csf_fmax(r5, r3));
		w5[i] = r5, err3[i] = r3;
	}
	if (m == 0) return 0;
	double s5 = 0, s3 = 0;
	for (size_t i = 0; i < st->dim; i++) {
		double r5 = w5[i] / m, r3 = err3[i] / m;
		s5 += r5 * r5;
		s3 += r3 * r3;
	}
	return s5 > 0 ? sqrt(s5 / (s5 + 0.01 * s3)) : 0;
}

/*
 * yerr = h err5 q, with bsum = sum b_j k_j (so that y1 = y0 + h bsum). err3
 * is bsum minus the 3rd-order combination; it goes into ysum's place once
 * bsum has been read. The extension's F0 is work space: a step unsets it.
 */
static void error_estimate(const csf_erk_state *st, double h, double *bsum, double *yerr)
{
	double *err5 = yerr, *err3 = bsum;
	double *const *k = st->k;
	csf_erk_combine(st->dim, e5, NSTAGE, k, err5);
	for (size_t i = 0; i < st->dim; i++) err3[i] = bsum[i] - bhh0 * k[0][i] - bhh8 * k[8][i] - bhh11 * k[11][i];
	double q = err_factor(st, err5, err3, st->f[0]);
	for (size_t i = 0; i < st->dim; i++) yerr[i] = h * (err5[i] * q);
}

static const csf_erk_method dop853 = {
	"dop853", 8, NSTAGE, NK, 4, &a[0][0], c, &d[0][0], error_estimate,
};

static void *dop853_alloc(size_t dim) { return csf_erk_alloc(&dop853, dim); }

static const gsl_odeiv2_step_type dop853_type = {
	"dop853",
	0, /* no dydt_in: GSL's evolve would evaluate it for every step, where k12 of the step before serves */
	1, /* gives exact dydt_out */
	dop853_alloc,
	csf_erk_apply,
	csf_erk_set_driver,
	csf_erk_reset,
	csf_erk_order,
	csf_erk_free,
};

const gsl_odeiv2_step_type *csf_step_dop853 = &dop853_type;
