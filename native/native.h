/* SPDX-License-Identifier: BSD-2-Clause */
#ifndef PMD_NATIVE_H
#define PMD_NATIVE_H

/* What the harness's native loops share (record_loop.h, memory_port.h, host_port.h, system.h, abi.h). */

/* Raised whenever a function's signature changes: python/pmdfmu/native.py
 * refuses a library of another ABI (a stale build). */
#define PMD_NATIVE_ABI 6

#if defined(_WIN32)
#define PMD_NATIVE_EXPORT __declspec(dllexport)
#else
#define PMD_NATIVE_EXPORT __attribute__((visibility("default")))
#endif

#include <stddef.h>

/* An FMI function of the FMU, any signature (ISO C converts function pointers among themselves only) */
typedef void (*PmdFmiFunction)(void);

/* FMPy raises for any status above Warning (Discard, Error, Fatal, Pending): so do the loops */
#define PMD_FAILED(status) ((status) > 1)

/* Where a loop stopped early: after `done` whole rows (record_loop.h) or blocks (memory_port.h), a
 * call (the loop's own numbering) returned `status` > Warning. */
typedef struct {
    size_t done;
    int call;
    int status;
} PmdStop;

#endif
