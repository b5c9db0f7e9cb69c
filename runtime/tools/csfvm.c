/*
 * csfvm - runs a compiled CSF model (.csfb) on the bytecode interpreter.
 */
#include "csf_int.h"

int main(int argc, char **argv) { return csf_main(argc, argv, NULL, 0, csf_vm_exec); }
