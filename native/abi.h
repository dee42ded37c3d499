/* SPDX-License-Identifier: BSD-2-Clause */
/* What the harness asks the library before it uses it (python/pmdfmu/native.py): its ABI, and
 * the layout of everything it mirrors with ctypes. */
#ifndef PMD_NATIVE_ABI_H
#define PMD_NATIVE_ABI_H

#include <stddef.h>

#include "native.h"

PMD_NATIVE_EXPORT int pmd_native_abi(void);

/* The layout of every struct and enum the harness mirrors with ctypes (python/pmdfmu/native.py): their
 * sizes, their members' offsets and the enums' values, in the order abi.c lists them; writes at most
 * n and returns how many there are. The harness refuses a library whose layout is not its own. */
PMD_NATIVE_EXPORT size_t pmd_native_layout(size_t *out, size_t n);

#endif
