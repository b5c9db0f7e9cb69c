"""Where this copy of csf finds libcsf and the programs (written by make)."""
LIBCSF = "/work/wt-when/build2/libcsf.so.1"
BINDIR = "/work/wt-when/build2"
