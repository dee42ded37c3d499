/* The harness's native side (python/pmdfmu/native.py loads it with ctypes):
 * loops that would cost a Python call per cycle or per word, run in C over
 * the FMU's own FMI functions. Not part of any FMU: it calls an FMU only
 * through the function pointers and instance the harness hands it. */
#include "native.h"

/* The harness checks it loaded a library of its own version. */
int pmd_native_abi(void)
{
    return PMD_NATIVE_ABI;
}
