#ifndef PMD_NATIVE_H
#define PMD_NATIVE_H

/* Raised whenever a function's signature changes: python/pmdfmu/native.py
 * refuses a library of another ABI (a stale build). */
#define PMD_NATIVE_ABI 4

#if defined(_WIN32)
#define PMD_NATIVE_EXPORT __declspec(dllexport)
#else
#define PMD_NATIVE_EXPORT __attribute__((visibility("default")))
#endif

PMD_NATIVE_EXPORT int pmd_native_abi(void);

#endif
