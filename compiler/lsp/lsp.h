/*
 * lsp.h - csfc --lsp: a Language Server Protocol server on standard input
 * and output (lsp.c).
 */
#ifndef CSF_LSP_H
#define CSF_LSP_H

/* Serves until `exit` or the end of the input; csfc's exit status (0 after shutdown, else 1).
   incdirs (nincdirs of them, -I) and units (--units) apply to every document compiled. */
int lsp_main(const char *stdlib, char **incdirs, int nincdirs, int units);

#endif
