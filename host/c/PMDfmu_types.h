/* SPDX-License-Identifier: BSD-2-Clause */
/* C-Motion's basic types and handles, as both generations of PMD's headers define them for the
   host (pmd-reference S1 PMDtypes.h for 5.x, S3 for the Navigator's 2.x), so that a program's
   `PMDint32 value; ... (long *)&value` compiles here where it compiled there: the vendor's
   PMDint32 is a long, 64 bits on LP64 hosts. The library never assumes 4 bytes: the generated
   calls refuse a value outside the 32-bit word (PMD_ERR_ParameterOutOfRange) and widen what the
   chip returns. */
#ifndef PMD_FMU_TYPES_H
#define PMD_FMU_TYPES_H

#include <limits.h>

/* Which generation's signatures a name takes where the two differ (PMDGetSampleTime's PMDuint16*
   in 2.x, PMDuint32* in 5.x; PMDGetGearMaster's source; PMD_ERR_InvalidParameter, 0x04 in 2.x and
   0x1108 in 5.x): 2 or 5. 5 by default, the generation of most public C-Motion code (ION, Prodigy
   and C-Motion Engine programs, the Tcl and Python wrappers). docs/c-motion.md lists the names. */
#ifndef PMD_CMOTION_GENERATION
#define PMD_CMOTION_GENERATION 5
#define PMD_CMOTION_GENERATION_UNNAMED 1    /* a Get's reply pointer picks where it can (PMDcalls.h) */
#endif
#if PMD_CMOTION_GENERATION != 2 && PMD_CMOTION_GENERATION != 5
#error "PMD_CMOTION_GENERATION must be 2 (C-Motion 2.x/3.x, Navigator) or 5 (C-Motion 5.x)"
#endif

typedef unsigned char PMDuint8;
typedef signed char PMDint8;
typedef unsigned short PMDuint16;
typedef short PMDint16;
typedef unsigned long PMDuint32;
typedef long PMDint32;
typedef long PMDlong32;
/* seed 000 section 1.3's spelling of the 32-bit unsigned word */
typedef PMDuint32 PMDUINT32;
/* the 5.x peripheral calls' integer argument */
typedef PMDuint32 PMDparam;

/* A call's result: the chip's host I/O error code (PMD_ERR_OK = 0 .. 0x0F), or a host-side code
   (cmotion_errors.csv). */
typedef PMDuint16 PMDresult;

/* An axis number, PMDAxis1 (0) .. PMDAxis4 (3). */
typedef PMDuint16 PMDAxis;

/* The limits vendor examples take from their platform headers. */
#ifndef MAXINT32
#define MAXINT32 0x7FFFFFFFL
#endif
#ifndef MININT32
#define MININT32 (-MAXINT32 - 1)
#endif
#ifndef MAXUINT32
#define MAXUINT32 0xFFFFFFFFUL
#endif
#ifndef MAXINT16
#define MAXINT16 0x7FFF
#endif
#ifndef MININT16
#define MININT16 (-MAXINT16 - 1)
#endif
#ifndef MAXUINT16
#define MAXUINT16 0xFFFFU
#endif
#ifndef TRUE
#define TRUE 1
#endif
#ifndef FALSE
#define FALSE 0
#endif

/* One axis of one chip. transport_data is the connection (the FMU instance) it talks through:
   every handle of a chip shares it (PMDCopyAxisInterface, PMDAxisOpen). */
typedef struct tagPMDAxisHandle {
    PMDAxis axis;
    void *transport_data;
} PMDAxisHandle;

/* C-Motion's name for what each call takes: &hAxis[n]. */
typedef PMDAxisHandle *PMDAxisInterface;

/* C-Motion 5.x's peripheral: the link a device is reached through (what the program opened, kept
   for the device it opens). `PMDPeriphHandle hPeriph = { 0 };` is a closed one. */
typedef struct tagPMDPeriphHandle {
    int type;                   /* PMDInterfaceType; 0 (InterfaceNone) when closed */
    PMDparam address;           /* the port number, IP address, I/O address, CAN address ... */
    PMDparam parameter;         /* the baud code, TCP port ... */
    void *transport_data;       /* reserved for PMDFMU_DEVICE's links */
    PMDparam multidrop;         /* PMDPeriphOpenPeriphMultiDrop's chip address + 1; 0: the parent's */
} PMDPeriphHandle;

/* C-Motion 5.x's device: a motion processor (or a resource-protocol product around one) reached
   through a peripheral. hAxis holds the chip: its axis handles are copies of it. */
typedef struct tagPMDDeviceHandle {
    int type;                   /* PMDDeviceType; 0 (PMDDeviceTypeNone) when closed */
    PMDPeriphHandle *hPeriph;
    PMDAxisHandle hAxis;
} PMDDeviceHandle;

#endif
