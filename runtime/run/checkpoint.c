/*
 * checkpoint.c - the file of --checkpoint and --resume: a list of named
 * parts, each the bytes of one array or value the run keeps.
 *
 * The run (run.c) and the modules it owns (the integrator, the contacts,
 * the constraints, the spectrum) each describe their state once, as a
 * sequence of csf_keep calls; the same sequence writes a checkpoint and
 * reads it back, so that what is saved and what is restored cannot differ,
 * and a new array is one more call. The file is
 *
 *     "CSF checkpoint 1\n"
 *     then for each part: u32 length of its name, the name, u64 size, the bytes
 *     and last the part "end" (8 bytes: the number of parts before it)
 *
 * in the machine's byte order (a checkpoint is read back on the machine
 * that wrote it). It is written to FILE.tmp, flushed to the disk, and
 * renamed over FILE, so that a kill at any instant leaves the previous
 * checkpoint whole.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "run_int.h"

static const char magic[] = "CSF checkpoint 1\n";

typedef struct part {
	const char *name;
	const unsigned char *p;
	uint64_t n;
} part;

struct csf_keeper {
	FILE *f;           /* writing: the temporary file */
	unsigned char *buf; /* reading: the file's bytes */
	part *parts;
	size_t nparts;
	uint64_t written;
	int bad;           /* a write failed, or a part was missing or of another size */
	char why[160];     /* reading: the first part that did not fit */
};

int csf_keep(csf_keeper *k, const char *name, void *p, size_t n)
{
	if (k->f) {
		uint32_t len = (uint32_t)strlen(name);
		uint64_t size = n;
		if (fwrite(&len, sizeof len, 1, k->f) != 1 || fwrite(name, 1, len, k->f) != len ||
		    fwrite(&size, sizeof size, 1, k->f) != 1 || (n && fwrite(p, 1, n, k->f) != n))
			k->bad = 1;
		k->written++;
		return k->bad ? -1 : 0;
	}
	for (size_t i = 0; i < k->nparts; i++)
		if (strcmp(k->parts[i].name, name) == 0) {
			if (k->parts[i].n == n) {
				if (n) memcpy(p, k->parts[i].p, n);
				return 0;
			}
			break;
		}
	if (!k->bad)
		snprintf(k->why, sizeof k->why, "its part '%s' is missing or not of %zu bytes", name, n);
	k->bad = 1;
	return -1;
}

long csf_kept(const csf_keeper *k, const char *name)
{
	for (size_t i = 0; !k->f && i < k->nparts; i++)
		if (strcmp(k->parts[i].name, name) == 0) return (long)k->parts[i].n;
	return -1;
}

int csf_keep_reading(const csf_keeper *k) { return k->f == NULL; }

csf_keeper *csf_keep_write(const char *path, char *err, size_t errlen)
{
	size_t n = strlen(path);
	char *tmp = malloc(n + 5);
	csf_keeper *k = calloc(1, sizeof *k);
	if (!tmp || !k) {
		free(tmp);
		free(k);
		snprintf(err, errlen, "out of memory");
		return NULL;
	}
	memcpy(tmp, path, n);
	memcpy(tmp + n, ".tmp", 5);
	k->f = fopen(tmp, "wb");
	free(tmp);
	if (!k->f) {
		snprintf(err, errlen, "cannot write %s.tmp: %s", path, strerror(errno));
		free(k);
		return NULL;
	}
	if (fwrite(magic, 1, sizeof magic - 1, k->f) != sizeof magic - 1) k->bad = 1;
	return k;
}

int csf_keep_commit(csf_keeper *k, const char *path, char *err, size_t errlen)
{
	uint64_t count = k->written;
	csf_keep(k, "end", &count, sizeof count);
	int bad = k->bad || fflush(k->f) != 0 || fsync(fileno(k->f)) != 0;
	int e = errno;
	bad |= fclose(k->f) != 0;
	if (!e) e = errno;
	size_t n = strlen(path);
	char *tmp = malloc(n + 5);
	if (tmp) {
		memcpy(tmp, path, n);
		memcpy(tmp + n, ".tmp", 5);
		if (!bad && rename(tmp, path) != 0) bad = 1, e = errno;
		if (bad) remove(tmp);
	}
	free(tmp);
	free(k);
	if (!bad && tmp) return 0;
	snprintf(err, errlen, "cannot write %s: %s", path, tmp ? strerror(e ? e : EIO) : "out of memory");
	return -1;
}

csf_keeper *csf_keep_read(const char *path, char *err, size_t errlen)
{
	size_t len;
	unsigned char *buf = csf_read_file(path, &len);
	if (!buf) {
		snprintf(err, errlen, "cannot read %s: %s", path, strerror(errno));
		return NULL;
	}
	csf_keeper *k = calloc(1, sizeof *k);
	size_t at = sizeof magic - 1, cap = 0;
	int ended = 0;
	if (!k || len < at || memcmp(buf, magic, at) != 0) {
		snprintf(err, errlen, k ? "%s is not a CSF checkpoint" : "out of memory", path);
		free(buf);
		free(k);
		return NULL;
	}
	k->buf = buf;
	while (!ended && at < len) {
		uint32_t nl;
		uint64_t size;
		if (len - at < sizeof nl) break;
		memcpy(&nl, buf + at, sizeof nl);
		at += sizeof nl;
		if (len - at < (uint64_t)nl + sizeof size) break;
		const unsigned char *name = buf + at;
		at += nl;
		memcpy(&size, buf + at, sizeof size);
		at += sizeof size;
		if (len - at < size) break;
		/* a name is followed by its size's bytes: NUL-terminate it where its first byte was copied from */
		char *s = malloc((size_t)nl + 1);
		if (!s || (k->nparts == cap && !(k->parts = realloc(k->parts, (cap = 2 * cap + 16) * sizeof *k->parts)))) {
			free(s);
			break;
		}
		memcpy(s, name, nl);
		s[nl] = '\0';
		k->parts[k->nparts++] = (part){ s, buf + at, size };
		at += size;
		ended = strcmp(s, "end") == 0;
	}
	if (!ended) {
		snprintf(err, errlen, "%s is cut short or damaged (no end after %zu parts)", path, k->nparts);
		csf_keep_free(k);
		return NULL;
	}
	return k;
}

const char *csf_keep_why(const csf_keeper *k) { return k->why; }

void csf_keep_free(csf_keeper *k)
{
	if (!k) return;
	for (size_t i = 0; i < k->nparts; i++) free((char *)k->parts[i].name);
	free(k->parts);
	free(k->buf);
	free(k);
}

uint64_t csf_hash_bytes(const unsigned char *b, size_t n)
{
	uint64_t h = 14695981039346656037u; /* FNV-1a, 64 bits */
	for (size_t i = 0; i < n; i++) h = (h ^ b[i]) * 1099511628211u;
	return h;
}

void csf_keep_options(const csf_opts *o, char *buf, size_t len)
{
	char v[4][32]; /* each as it reads back to the same double */
	csf_fmt_double(v[0], o->tol), csf_fmt_double(v[1], o->atol), csf_fmt_double(v[2], o->step), csf_fmt_double(v[3], o->hmax);
	int n = snprintf(buf, len, "--method %s --tol %s --atol %s --step %s --hmax %s%s --every %lu",
	                 o->method ? o->method : "auto", v[0], v[1], v[2], v[3], o->fixed ? " --fixed" : "",
	                 o->every > 1 ? o->every : 1);
	for (int i = 0; i < o->ndefs && n > 0 && (size_t)n < len; i++) n += snprintf(buf + n, len - (size_t)n, " -D %s", o->defs[i]);
	for (int i = 0; i < o->nsweeps && n > 0 && (size_t)n < len; i++)
		n += snprintf(buf + n, len - (size_t)n, " --sweep %s", o->sweeps[i]);
	if (o->sweep_file && n > 0 && (size_t)n < len) n += snprintf(buf + n, len - (size_t)n, " --sweep-file %s", o->sweep_file);
	if (o->summary && n > 0 && (size_t)n < len) n += snprintf(buf + n, len - (size_t)n, " --sweep-summary %s", o->summary);
	if (o->sweep_binary && n > 0 && (size_t)n < len) snprintf(buf + n, len - (size_t)n, " --sweep-binary");
}

int csf_keep_header(csf_keeper *k, unsigned long long *hash, char *opts, size_t optlen, long long *off)
{
	return csf_keep(k, "bytecode", hash, sizeof *hash) | csf_keep(k, "options", opts, optlen) |
	       csf_keep(k, "offset", off, sizeof *off);
}

int csf_keep_check(csf_keeper *k, const char *path, unsigned long long hash, const char *opts, size_t optlen,
                   long long *off, char *err, size_t errlen)
{
	unsigned long long h = 0;
	char *o = malloc(optlen);
	if (!o || csf_keep_header(k, &h, o, optlen, off)) {
		snprintf(err, errlen, "--resume: %s does not fit this run: %s", path, o ? csf_keep_why(k) : "out of memory");
		free(o);
		return -1;
	}
	o[optlen - 1] = '\0';
	int bad = -1;
	if (h != hash)
		snprintf(err, errlen, "--resume: %s belongs to another model: its bytecode's hash is %016llx, this one's %016llx",
		         path, h, hash);
	else if (strcmp(o, opts) != 0)
		snprintf(err, errlen, "--resume: %s was written by a run with other options: '%s', not '%s' (give the same ones)",
		         path, o, opts);
	else bad = 0;
	free(o);
	return bad;
}

int csf_keep_output(FILE *out, long long off, const char *path, char *err, size_t errlen)
{
	struct stat st;
	if (!out || off < 0 || fstat(fileno(out), &st) || !S_ISREG(st.st_mode)) return 0;
	fflush(out);
	off_t end = lseek(fileno(out), 0, SEEK_END);
	if (end == 0 && off > 0) { /* a new file (> instead of >>): the rows after the checkpoint's, as into a pipe */
		fprintf(stderr,
		        "warning: --resume: the output is empty, not the first run's %lld bytes up to the checkpoint in %s: "
		        "it gets the rows after them (append it to the first %lld bytes of the first run's output)\n",
		        off, path, off);
		return 0;
	}
	if (end < (off_t)off) {
		snprintf(err, errlen,
		         "--resume: the output has %lld bytes, fewer than the %lld of the rows up to the checkpoint in %s "
		         "(a resumed run appends to the first run's output: use >> or the same -o FILE)",
		         (long long)end, off, path);
		return -1;
	}
	if (ftruncate(fileno(out), (off_t)off) || fseeko(out, (off_t)off, SEEK_SET)) {
		snprintf(err, errlen, "--resume: cannot cut the output back to %lld bytes: %s", off, strerror(errno));
		return -1;
	}
	return 0;
}

long long csf_keep_offset(FILE *out)
{
	if (!out) return -1;
	csf_out_begin();
	int bad = fflush(out) != 0;
	csf_out_end();
	return bad ? -1 : (long long)ftello(out);
}
